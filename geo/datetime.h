#pragma once
// An instant in time as ISO 8601 / RFC 3339 writes it: a calendar date, a time of day and the
// zone it was written in ("2015-08-18T17:58:00Z", "2026-06-21T06:45:00-06:00"). The sun's
// position needs the instant (UTC); the offset is kept so that the date and time read back the
// way the user wrote them. Calendar arithmetic is std::chrono's (proleptic Gregorian).

#include <cstdint>
#include <string>
#include <string_view>

#include "core/result.h"

namespace vegstream::geo {

struct DateTime {
  std::int64_t unixMs = 0;  // the instant: UTC milliseconds since 1970-01-01T00:00:00Z
  int offsetMinutes = 0;    // the offset from UTC it was written with (−06:00 → −360)

  bool operator==(const DateTime&) const = default;
};

// YYYY-MM-DDTHH:MM[:SS[.fraction]] followed by a zone, Z or ±HH:MM (required: a local time
// without one names no instant). 't' and 'z' may be lower case; the fraction (any number of
// digits) is rounded to the millisecond. Years 0001–9999. Rejects dates that do not exist
// (month 13, 31 April, 29 February of a common year), hour 24, minute or second 60, offsets
// beyond ±23:59 and anything after the zone. The error (ErrorKind::InvalidInput) quotes the
// text and says what is wrong with it; the caller prefixes the option or field name.
Result<DateTime> parseIsoDateTime(std::string_view text);

// The same instant in its own offset: "2026-06-21T06:45:00-06:00", "2015-08-18T17:58:00Z" for
// offset 0; seconds always, ".mmm" only when the milliseconds are not zero.
// parseIsoDateTime(formatIsoDateTime(t)) == t.
std::string formatIsoDateTime(const DateTime& t);

// t moved by `seconds` (may be negative), rounded to the millisecond; the offset is kept.
DateTime addSeconds(const DateTime& t, double seconds);

}  // namespace vegstream::geo
