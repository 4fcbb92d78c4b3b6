// A flight path's "datetime" (issue 39): when the flight starts, ISO 8601 with a zone; read,
// written back, and a bad one is one InvalidInput error naming the file, line, column and field.

#include <string>

#include <gtest/gtest.h>

#include "flight/flight_path_json.h"

namespace vegstream::flight {
namespace {

std::string withDatetime(const std::string& value) {
  return "{\n  \"name\": \"dawn\",\n  \"datetime\": " + value + R"(,
  "keyframes": [
    {"t": 0, "lat": 37.20, "lon": -112.98, "alt_m": 500, "heading": 10, "pitch": -20},
    {"t": 5, "lat": 37.21, "lon": -112.97, "alt_m": 500, "heading": 20, "pitch": -10}
  ]
})";
}

std::string errorFor(const std::string& text) {
  const Result<FlightPath> r = parseFlightPath(text, "paths/dawn.json");
  EXPECT_FALSE(r.ok()) << text;
  if (r.ok()) return "";
  EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
  EXPECT_EQ(r.error().message.find('\n'), std::string::npos) << r.error().message;
  return r.error().message;
}

TEST(FlightPathDatetime, AbsentByDefault) {
  const Result<FlightPath> r =
      parseFlightPath(R"({"keyframes": [{"t": 0, "lat": 1, "lon": 2, "alt_m": 3, "heading": 0, "pitch": 0},
                                        {"t": 1, "lat": 1, "lon": 2, "alt_m": 3, "heading": 0, "pitch": 0}]})",
                      "p.json");
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_FALSE(r->datetime.has_value());
  EXPECT_EQ(flightPathToJson(*r).find("datetime"), std::string::npos);
}

TEST(FlightPathDatetime, ReadsAndWritesIt) {
  const Result<FlightPath> r = parseFlightPath(withDatetime(R"("2026-06-21T06:45:00-06:00")"), "paths/dawn.json");
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_TRUE(r->datetime.has_value());
  EXPECT_EQ(r->datetime->unixMs, 1782045900000);  // 12:45 UTC
  EXPECT_EQ(r->datetime->offsetMinutes, -360);
  const std::string text = flightPathToJson(*r);
  EXPECT_NE(text.find(R"("datetime": "2026-06-21T06:45:00-06:00")"), std::string::npos) << text;
  const Result<FlightPath> again = parseFlightPath(text, "again.json");
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(again->datetime, r->datetime);
}

TEST(FlightPathDatetime, ABadOneNamesFileLineColumnAndField) {
  // The value sits on line 3, column 15.
  EXPECT_EQ(errorFor(withDatetime(R"("2026-13-01T00:00:00Z")")),
            "paths/dawn.json:3:15: datetime: \"2026-13-01T00:00:00Z\": month 13 does not exist (01–12)");
  EXPECT_EQ(errorFor(withDatetime(R"("2026-06-21T06:45:00")")),
            "paths/dawn.json:3:15: datetime: \"2026-06-21T06:45:00\": no zone: add Z for UTC or the offset it "
            "was written in, e.g. -06:00");
  EXPECT_EQ(errorFor(withDatetime("20260621")), "paths/dawn.json:3:15: datetime: must be a string, found a number");
  EXPECT_NE(errorFor(withDatetime(R"("tomorrow")")).find("paths/dawn.json:3:15: datetime: \"tomorrow\": not an ISO"),
            std::string::npos);
}

}  // namespace
}  // namespace vegstream::flight
