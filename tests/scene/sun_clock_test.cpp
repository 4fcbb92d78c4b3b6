// The sun over a scene (scene/sun_clock.h): where the start date-time comes from, the default
// mid-morning summer sun, and the sun moving with flight time. No GPU, no dataset.

#include "scene/sun_clock.h"

#include <cmath>

#include <gtest/gtest.h>

namespace vegstream::scene {
namespace {

const double kLat = 37.3, kLon = -113.05;  // Zion

geo::DateTime at(std::string_view iso) {
  auto t = geo::parseIsoDateTime(iso);
  EXPECT_TRUE(t.ok()) << iso;
  return t.ok() ? *t : geo::DateTime{};
}

TEST(SunClock, TheDefaultIsTenOClockMeanSolarTimeOnTheJuneSolstice2024) {
  const geo::DateTime zion = defaultDatetime(kLon);
  EXPECT_EQ(geo::formatIsoDateTime(zion), "2024-06-21T10:00:00-07:32");  // 113.05° · 4 min = 7 h 32.2 min
  EXPECT_EQ(zion.unixMs, at("2024-06-21T17:32:00Z").unixMs);
  EXPECT_EQ(geo::formatIsoDateTime(defaultDatetime(0.0)), "2024-06-21T10:00:00Z");
  EXPECT_EQ(geo::formatIsoDateTime(defaultDatetime(135.0)), "2024-06-21T10:00:00+09:00");
  // Mid-morning, summer: well up in the east-south-east at Zion.
  const geo::SolarPosition sun = geo::solarPosition(zion.unixMs, kLat, kLon);
  EXPECT_GT(sun.elevationDeg, 50.0);
  EXPECT_GT(sun.azimuthDeg, 90.0);
  EXPECT_LT(sun.azimuthDeg, 135.0);
}

TEST(SunClock, TheOptionWinsOverTheImageryTime) {
  const auto c = resolveSunClock(at("2026-06-21T06:45:00-06:00"), "2015-08-18T17:58:00Z", "d/dataset.json", kLat, kLon);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->source, DatetimeSource::Option);
  EXPECT_EQ(c->start, at("2026-06-21T06:45:00-06:00"));
  EXPECT_STREQ(toString(c->source), "option");
}

TEST(SunClock, TheImageryTimeWinsOverTheDefault) {
  const auto c = resolveSunClock(std::nullopt, "2015-08-18T17:58:00Z", "d/dataset.json", kLat, kLon);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->source, DatetimeSource::Dataset);
  EXPECT_EQ(c->start, at("2015-08-18T17:58:00Z"));
  const auto d = resolveSunClock(std::nullopt, "", "d/dataset.json", kLat, kLon);
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(d->source, DatetimeSource::Default);
  EXPECT_EQ(d->start, defaultDatetime(kLon));
  EXPECT_STREQ(toString(d->source), "default");
}

TEST(SunClock, ABadImageryTimeNamesTheFileAndField) {
  const auto c = resolveSunClock(std::nullopt, "2015-08-18 17:58", "/data/zion/dataset.json", kLat, kLon);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.error().kind, ErrorKind::InvalidInput);
  EXPECT_EQ(c.error().message,
            "'/data/zion/dataset.json': field 'imagery.datetime' \"2015-08-18 17:58\": expected 'T' between the date "
            "and the time");
}

TEST(SunClock, TheSunMovesWithFlightTime) {
  const auto c = resolveSunClock(at("2015-08-18T17:58:00Z"), "", "d/dataset.json", kLat, kLon);
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->at(90.0), at("2015-08-18T17:59:30Z"));
  const geo::SolarPosition now = c->sunAt(0.0), later = c->sunAt(3600.0);
  const geo::SolarPosition direct = geo::solarPosition(at("2015-08-18T18:58:00Z").unixMs, kLat, kLon);
  EXPECT_DOUBLE_EQ(later.azimuthDeg, direct.azimuthDeg);
  EXPECT_DOUBLE_EQ(later.elevationDeg, direct.elevationDeg);
  EXPECT_GT(later.elevationDeg, now.elevationDeg);  // the morning sun climbs
  EXPECT_GT(later.azimuthDeg, now.azimuthDeg);      // and moves west
}

}  // namespace
}  // namespace vegstream::scene
