// EPW reader (epw_reader.h). Field numbers, names, missing codes and valid ranges follow the
// EnergyPlus "Auxiliary Programs" EPW data dictionary (weather converter program chapter).
#include "io/epw_reader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/input_error.h"
#include "io/utf8_text.h"

namespace skyband {
namespace {

constexpr int kHeaderLines = 8;
constexpr int kRecordFields = 35;
constexpr int kOldRecordFields = 32;  // older files end after field 32 (present weather codes)

// Names of the 35 record fields, 1-based (index 0 unused), as the data dictionary calls them.
constexpr std::array<const char*, kRecordFields + 1> kFieldNames = {"",
                                                                    "year",
                                                                    "month",
                                                                    "day",
                                                                    "hour",
                                                                    "minute",
                                                                    "data source and uncertainty flags",
                                                                    "dry bulb temperature",
                                                                    "dew point temperature",
                                                                    "relative humidity",
                                                                    "atmospheric station pressure",
                                                                    "extraterrestrial horizontal radiation",
                                                                    "extraterrestrial direct normal radiation",
                                                                    "horizontal infrared radiation intensity",
                                                                    "global horizontal radiation",
                                                                    "direct normal radiation",
                                                                    "diffuse horizontal radiation",
                                                                    "global horizontal illuminance",
                                                                    "direct normal illuminance",
                                                                    "diffuse horizontal illuminance",
                                                                    "zenith luminance",
                                                                    "wind direction",
                                                                    "wind speed",
                                                                    "total sky cover",
                                                                    "opaque sky cover",
                                                                    "visibility",
                                                                    "ceiling height",
                                                                    "present weather observation",
                                                                    "present weather codes",
                                                                    "precipitable water",
                                                                    "aerosol optical depth",
                                                                    "snow depth",
                                                                    "days since last snowfall",
                                                                    "albedo",
                                                                    "liquid precipitation depth",
                                                                    "liquid precipitation quantity"};

// 1-based record fields read here.
enum Field : int {
  kYear = 1,
  kMonth = 2,
  kDay = 3,
  kHour = 4,
  kMinute = 5,
  kDewPoint = 8,
  kGlobalRadiation = 14,
  kDirectRadiation = 15,
  kDiffuseRadiation = 16,
  kGlobalIlluminance = 17,
  kDirectIlluminance = 18,
  kDiffuseIlluminance = 19,
  kAlbedo = 33
};

// Missing-data codes: a value ≥ the code is missing (data dictionary, \missing).
constexpr double kMissingRadiation_Wh_m2 = 9999;
constexpr double kMissingIlluminance_lux = 999900;  // the code is 999999, "missing if ≥ 999900"
constexpr double kMissingDewPoint_C = 99.9;
constexpr double kMissingAlbedo = 999;

// Largest plausible hourly radiation (Wh/m² = mean W/m² over the hour). Above the atmosphere
// the sun gives 1361 W/m² at 1 AU (Kopp & Lean 2011) and 1361/0.9833² ≈ 1408 W/m² at perihelion;
// at the ground an hourly mean stays well below that (cloud enhancement lasts minutes), so 1400
// only rejects corrupt values.
constexpr double kMaxRadiation_Wh_m2 = 1400;
// Largest plausible illuminance: the extraterrestrial solar illuminance is 133.3 klx at 1 AU
// (Darula, Kittler & Gueymard 2005, Solar Energy 79:559) and ≈138 klx at perihelion.
constexpr double kMaxIlluminance_lux = 150000;
// Dew point: the data dictionary's valid range is −70 < T < 70 °C.
constexpr double kMinDewPoint_C = -70, kMaxDewPoint_C = 70;

// "Many" diffuse-above-global records: a handful occur where the two come from different
// instruments or models and round differently; a systematic excess means swapped columns or a
// broken model. Warn when at least this share of the daylight records (and at least 3) have a
// diffuse more than 5 % (and at least 2 Wh/m², beyond the rounding of two integers) above global.
constexpr double kDiffuseExcessRatio = 1.05;
constexpr double kDiffuseExcessMin_Wh_m2 = 2;
constexpr double kDiffuseExcessShare = 0.01;

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

// The text shown for a bad line or value: at most 40 characters.
// At most 40 bytes of a field for a message, printable (a NUL would cut the message short).
std::string excerpt(std::string_view s) {
  return s.size() <= 40 ? printable_text(s) : printable_text(s.substr(0, 40)) + "…";
}

std::string two_digits(int v) {
  char b[16];
  std::snprintf(b, sizeof b, "%02d", v);
  return b;
}

std::string format_g(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

// Lines of the file without their line ends (LF, CR LF or lone CR) and without a leading BOM.
std::vector<std::string_view> split_lines(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\n' && text[i] != '\r') continue;
    lines.push_back(text.substr(start, i - start));
    if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
    start = i + 1;
  }
  if (start < text.size()) lines.push_back(text.substr(start));
  return lines;
}

// Comma-separated fields of a line (no quoting in EPW records and the headers read here).
std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  for (;;) {
    const auto comma = line.find(',', start);
    fields.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

std::optional<double> parse_double(std::string_view s) {
  s = trim(s);
  if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<int> parse_int(std::string_view s) {
  s = trim(s);
  if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
  int v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

bool keyword_is(std::string_view field, std::string_view keyword) {
  field = trim(field);
  return field.size() == keyword.size() && std::equal(field.begin(), field.end(), keyword.begin(), [](char a, char b) {
           return std::toupper(static_cast<unsigned char>(a)) == b;
         });
}

struct Slot {
  int month = 0, day = 0, hour = 0;
  bool operator==(const Slot&) const = default;
};

std::string describe(const Slot& s) {
  return two_digits(s.month) + "-" + two_digits(s.day) + " hour " + std::to_string(s.hour);
}

// The hours that may follow `s`: the next hour, or hour 1 of the next day; after February 28
// both February 29 (leap-year files) and March 1.
std::vector<Slot> successors(const Slot& s) {
  if (s.hour < 24) return {{s.month, s.day, s.hour + 1}};
  const Slot next_month{s.month % 12 + 1, 1, 1};
  if (s.month == 2 && s.day == 28) return {{2, 29, 1}, next_month};
  if (s.day >= max_month_length_days(s.month)) return {next_month};
  return {{s.month, s.day + 1, 1}};
}

class EpwParser {
 public:
  EpwParser(std::filesystem::path file, std::string_view text)
      : file_(std::move(file)), name_(file_.string()), lines_(split_lines(text)) {}

  WeatherSeries parse() {
    while (!lines_.empty() && trim(lines_.back()).empty()) lines_.pop_back();
    if (lines_.size() < static_cast<std::size_t>(kHeaderLines))
      throw InputError(name_ + ":" + std::to_string(lines_.size() + 1) + ": the file ends after " +
                       std::to_string(lines_.size()) + " line(s); an EPW file has " + std::to_string(kHeaderLines) +
                       " header lines (LOCATION … DATA PERIODS) before its hourly records");
    WeatherSeries series;
    series.file = file_;
    series.location = parse_location();
    check_data_periods();
    if (lines_.size() == static_cast<std::size_t>(kHeaderLines))
      throw InputError(name_ + ":" + std::to_string(kHeaderLines + 1) + ": no weather records after the " +
                       std::to_string(kHeaderLines) + " header lines");
    series.records.reserve(lines_.size() - kHeaderLines);
    for (std::size_t i = kHeaderLines; i < lines_.size(); ++i) series.records.push_back(parse_record(i + 1, lines_[i]));
    add_warnings(series);
    return series;
  }

 private:
  [[noreturn]] void header_fail(std::size_t line, const char* header, int field, const char* field_name, std::string_view value,
                                const std::string& why) const {
    throw InputError(name_ + ":" + std::to_string(line) + ": " + header + " field " + std::to_string(field) + " (" + field_name +
                     ") = '" + excerpt(trim(value)) + "': " + why);
  }

  WeatherLocation parse_location() {
    const auto fields = split_fields(lines_[0]);
    if (!keyword_is(fields[0], "LOCATION"))
      throw InputError(name_ + ":1: the first line must be the LOCATION header of an EPW file; found '" + excerpt(lines_[0]) +
                       "'");
    // fields[0] is the keyword; LOCATION field k is fields[k].
    std::size_t count = fields.size();
    while (count > 10 && trim(fields[count - 1]).empty()) --count;  // trailing commas
    if (count < 10)
      throw InputError(name_ + ":1: the LOCATION header has " + std::to_string(count - 1) +
                       " fields; 9 expected (city, state/province, country, source, WMO, latitude, longitude, "
                       "time zone, elevation)");
    if (count > 10)  // some writers append a field (a climate zone): the nine named ones are read
      location_extra_ = "the LOCATION header has " + std::to_string(count - 1) + " fields; the 9 named ones are read and '" +
                        excerpt(trim(fields[10])) + "'" + (count > 11 ? " and what follows" : "") + " ignored";
    const auto number = [&](int k, const char* what, double lo, double hi, bool hi_open, const char* range) {
      const auto v = parse_double(fields[static_cast<std::size_t>(k)]);
      if (!v) header_fail(1, "LOCATION", k, what, fields[static_cast<std::size_t>(k)], "not a finite number");
      if (!(*v >= lo && (hi_open ? *v < hi : *v <= hi)))
        header_fail(1, "LOCATION", k, what, fields[static_cast<std::size_t>(k)], std::string("outside ") + range);
      return *v;
    };
    WeatherLocation loc;
    loc.name = std::string(trim(fields[1]));
    loc.region = std::string(trim(fields[2]));
    loc.country = std::string(trim(fields[3]));
    loc.source = std::string(trim(fields[4]));
    loc.station_id = std::string(trim(fields[5]));
    loc.latitude_deg = number(6, "latitude", -90, 90, false, "[-90, 90] degrees (north positive)");
    loc.longitude_deg = number(7, "longitude", -180, 180, false, "[-180, 180] degrees (east positive)");
    loc.time_zone_hours = number(8, "time zone", -12, 14, false, "[-12, +14] hours from UTC (east positive)");
    loc.elevation_m = number(9, "elevation", -1000, 9999.9, true, "[-1000, 9999.9) m");
    return loc;
  }

  void check_data_periods() const {
    const std::size_t line = kHeaderLines;
    const auto fields = split_fields(lines_[line - 1]);
    if (!keyword_is(fields[0], "DATA PERIODS"))
      throw InputError(name_ + ":" + std::to_string(line) +
                       ": line 8 must be the DATA PERIODS header (an EPW file has 8 header lines); found '" +
                       excerpt(lines_[line - 1]) + "'");
    const std::string_view per_hour = fields.size() > 2 ? fields[2] : std::string_view();
    const auto n = parse_int(per_hour);
    if (!n || *n != 1)
      header_fail(line, "DATA PERIODS", 2, "records per hour", per_hour, "only hourly files (1 record per hour) are supported");
  }

  [[noreturn]] void fail(std::size_t line, int field, std::string_view value, const std::string& why) const {
    throw InputError(name_ + ":" + std::to_string(line) + ": field " + std::to_string(field) + " (" +
                     kFieldNames[static_cast<std::size_t>(field)] + ") = '" + excerpt(trim(value)) + "': " + why);
  }

  double number(std::size_t line, int field) const {
    const std::string_view text = fields_[static_cast<std::size_t>(field) - 1];
    const auto v = parse_double(text);
    if (!v) fail(line, field, text, "not a finite number");
    return *v;
  }

  int integer(std::size_t line, int field, int lo, int hi, const std::string& range) const {
    const std::string_view text = fields_[static_cast<std::size_t>(field) - 1];
    const auto v = parse_int(text);
    if (!v) fail(line, field, text, "not an integer");
    if (*v < lo || *v > hi) fail(line, field, text, range);
    return *v;
  }

  double radiation(std::size_t line, int field) const {
    const double v = number(line, field);
    const std::string_view text = fields_[static_cast<std::size_t>(field) - 1];
    if (v >= kMissingRadiation_Wh_m2)
      fail(line, field, text, "the missing-data code (>= 9999); every radiation value is needed, so fill the gap before use");
    if (v < 0) fail(line, field, text, "negative; radiation must be >= 0 Wh/m2");
    if (v > kMaxRadiation_Wh_m2)
      fail(line, field, text, "above 1400 Wh/m2, more than the sun delivers in an hour even above the atmosphere");
    return v;
  }

  std::optional<double> illuminance(std::size_t line, int field) const {
    const double v = number(line, field);
    const std::string_view text = fields_[static_cast<std::size_t>(field) - 1];
    if (v >= kMissingIlluminance_lux) return std::nullopt;
    if (v < 0) fail(line, field, text, "negative; illuminance must be >= 0 lux");
    if (v > kMaxIlluminance_lux)
      fail(line, field, text, "above 150000 lux, more than the sun's illuminance above the atmosphere (about 133000 lux)");
    return v;
  }

  WeatherRecord parse_record(std::size_t line, std::string_view text) {
    if (trim(text).empty()) throw InputError(name_ + ":" + std::to_string(line) + ": empty line between the weather records");
    fields_ = split_fields(text);
    // Empty fields after field 35 (a trailing comma, as spreadsheet exports write): dropped, and
    // counted for one warning. A value there is refused: it may mean a field inserted or shifted.
    if (fields_.size() > static_cast<std::size_t>(kRecordFields) &&
        std::all_of(fields_.begin() + kRecordFields, fields_.end(), [](std::string_view f) { return trim(f).empty(); })) {
      if (trailing_empty_records_++ == 0)
        first_trailing_empty_ = "line " + std::to_string(line) + ": " + std::to_string(fields_.size()) + " fields";
      fields_.resize(kRecordFields);
    }
    if (fields_.size() < static_cast<std::size_t>(kOldRecordFields) || fields_.size() > static_cast<std::size_t>(kRecordFields))
      throw InputError(name_ + ":" + std::to_string(line) + ": the record has " + std::to_string(fields_.size()) +
                       " fields; an EPW record has " + std::to_string(kRecordFields) +
                       " (year, month, day, hour, minute, … liquid precipitation quantity), or " +
                       std::to_string(kOldRecordFields) + " in older files (without albedo and precipitation)");
    if (fields_.size() < static_cast<std::size_t>(kAlbedo) && short_records_++ == 0)
      first_short_record_ = "line " + std::to_string(line) + ": " + std::to_string(fields_.size()) + " fields";
    WeatherRecord r;
    r.line = line;
    r.interval_hours = 1;
    r.year = integer(line, kYear, 1, 9999, "outside 1..9999");
    r.month = integer(line, kMonth, 1, 12, "outside 1..12");
    r.day = integer(
        line, kDay, 1, max_month_length_days(r.month),
        "month " + std::to_string(r.month) + " has no such day (1.." + std::to_string(max_month_length_days(r.month)) + ")");
    r.hour = integer(line, kHour, 1, 24, "outside 1..24 (hour h covers (h-1, h]: hour 1 is 00:00-01:00)");
    integer(line, kMinute, 0, 60, "outside 0..60");
    check_sequence(line, r);

    const double dew = number(line, kDewPoint);
    if (dew < kMissingDewPoint_C) {
      if (!(dew > kMinDewPoint_C && dew < kMaxDewPoint_C))
        fail(line, kDewPoint, fields_[kDewPoint - 1], "outside (-70, 70) degrees C");
      r.dew_point_C = dew;
    }
    r.ghi_Wh_m2 = radiation(line, kGlobalRadiation);
    r.dni_Wh_m2 = radiation(line, kDirectRadiation);
    r.dhi_Wh_m2 = radiation(line, kDiffuseRadiation);
    r.global_illuminance_lux = illuminance(line, kGlobalIlluminance);
    r.direct_illuminance_lux = illuminance(line, kDirectIlluminance);
    r.diffuse_illuminance_lux = illuminance(line, kDiffuseIlluminance);
    const double albedo = fields_.size() >= static_cast<std::size_t>(kAlbedo) ? number(line, kAlbedo) : kMissingAlbedo;
    if (albedo < kMissingAlbedo) {
      if (albedo > 0 && albedo <= 1) {
        r.albedo = albedo;
      } else if (albedo == 0) {
        ++zero_albedo_;  // no ground reflects nothing: files write 0 where the albedo is unknown
      } else if (invalid_albedo_++ == 0) {
        first_invalid_albedo_ = "line " + std::to_string(line) + ": '" + excerpt(trim(fields_[kAlbedo - 1])) + "'";
      }
    }

    // Statistics for the warnings.
    if (r.ghi_Wh_m2 > 0 || r.dhi_Wh_m2 > 0) ++daylight_;
    if (r.dhi_Wh_m2 > kDiffuseExcessRatio * r.ghi_Wh_m2 && r.dhi_Wh_m2 - r.ghi_Wh_m2 >= kDiffuseExcessMin_Wh_m2 &&
        diffuse_excess_++ == 0)
      first_diffuse_excess_ =
          "line " + std::to_string(line) + ": global " + format_g(r.ghi_Wh_m2) + ", diffuse " + format_g(r.dhi_Wh_m2) + " Wh/m2";
    if (r.month == 2 && r.day == 29 && r.hour == 1 && !is_leap_year(r.year) && false_leap_days_++ == 0)
      first_false_leap_day_ = "line " + std::to_string(line) + ", year " + std::to_string(r.year);
    return r;
  }

  void check_sequence(std::size_t line, const WeatherRecord& r) {
    const Slot here{r.month, r.day, r.hour};
    if (previous_line_ != 0) {
      const auto allowed = successors(previous_);
      if (std::find(allowed.begin(), allowed.end(), here) == allowed.end()) {
        // Name the first field that departs from the expected hour (of the same month, if one is).
        Slot expected = allowed.front();
        for (const auto& a : allowed)
          if (a.month == here.month) expected = a;
        const int field = here.month != expected.month ? kMonth : here.day != expected.day ? kDay : kHour;
        std::string expect = describe(allowed.front());
        for (std::size_t k = 1; k < allowed.size(); ++k) expect += " or " + describe(allowed[k]);
        fail(line, field, fields_[static_cast<std::size_t>(field) - 1],
             describe(here) + " does not follow " + describe(previous_) + " on line " + std::to_string(previous_line_) +
                 "; records must be consecutive hours (expected " + expect + ")");
      }
    } else {
      first_ = here;
    }
    previous_ = here;
    previous_line_ = line;
  }

  void add_warnings(WeatherSeries& series) const {
    auto& w = series.warnings;
    const std::size_t n = series.records.size();
    if (!(first_ == Slot{1, 1, 1}) || !(previous_ == Slot{12, 31, 24}))
      w.push_back(name_ + ": the " + std::to_string(n) + " records run from " + describe(first_) + " to " + describe(previous_) +
                  ", not whole calendar years (01-01 hour 1 to 12-31 hour 24)");
    if (false_leap_days_ > 0)
      w.push_back(name_ + ": " + std::to_string(false_leap_days_) + " February 29 record day(s) in years that are not " +
                  "leap years (first on " + first_false_leap_day_ + ")");
    if (diffuse_excess_ >= 3 && static_cast<double>(diffuse_excess_) >= kDiffuseExcessShare * static_cast<double>(daylight_))
      w.push_back(name_ + ": diffuse horizontal radiation exceeds global horizontal by more than 5 % in " +
                  std::to_string(diffuse_excess_) + " of " + std::to_string(daylight_) + " daylight records (first on " +
                  first_diffuse_excess_ + "); global includes diffuse, so fields 14 and 16 may be swapped or wrong");
    if (!location_extra_.empty()) w.push_back(name_ + ":1: " + location_extra_);
    if (trailing_empty_records_ > 0)
      w.push_back(name_ + ": " + std::to_string(trailing_empty_records_) +
                  " record(s) with empty fields after field 35 (a trailing comma), ignored (first on " + first_trailing_empty_ +
                  ")");
    if (short_records_ > 0)
      w.push_back(name_ + ": " + std::to_string(short_records_) + " record(s) without fields 33-35 (albedo, precipitation), " +
                  "as in older EPW files (first on " + first_short_record_ + "); the ground albedo there is --albedo or " +
                  "the default 0.2");
    if (invalid_albedo_ > 0)
      w.push_back(name_ + ": " + std::to_string(invalid_albedo_) +
                  " albedo value(s) (field 33) outside [0, 1] treated as missing (first on " + first_invalid_albedo_ + ")");
    if (zero_albedo_ > 0)
      w.push_back(name_ + ": " + std::to_string(zero_albedo_) + " albedo value(s) (field 33) of 0 treated as missing " +
                  "(no ground reflects nothing; files write 0 where the albedo is unknown): the ground albedo there is " +
                  "--albedo or the default 0.2");
    if (daylight_ == 0) w.push_back(name_ + ": no solar radiation in any record (fields 14 and 16 are all zero)");
  }

  std::filesystem::path file_;
  std::string name_;
  std::vector<std::string_view> lines_;
  std::vector<std::string_view> fields_;  // of the record being parsed

  Slot first_, previous_;
  std::size_t previous_line_ = 0;
  std::size_t daylight_ = 0;
  std::size_t diffuse_excess_ = 0, invalid_albedo_ = 0, zero_albedo_ = 0, false_leap_days_ = 0, short_records_ = 0;
  std::size_t trailing_empty_records_ = 0;
  std::string first_diffuse_excess_, first_invalid_albedo_, first_false_leap_day_, first_short_record_, location_extra_;
  std::string first_trailing_empty_;
};

}  // namespace

WeatherSeries read_epw(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("cannot open weather file '" + file.string() + "'");
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError("cannot read weather file '" + file.string() + "'");
  refuse_wide_text(file.string(), bytes, "EPW");
  return EpwParser(file, bytes).parse();
}

}  // namespace skyband
