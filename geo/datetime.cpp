#include "geo/datetime.h"

#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>

namespace vegstream::geo {
namespace {

namespace chr = std::chrono;

constexpr std::int64_t kMsPerMinute = 60'000;
constexpr std::string_view kExpected =
    "expected YYYY-MM-DDTHH:MM:SS followed by Z or ±HH:MM, e.g. 2015-08-18T17:58:00Z";

// The text as the message quotes it: whole, or its first 40 characters.
std::string quoted(std::string_view text) {
  constexpr std::size_t kMax = 40;
  return "\"" + std::string(text.substr(0, kMax)) + (text.size() > kMax ? "…\"" : "\"");
}

Error bad(std::string_view text, std::string_view what) {
  return makeError(ErrorKind::InvalidInput, quoted(text) + ": " + std::string(what));
}

std::string twoDigits(int v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%02d", v);
  return buf;
}

// A left-to-right reader over the text.
struct Cursor {
  std::string_view s;
  std::size_t pos = 0;

  bool atEnd() const { return pos >= s.size(); }
  bool accept(char a, char b = '\0') {
    if (atEnd() || (s[pos] != a && (b == '\0' || s[pos] != b))) return false;
    ++pos;
    return true;
  }
  // Exactly n decimal digits.
  bool digits(int n, int& out) {
    if (s.size() - pos < std::size_t(n)) return false;
    int v = 0;
    for (int i = 0; i < n; ++i) {
      const char c = s[pos + std::size_t(i)];
      if (c < '0' || c > '9') return false;
      v = v * 10 + (c - '0');
    }
    pos += std::size_t(n);
    out = v;
    return true;
  }
  std::string_view rest() const { return s.substr(pos); }
};

// The day part: checked against the calendar.
Result<chr::year_month_day> readDate(Cursor& c) {
  int y = 0, m = 0, d = 0;
  if (!(c.digits(4, y) && c.accept('-') && c.digits(2, m) && c.accept('-') && c.digits(2, d))) {
    return bad(c.s, std::string("not an ISO 8601 date and time: ") + std::string(kExpected));
  }
  if (y < 1) return bad(c.s, "year 0000 does not exist here (years 0001–9999)");
  if (m < 1 || m > 12) return bad(c.s, "month " + twoDigits(m) + " does not exist (01–12)");
  const chr::year_month_day ymd{chr::year{y}, chr::month{unsigned(m)}, chr::day{unsigned(d)}};
  if (!ymd.ok()) {
    const unsigned last =
        unsigned(chr::year_month_day_last{chr::year{y}, chr::month_day_last{chr::month{unsigned(m)}}}.day());
    return bad(c.s, "day " + twoDigits(d) + " does not exist: " + std::to_string(y) + "-" + twoDigits(m) + " has " +
                        std::to_string(last) + " days");
  }
  return ymd;
}

// HH:MM[:SS[.fraction]] → milliseconds since midnight.
Result<std::int64_t> readTime(Cursor& c) {
  int h = 0, m = 0, s = 0;
  if (!(c.digits(2, h) && c.accept(':') && c.digits(2, m))) {
    return bad(c.s, "the time of day is not HH:MM:SS (" + std::string(kExpected) + ")");
  }
  if (c.accept(':') && !c.digits(2, s)) return bad(c.s, "the seconds are not two digits");
  if (h > 23) return bad(c.s, "hour " + twoDigits(h) + " does not exist (00–23)");
  if (m > 59) return bad(c.s, "minute " + twoDigits(m) + " does not exist (00–59)");
  if (s > 59) return bad(c.s, "second " + twoDigits(s) + " does not exist (00–59; leap seconds are not supported)");
  std::int64_t ms = ((std::int64_t{h} * 60 + m) * 60 + s) * 1000;
  if (c.accept('.', ',')) {
    int scale = 100, n = 0, digit = 0;
    for (; c.digits(1, digit); ++n) {
      if (scale > 0) ms += std::int64_t{digit} * scale;
      if (scale == 0 && n == 3 && digit >= 5) ms += 1;  // rounded to the millisecond
      scale /= 10;
    }
    if (n == 0) return bad(c.s, "no digits after the decimal point of the seconds");
  }
  return ms;
}

// Z or ±HH:MM → minutes east of UTC.
Result<int> readZone(Cursor& c) {
  if (c.atEnd()) return bad(c.s, "no zone: add Z for UTC or the offset it was written in, e.g. -06:00");
  if (c.accept('Z', 'z')) return 0;
  const bool east = c.accept('+');
  if (!east && !c.accept('-')) {
    return bad(c.s, "expected the zone (Z or ±HH:MM) after the time, found \"" + std::string(c.rest()) + "\"");
  }
  int h = 0, m = 0;
  if (!(c.digits(2, h) && c.accept(':') && c.digits(2, m))) return bad(c.s, "the zone offset is not ±HH:MM");
  if (h > 23 || m > 59) return bad(c.s, "offset " + twoDigits(h) + ":" + twoDigits(m) + " is beyond ±23:59");
  return (east ? 1 : -1) * (h * 60 + m);
}

}  // namespace

Result<DateTime> parseIsoDateTime(std::string_view text) {
  if (text.empty()) return bad(text, "empty; " + std::string(kExpected));
  Cursor c{text};
  const Result<chr::year_month_day> date = readDate(c);
  if (!date) return date.error();
  if (c.atEnd()) return bad(text, "no time of day and zone after the date (" + std::string(kExpected) + ")");
  if (!c.accept('T', 't')) return bad(text, "expected 'T' between the date and the time");
  const Result<std::int64_t> timeMs = readTime(c);
  if (!timeMs) return timeMs.error();
  const Result<int> offset = readZone(c);
  if (!offset) return offset.error();
  if (!c.atEnd()) return bad(text, "unexpected \"" + std::string(c.rest()) + "\" after the zone");

  const std::int64_t dayMs = std::int64_t{chr::sys_days{*date}.time_since_epoch().count()} * 86'400'000;
  return DateTime{dayMs + *timeMs - std::int64_t{*offset} * kMsPerMinute, *offset};
}

std::string formatIsoDateTime(const DateTime& t) {
  const chr::sys_time<chr::milliseconds> local{
      chr::milliseconds{t.unixMs + std::int64_t{t.offsetMinutes} * kMsPerMinute}};
  const chr::sys_days day = chr::floor<chr::days>(local);
  const chr::year_month_day ymd{day};
  const std::int64_t msOfDay = (local - day).count();
  const int sec = int(msOfDay / 1000 % 60), min = int(msOfDay / 60'000 % 60), hour = int(msOfDay / 3'600'000);
  const int ms = int(msOfDay % 1000);

  char buf[64];
  int n = std::snprintf(buf, sizeof buf, "%04d-%02u-%02uT%02d:%02d:%02d", int(ymd.year()), unsigned(ymd.month()),
                        unsigned(ymd.day()), hour, min, sec);
  if (ms != 0) n += std::snprintf(buf + n, sizeof buf - std::size_t(n), ".%03d", ms);
  if (t.offsetMinutes == 0) {
    std::snprintf(buf + n, sizeof buf - std::size_t(n), "Z");
  } else {
    const int a = std::abs(t.offsetMinutes);
    std::snprintf(buf + n, sizeof buf - std::size_t(n), "%c%02d:%02d", t.offsetMinutes > 0 ? '+' : '-', a / 60, a % 60);
  }
  return buf;
}

DateTime addSeconds(const DateTime& t, double seconds) {
  assert(std::isfinite(seconds));
  return DateTime{t.unixMs + std::llround(seconds * 1000.0), t.offsetMinutes};
}

}  // namespace vegstream::geo
