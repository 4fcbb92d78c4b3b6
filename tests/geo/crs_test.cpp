// geo::Crs through PROJ (geo/crs.h): EPSG codes, WKT and PROJJSON; names and codes as PROJ
// gives them; the CRSs the old hand-written table refused (issue 40); errors naming the text.

#include "geo/crs.h"

#include <string>

#include <gtest/gtest.h>

#include "geo/projection.h"

namespace vegstream::geo {
namespace {

TEST(Crs, Wgs84) {
  const Crs crs = wgs84Crs();
  EXPECT_EQ(crs.epsg(), 4326);
  EXPECT_EQ(crs.name(), "WGS 84 (EPSG:4326)");
  EXPECT_EQ(crs.code(), "EPSG:4326");
  EXPECT_TRUE(crs.isGeographic());
  EXPECT_TRUE(crs.isWgs84LonLat());
  EXPECT_EQ(Crs(), crs);
}

TEST(Crs, WebMercatorAndUtm) {
  EXPECT_TRUE(webMercatorCrs().isWebMercator());
  EXPECT_EQ(webMercatorCrs().name(), "WGS 84 / Pseudo-Mercator (EPSG:3857)");
  EXPECT_EQ(utmCrs(12, true).name(), "WGS 84 / UTM zone 12N (EPSG:32612)");
  EXPECT_EQ(utmCrs(33, false).epsg(), 32733);
  EXPECT_FALSE(utmCrs(12, true).isGeographic());
}

TEST(Crs, TheCrssTheOldTableRefused) {
  // British National Grid, NAD83 / UTM 12N (USGS 1 m DEMs, NAIP), Swiss LV95, ETRS89 and NZTM.
  for (int code : {27700, 26912, 2056, 4258, 2193, 4269}) {
    auto crs = Crs::fromUserInput("EPSG:" + std::to_string(code));
    ASSERT_TRUE(crs.ok()) << code << ": " << crs.error().message;
    EXPECT_EQ(crs->epsg(), code);
    EXPECT_NE(crs->name().find("(EPSG:" + std::to_string(code) + ")"), std::string::npos) << crs->name();
  }
  EXPECT_NE(Crs::fromUserInput("EPSG:27700")->name().find("British National Grid"), std::string::npos);
}

TEST(Crs, WktAndProjjsonNameTheSameCrs) {
  const Crs utm = utmCrs(12, true);
  auto fromWkt = Crs::fromWkt(utm.wkt());
  ASSERT_TRUE(fromWkt.ok()) << fromWkt.error().message;
  EXPECT_EQ(*fromWkt, utm);
  EXPECT_EQ(fromWkt->epsg(), 32612);
  auto fromJson = Crs::fromUserInput(utm.projjson());
  ASSERT_TRUE(fromJson.ok()) << fromJson.error().message;
  EXPECT_EQ(*fromJson, utm);
  EXPECT_NE(utm.projjson().find("\"type\""), std::string::npos);
  // A CRS without an EPSG code: named, no code, still usable.
  auto custom = Crs::fromUserInput("+proj=tmerc +lat_0=0 +lon_0=-111.5 +k=0.9996 +x_0=500000 +y_0=0 +ellps=GRS80 +units=m");
  ASSERT_TRUE(custom.ok()) << custom.error().message;
  EXPECT_EQ(custom->code(), "");
  EXPECT_FALSE(custom->epsg().has_value());
  EXPECT_FALSE(custom->projjson().empty());
  auto xy = toProjected(*custom, Geodetic{37.3, -111.5, 0.0});
  ASSERT_TRUE(xy.ok());
  EXPECT_NEAR(xy->x, 500000.0, 1e-3);
}

TEST(Crs, CommonSpellings) {
  EXPECT_EQ(Crs::fromUserInput("4326")->epsg(), 4326);
  EXPECT_EQ(Crs::fromUserInput("  EpSg:3857 \n")->epsg(), 3857);
  EXPECT_TRUE(Crs::fromUserInput("epsg:32612")->epsg() == 32612);
}

TEST(Crs, TextProjDoesNotKnowIsRefusedWithItsName) {
  for (const char* text : {"", "EPSG:", "not a crs", "EPSG:99999", "EPSG 4326x"}) {
    auto crs = Crs::fromUserInput(text);
    ASSERT_FALSE(crs.ok()) << text;
    EXPECT_EQ(crs.error().kind, ErrorKind::InvalidInput) << text;
    std::string quoted = "'";  // built piecewise: GCC 12 -O3 false -Wrestrict on "'" + string
    quoted.append(text).append("'");
    EXPECT_NE(crs.error().message.find(quoted), std::string::npos) << crs.error().message;
  }
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
