#include "geo/datetime.h"

#include <string>

#include <gtest/gtest.h>

namespace vegstream::geo {
namespace {

DateTime parsed(std::string_view text) {
  const Result<DateTime> r = parseIsoDateTime(text);
  EXPECT_TRUE(r.ok()) << text << ": " << (r.ok() ? "" : r.error().message);
  return r.ok() ? *r : DateTime{};
}

std::string errorOf(std::string_view text) {
  const Result<DateTime> r = parseIsoDateTime(text);
  EXPECT_FALSE(r.ok()) << text << " was accepted";
  if (r.ok()) return {};
  EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
  return r.error().message;
}

TEST(DateTime, ParsesUtcAndOffsets) {
  // date -u -d 2015-08-18T17:58:00Z +%s → 1439920680
  EXPECT_EQ(parsed("2015-08-18T17:58:00Z"), (DateTime{1439920680000, 0}));
  // 06:45 at −06:00 is 12:45 UTC: date -u -d 2026-06-21T12:45:00Z +%s → 1782045900
  EXPECT_EQ(parsed("2026-06-21T06:45:00-06:00"), (DateTime{1782045900000, -360}));
  EXPECT_EQ(parsed("2026-06-21T18:15:00+05:30"), (DateTime{1782045900000, 330}));
  EXPECT_EQ(parsed("1970-01-01T00:00:00Z").unixMs, 0);
  EXPECT_EQ(parsed("1969-12-31T23:59:59Z").unixMs, -1000);
  EXPECT_EQ(parsed("2015-08-18t17:58:00z"), parsed("2015-08-18T17:58:00Z"));
  EXPECT_EQ(parsed("2015-08-18T17:58Z"), parsed("2015-08-18T17:58:00Z"));  // seconds optional
  EXPECT_EQ(parsed("2026-06-21T06:45:00-00:00").offsetMinutes, 0);
}

TEST(DateTime, FractionalSecondsRoundToTheMillisecond) {
  EXPECT_EQ(parsed("2015-08-18T17:58:00.5Z").unixMs, 1439920680500);
  EXPECT_EQ(parsed("2015-08-18T17:58:00.123Z").unixMs, 1439920680123);
  EXPECT_EQ(parsed("2015-08-18T17:58:00,123Z").unixMs, 1439920680123);
  EXPECT_EQ(parsed("2015-08-18T17:58:00.1234Z").unixMs, 1439920680123);
  EXPECT_EQ(parsed("2015-08-18T17:58:00.1235999Z").unixMs, 1439920680124);
  EXPECT_EQ(parsed("1969-12-31T23:59:59.9996Z").unixMs, 0);
}

TEST(DateTime, LeapDaysFollowTheGregorianCalendar) {
  EXPECT_EQ(parsed("2024-02-29T00:00:00Z").unixMs, 1709164800000);
  EXPECT_EQ(parsed("2000-02-29T00:00:00Z").unixMs, 951782400000);  // divisible by 400
  EXPECT_NE(errorOf("1900-02-29T00:00:00Z").find("day 29 does not exist: 1900-02 has 28 days"), std::string::npos);
  EXPECT_NE(errorOf("2023-02-29T00:00:00Z").find("2023-02 has 28 days"), std::string::npos);
}

TEST(DateTime, RejectsWhatIsNotADateAndTime) {
  const auto says = [](std::string_view text, std::string_view what) {
    const std::string msg = errorOf(text);
    EXPECT_NE(msg.find(what), std::string::npos) << text << " → " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  };
  says("2026-13-01T00:00:00Z", "month 13 does not exist");
  says("2026-13-01", "month 13 does not exist");
  says("2026-00-10T00:00:00Z", "month 00 does not exist");
  says("2026-04-31T00:00:00Z", "day 31 does not exist: 2026-04 has 30 days");
  says("2026-01-00T00:00:00Z", "day 00 does not exist");
  says("0000-01-01T00:00:00Z", "year 0000");
  says("2026-06-21T24:00:00Z", "hour 24 does not exist");
  says("2026-06-21T12:60:00Z", "minute 60 does not exist");
  says("2026-06-21T12:00:60Z", "second 60 does not exist");
  says("2026-06-21T06:45:00", "no zone");
  says("2026-06-21", "no time of day");
  says("2026-06-21 06:45:00Z", "expected 'T'");
  says("2026-06-21T06:45:00+25:00", "beyond ±23:59");
  says("2026-06-21T06:45:00+0600", "not ±HH:MM");
  says("2026-06-21T06:45:00EST", "expected the zone");
  says("2026-06-21T06:45:00.Z", "no digits after the decimal point");
  says("2026-06-21T06:45:00Z extra", "unexpected \" extra\" after the zone");
  says("2026-06-21T6:45:00Z", "not HH:MM:SS");
  says("garbage", "\"garbage\": not an ISO 8601 date and time");
  says("nan", "not an ISO 8601 date and time");
  says("", "empty");
  says("26-06-21T06:45:00Z", "not an ISO 8601 date and time");
}

TEST(DateTime, LongGarbageIsQuotedShort) {
  const std::string msg = errorOf(std::string(500, 'x'));
  EXPECT_LT(msg.size(), 200u) << msg;
}

TEST(DateTime, FormatsInItsOwnOffset) {
  EXPECT_EQ(formatIsoDateTime(DateTime{1439920680000, 0}), "2015-08-18T17:58:00Z");
  EXPECT_EQ(formatIsoDateTime(DateTime{1782045900000, -360}), "2026-06-21T06:45:00-06:00");
  EXPECT_EQ(formatIsoDateTime(DateTime{1782045900000, 330}), "2026-06-21T18:15:00+05:30");
  EXPECT_EQ(formatIsoDateTime(DateTime{1439920680007, 0}), "2015-08-18T17:58:00.007Z");
  EXPECT_EQ(formatIsoDateTime(DateTime{-1, 0}), "1969-12-31T23:59:59.999Z");
  EXPECT_EQ(formatIsoDateTime(DateTime{0, -720}), "1969-12-31T12:00:00-12:00");  // across the date line
  EXPECT_EQ(formatIsoDateTime(DateTime{0, 840}), "1970-01-01T14:00:00+14:00");
}

TEST(DateTime, FormatThenParseIsTheSameInstant) {
  for (const char* text : {"2015-08-18T17:58:00Z", "2026-06-21T06:45:00-06:00", "2024-02-29T23:59:59.999+05:45",
                           "1900-03-01T00:00:00-09:30", "9999-12-31T23:59:59Z", "0001-01-01T00:00:00Z"}) {
    const DateTime t = parsed(text);
    EXPECT_EQ(formatIsoDateTime(t), text);
    EXPECT_EQ(parsed(formatIsoDateTime(t)), t);
  }
}

TEST(DateTime, AddSecondsMovesTheInstantAndKeepsTheOffset) {
  const DateTime t = parsed("2024-02-28T23:30:00-06:00");
  EXPECT_EQ(formatIsoDateTime(addSeconds(t, 1800.0)), "2024-02-29T00:00:00-06:00");
  EXPECT_EQ(formatIsoDateTime(addSeconds(t, 86400.0 + 1800.0)), "2024-03-01T00:00:00-06:00");
  EXPECT_EQ(formatIsoDateTime(addSeconds(t, -0.25)), "2024-02-28T23:29:59.750-06:00");
  EXPECT_EQ(addSeconds(t, 1.0 / 60.0).unixMs - t.unixMs, 17);  // 16.67 ms rounds to 17
  EXPECT_EQ(addSeconds(t, 0.0), t);
}

}  // namespace
}  // namespace vegstream::geo
