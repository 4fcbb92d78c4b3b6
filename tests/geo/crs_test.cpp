#include "geo/crs.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace vegstream::geo {
namespace {

TEST(Crs, Wgs84) {
  auto crs = crsFromEpsg(4326);
  ASSERT_TRUE(crs.ok());
  EXPECT_EQ(crs->kind, Crs::Kind::Geographic);
  EXPECT_EQ(crs->epsg, 4326);
  EXPECT_EQ(crs->name(), "WGS 84 (EPSG:4326)");
  EXPECT_EQ(crs->code(), "EPSG:4326");
}

TEST(Crs, Nad83IsWgs84WithOneWarning) {
  std::vector<std::string> warnings;
  auto crs = crsFromEpsg(4269, [&](const std::string& w) { warnings.push_back(w); });
  ASSERT_TRUE(crs.ok());
  EXPECT_EQ(crs->kind, Crs::Kind::Geographic);
  EXPECT_EQ(crs->epsg, 4269);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("EPSG:4269"), std::string::npos);
  EXPECT_NE(warnings[0].find("NAD83"), std::string::npos);
  EXPECT_NE(warnings[0].find("about 1 m"), std::string::npos);
  EXPECT_NE(warnings[0].find("sub-metre"), std::string::npos);
  // No sink: still accepted, nothing to call.
  EXPECT_TRUE(crsFromEpsg(4269).ok());
}

TEST(Crs, WebMercatorAndAliases) {
  for (int code : {3857, 900913, 3785}) {
    auto crs = crsFromEpsg(code);
    ASSERT_TRUE(crs.ok()) << code;
    EXPECT_EQ(crs->kind, Crs::Kind::WebMercator);
    EXPECT_EQ(crs->epsg, 3857);  // canonical code
  }
  EXPECT_EQ(webMercatorCrs().name(), "WGS 84 / Pseudo-Mercator (EPSG:3857)");
}

TEST(Crs, UtmZonesBothHemispheres) {
  auto n12 = crsFromEpsg(32612);
  ASSERT_TRUE(n12.ok());
  EXPECT_EQ(n12->kind, Crs::Kind::Utm);
  EXPECT_EQ(n12->utmZone, 12);
  EXPECT_TRUE(n12->north);
  EXPECT_EQ(n12->name(), "WGS 84 / UTM zone 12N (EPSG:32612)");

  auto s33 = crsFromEpsg(32733);
  ASSERT_TRUE(s33.ok());
  EXPECT_EQ(s33->utmZone, 33);
  EXPECT_FALSE(s33->north);
  EXPECT_EQ(s33->name(), "WGS 84 / UTM zone 33S (EPSG:32733)");

  EXPECT_EQ(crsFromEpsg(32601)->utmZone, 1);
  EXPECT_EQ(crsFromEpsg(32660)->utmZone, 60);
  EXPECT_EQ(crsFromEpsg(32701)->utmZone, 1);
  EXPECT_EQ(crsFromEpsg(32760)->utmZone, 60);
  EXPECT_EQ(utmCrs(33, false), *s33);
  EXPECT_EQ(utmCrs(12, true).epsg, 32612);
}

TEST(Crs, UnsupportedCodesNameTheCode) {
  // Swiss LV95, UTM zone numbers 0 / 61 and UPS are all out.
  for (int code : {2056, 32600, 32661, 32700, 32761, 27700, 4258}) {
    auto crs = crsFromEpsg(code);
    ASSERT_FALSE(crs.ok()) << code;
    EXPECT_EQ(crs.error().kind, ErrorKind::Unsupported);
    EXPECT_NE(crs.error().message.find("EPSG:" + std::to_string(code) + " is not supported"), std::string::npos)
        << crs.error().message;
    EXPECT_NE(crs.error().message.find("4326"), std::string::npos);
  }
}

TEST(Crs, ParseAcceptsCommonSpellings) {
  EXPECT_EQ(parseCrs("EPSG:4326")->epsg, 4326);
  EXPECT_EQ(parseCrs("epsg:32612")->utmZone, 12);
  EXPECT_EQ(parseCrs("4326")->kind, Crs::Kind::Geographic);
  EXPECT_EQ(parseCrs("  EpSg:3857 \n")->kind, Crs::Kind::WebMercator);
  int warnings = 0;
  EXPECT_TRUE(parseCrs("EPSG:4269", [&](const std::string&) { ++warnings; }).ok());
  EXPECT_EQ(warnings, 1);
}

TEST(Crs, ParseRejectsTextWithItsName) {
  for (const char* text :
       {"", "EPSG:", "WGS84", "EPSG:43a26", "EPSG:-4326", "4326.0", "EPSG:99999999999", "EPSG 4326"}) {
    auto crs = parseCrs(text);
    ASSERT_FALSE(crs.ok()) << text;
    EXPECT_EQ(crs.error().kind, ErrorKind::InvalidInput) << text;
    std::string quoted = "'";  // built piecewise: GCC 12 -O3 false -Wrestrict on "'" + string
    quoted.append(text).append("'");
    EXPECT_NE(crs.error().message.find(quoted), std::string::npos) << crs.error().message;
  }
  auto unsupported = parseCrs("EPSG:2056");
  ASSERT_FALSE(unsupported.ok());
  EXPECT_EQ(unsupported.error().kind, ErrorKind::Unsupported);
  EXPECT_NE(unsupported.error().message.find("EPSG:2056"), std::string::npos);
}

TEST(Crs, StandardUtmZone) {
  EXPECT_EQ(standardUtmZone(37.3, -113.05), 12);  // Zion
  EXPECT_EQ(standardUtmZone(-22.5, 17.1), 33);    // Namibia
  EXPECT_EQ(standardUtmZone(60.0, 5.0), 32);      // Norway exception (would be 31)
  EXPECT_EQ(standardUtmZone(78.0, 20.0), 33);     // Svalbard exception (would be 34)
  EXPECT_EQ(standardUtmZone(89.0, 20.0), 33);     // beyond 84°N: still a UTM zone
  EXPECT_EQ(standardUtmZone(-85.0, -177.0), 1);
}

}  // namespace
}  // namespace vegstream::geo
