#pragma once
// Moments for sums over time, so that nobody writes a times file by hand: every `step` minutes
// through whole local days in a time zone, each moment at the middle of its step (so a step's
// sun stands for the whole step) and weighted by the step's length in hours.
//
// Time zones: an IANA name (Europe/Amsterdam, America/Chicago) through Howard Hinnant's date/tz
// library on the system's tz database (Debian tzdata), daylight saving time included; or a fixed
// offset from UTC in hours. The days run from local midnight of the first date to local midnight
// after the last one; the steps are taken in UTC between those two instants, so a day with a
// daylight-saving change has 23 or 25 hours of moments, as it has in reality.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lighting/sun/sun_position.h"

namespace skyband {

struct MomentSeriesSpec {
  std::string first_date, last_date;  // YYYY-MM-DD, inclusive; last ≥ first
  double step_minutes = 10;           // (0, 1440], dividing nothing in particular
  std::string zone;                   // IANA name, or empty for utc_offset_hours
  std::optional<double> utc_offset_hours;
};

struct TimedMoment {
  LocalDateTime time;  // local civil time with its UTC offset at that instant (DST applied)
  double hours = 0;    // the step's length
};

// Throws InputError naming the flag (`--date`, `--step`, `--zone`, `--tz`) and the value for an
// unparsable or impossible date, a last date before the first, a step outside (0, 1440] minutes,
// an unknown zone name, both or neither of zone and offset, or more than 10⁶ moments.
std::vector<TimedMoment> moment_series(const MomentSeriesSpec& spec);

// "YYYY-MM-DD" or "YYYY-MM-DD:YYYY-MM-DD" → (first, last) (the same date twice for one day).
std::pair<std::string, std::string> parse_date_range(std::string_view text, std::string_view flag);

}  // namespace skyband
