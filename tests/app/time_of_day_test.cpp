// The window's time of day without a window (issue 39): the keys step the date-time the sun's
// clock starts at (time_of_day.h), the HUD's slider sets the local time of day and nothing else,
// and the HUD's sun line says when and where the sun is.

#include <cmath>

#include <gtest/gtest.h>

#include "app/hud.h"
#include "app/imgui_overlay.h"
#include "app/time_of_day.h"

namespace vegstream::app {
namespace {

geo::DateTime at(std::string_view iso) {
  auto t = geo::parseIsoDateTime(iso);
  EXPECT_TRUE(t.ok()) << iso;
  return t.ok() ? *t : geo::DateTime{};
}

TEST(TimeOfDay, KeysStepHalfAnHourOrThreeHoursAcrossMidnight) {
  const geo::DateTime t = at("2024-06-21T23:45:00-06:00");
  EXPECT_EQ(geo::formatIsoDateTime(stepTime(t, {1, false})), "2024-06-22T00:15:00-06:00");
  EXPECT_EQ(geo::formatIsoDateTime(stepTime(t, {-2, false})), "2024-06-21T22:45:00-06:00");
  EXPECT_EQ(geo::formatIsoDateTime(stepTime(t, {1, true})), "2024-06-22T02:45:00-06:00");
  EXPECT_EQ(stepTime(t, {0, true}), t);
  EXPECT_FALSE(TimeKeys{}.any());
  EXPECT_TRUE((TimeKeys{-1, false}.any()));
}

TEST(TimeOfDay, LocalHoursAreInTheDateTimesOwnOffset) {
  EXPECT_DOUBLE_EQ(localHours(at("2024-06-21T06:45:00-06:00")), 6.75);
  EXPECT_DOUBLE_EQ(localHours(at("2024-06-21T12:45:00Z")), 12.75);  // the same instant in UTC
  EXPECT_DOUBLE_EQ(localHours(at("1969-12-31T18:00:00Z")), 18.0);   // before 1970 too
  EXPECT_DOUBLE_EQ(localHours(at("2024-06-21T00:00:00+05:30")), 0.0);
}

TEST(TimeOfDay, SettingTheHoursKeepsTheLocalDate) {
  const geo::DateTime t = at("2024-06-21T06:45:00-06:00");
  EXPECT_EQ(geo::formatIsoDateTime(atLocalHours(t, 18.5)), "2024-06-21T18:30:00-06:00");
  EXPECT_EQ(geo::formatIsoDateTime(atLocalHours(t, 0.0)), "2024-06-21T00:00:00-06:00");
  EXPECT_EQ(geo::formatIsoDateTime(atLocalHours(t, 24.0)), "2024-06-21T23:59:00-06:00");  // the slider's end
  EXPECT_EQ(geo::formatIsoDateTime(atLocalHours(t, -3.0)), "2024-06-21T00:00:00-06:00");
  EXPECT_EQ(atLocalHours(t, 18.5).offsetMinutes, -360);
  EXPECT_DOUBLE_EQ(localHours(atLocalHours(t, 9.25)), 9.25);
}

TEST(TimeOfDay, HudLineSaysWhenAndWhereTheSunIs) {
  geo::SolarPosition sun;
  sun.azimuthDeg = 109.2;
  sun.elevationDeg = 60.42;
  EXPECT_EQ(describeSun(at("2024-06-21T10:00:00-07:32"), sun), "2024-06-21 10:00 -07:32, sun 109° (E), 60.4° up");
  sun.azimuthDeg = 300.0;
  sun.elevationDeg = -4.0;
  EXPECT_EQ(describeSun(at("2024-06-21T21:30:00Z"), sun), "2024-06-21 21:30 Z, sun 300° (NW), 4.0° below");
}

// The slider: clicks over the whole HUD find it; every edit is a time of day in [0, 24] and
// leaves the wind alone; hovering changes nothing.
TEST(TimeOfDay, HudSliderSetsTheTimeOfDay) {
  ImGuiOverlay overlay;
  HudState s;
  s.datasetName = "test";
  s.deviceName = "llvmpipe";
  s.sun = "2024-06-21 10:00 -07:32, sun 109° (E), 60.4° up";
  s.timeOfDayH = 10.0;
  auto frame = [&](const OverlayPointer& p) {
    overlay.begin(1280.0f, 1000.0f, 1.0 / 60.0, p);
    const HudEdits e = drawHud(s);
    overlay.end();
    return e;
  };
  frame({});
  frame({});  // ImGui sizes auto-resizing windows on the second frame
  bool found = false;
  for (float y = 0.0f; y < 1000.0f; y += 4.0f)
    for (float x = 20.0f; x < 200.0f; x += 40.0f) {
      EXPECT_FALSE(frame({true, x, y, false}).timeOfDayH);
      const HudEdits e = frame({true, x, y, true});
      frame({true, x, y, false});
      if (!e.timeOfDayH) continue;
      EXPECT_FALSE(e.wind) << x << ", " << y;
      EXPECT_GE(*e.timeOfDayH, 0.0);
      EXPECT_LE(*e.timeOfDayH, 24.0);
      found |= *e.timeOfDayH != 10.0;
    }
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace vegstream::app
