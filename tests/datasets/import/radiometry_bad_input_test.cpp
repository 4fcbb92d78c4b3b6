// Bad radiometry, de-shading and datetime options to `vegstream import`, through the real
// executable: exit 2, one line naming the option, nothing left at or beside --out.

#include <gtest/gtest.h>

#include "import_test_util.h"

namespace vegstream::datasets {
namespace {
using namespace vegstream::datasets::test;

const std::string kZ = samples() + "/zion/";
const std::string kZion = "--dem " + kZ + "srtm.tif --imagery-bands " + kZ + "landsat_b4.tif," + kZ +
                          "landsat_b3.tif," + kZ + "landsat_b2.tif ";

struct Case {
  const char* name;
  const char* args;
  const char* names;  // what the message must name
  const char* what;   // and say
};

class RadiometryBadInput : public ::testing::TestWithParam<Case> {};

TEST_P(RadiometryBadInput, IsRefusedWithOneLineNamingTheOption) {
  const Case& c = GetParam();
  expectRefused(runImportIn(std::string("bad_") + c.name, kZion + c.args), c.names, c.what);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, RadiometryBadInput,
    ::testing::Values(
        Case{"method", "--radiometry albedo", "--radiometry 'albedo'", "expected auto, reflectance, srgb or stretch"},
        Case{"scale_nan", "--reflectance-scale nan", "--reflectance-scale 'nan'", "finite number"},
        Case{"scale_text", "--reflectance-scale 2e-5x", "--reflectance-scale '2e-5x'", "finite number"},
        Case{"scale_negative", "--reflectance-scale -1", "--reflectance-scale '-1'", "above 0"},
        Case{"offset_inf", "--reflectance-offset inf", "--reflectance-offset 'inf'", "finite number"},
        Case{"datetime_month", "--imagery-datetime 2026-13-01T00:00:00Z", "--imagery-datetime", "2026-13-01"},
        Case{"datetime_zone", "--imagery-datetime 2015-08-18T17:58:00", "--imagery-datetime", "2015-08-18T17:58:00"},
        Case{"sun", "--imagery-sun 400,10", "--imagery-sun '400,10'", "AZIMUTH,ELEVATION"},
        Case{"deshading", "--deshading maybe", "--deshading 'maybe'", "expected on or off"},
        Case{"srgb_16bit", "--radiometry srgb", "--radiometry srgb", "landsat_b4.tif"},
        Case{"stretch_and_reflectance", "--radiometry reflectance --stretch p1,p99", "--stretch",
             "--radiometry reflectance"}),
    [](const ::testing::TestParamInfo<Case>& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace vegstream::datasets
