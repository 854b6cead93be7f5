#include "io/tmy3_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/input_error.h"
#include "io/epw_reader.h"
#include "io/mesh_reader.h"  // mesh_io::for_each_line
#include "io/utf8_text.h"

namespace skyband {

namespace {

constexpr double kMissing = -9900;  // the manual's missing-value code
constexpr double kMaxRadiation_Wh_m2 = 1400, kMaxIlluminance_lux = 150000;

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// The comma-separated fields of one line, RFC 4180 style: a field may be enclosed in double quotes
// and then hold commas, with "" for a quote inside. Spaces and tabs around a field (outside its
// quotes) are trimmed. `fail` receives the 1-based field and a reason for a quote that is never
// closed or text after a closing quote, with the offset in `line` where that field starts, and does
// not return.
template <class Fail>
void split(std::string_view line, std::vector<std::string>& out, Fail&& fail) {
  out.clear();
  std::size_t i = 0;
  for (;;) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::string field;
    const std::size_t start = i;
    if (i < line.size() && line[i] == '"') {
      for (++i;; ++i) {
        if (i >= line.size()) fail(out.size() + 1, start, "the quoted field is never closed on its line");
        if (line[i] != '"') {
          field += line[i];
        } else if (i + 1 < line.size() && line[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          break;
        }
      }
      ++i;  // past the closing quote
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i < line.size() && line[i] != ',') fail(out.size() + 1, start, "text after the closing quote");
    } else {
      const std::size_t comma = std::min(line.find(',', i), line.size());
      field = std::string(trim(line.substr(i, comma - i)));
      i = comma;
    }
    out.push_back(std::move(field));
    if (i >= line.size()) return;
    ++i;  // past the comma
  }
}

std::string slurp(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw InputError(file.string() + ": no such weather file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot be read");
  std::ostringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
  return text;
}

class Tmy3Parser {
 public:
  Tmy3Parser(std::filesystem::path file, const std::string& text) : file_(std::move(file)), name_(file_.string()) {
    mesh_io::reject_nul_bytes(name_, text, "the TMY3 text");
    mesh_io::for_each_line(text, [&](std::size_t n, std::string_view l) {
      if (!trim(l).empty() || lines_.size() < 2) lines_.push_back({n, l});
    });
  }

  WeatherSeries parse() {
    if (lines_.size() < 2) throw InputError(name_ + ": a TMY3 file has a site line and a column line before its records");
    WeatherSeries s;
    s.file = file_;
    s.location = site(lines_[0]);
    columns(lines_[1]);
    if (lines_.size() == 2) throw InputError(name_ + ":3: no weather records after the two header lines");
    for (std::size_t i = 2; i < lines_.size(); ++i) s.records.push_back(record(lines_[i].first, lines_[i].second));
    const WeatherRecord &a = s.records.front(), &b = s.records.back();
    if (!(a.month == 1 && a.day == 1 && a.hour == 1) || !(b.month == 12 && b.day == 31 && b.hour == 24))
      s.warnings.push_back(name_ + ": the " + std::to_string(s.records.size()) +
                           " records are not whole calendar years (01/01 01:00 to 12/31 24:00)");
    if (const std::size_t n = unknown_source_albedo_ + zero_albedo_ + invalid_albedo_; n > 0) {
      std::string why;
      const auto add = [&](std::size_t count, const std::string& what) {
        if (count > 0) why += (why.empty() ? "" : ", ") + std::to_string(count) + " " + what;
      };
      add(unknown_source_albedo_, "with source flag '?' (no known source)");
      add(zero_albedo_, "of 0 (no ground reflects nothing; files write 0 where the albedo is unknown)");
      add(invalid_albedo_, "outside [0, 1]");
      s.warnings.push_back(name_ + ": " + std::to_string(n) + " albedo value(s) in column '" + names_[std::size_t(albedo_)] +
                           "' treated as missing: " + why + "; first on line " + std::to_string(first_missing_albedo_line_) +
                           ": the ground albedo there is --albedo or the default 0.2");
    }
    if (!daylight_) s.warnings.push_back(name_ + ": no solar radiation in any record (GHI and DHI are all zero)");
    return s;
  }

 private:
  [[noreturn]] void fail(std::size_t line, std::string_view column, std::string_view value, const std::string& why) const {
    throw InputError(name_ + ":" + std::to_string(line) + ": " + std::string(column) + " = '" + printable_text(value) +
                     "': " + why);
  }

  // The fields of line `line` into `out`; a malformed quoted field is an InputError naming the
  // file, line, field and its text.
  void split_line(std::size_t line, std::string_view text, std::vector<std::string>& out) const {
    split(text, out, [&](std::size_t field, std::size_t start, const char* why) {
      const std::string_view rest = text.substr(start);
      throw InputError(name_ + ":" + std::to_string(line) + ": field " + std::to_string(field) + " = '" +
                       printable_text(rest.substr(0, 40)) + (rest.size() > 40 ? "…" : "") + "': " + why);
    });
  }

  double number(std::size_t line, std::string_view column, std::string_view text) const {
    double v = 0;
    const char* end = text.data() + text.size();
    const char* b = text.data() + (!text.empty() && text.front() == '+' ? 1 : 0);
    const auto [p, ec] = std::from_chars(b, end, v);
    if (text.empty() || ec != std::errc() || p != end || !std::isfinite(v)) fail(line, column, text, "not a number");
    return v;
  }

  WeatherLocation site(const std::pair<std::size_t, std::string_view>& l) {
    std::vector<std::string> f;
    split_line(l.first, l.second, f);
    if (f.size() < 7)
      throw InputError(name_ + ":1: the site line has " + std::to_string(f.size()) +
                       " fields; TMY3's has 7 (USAF, name, state, time zone, latitude, longitude, elevation)");
    WeatherLocation w;
    w.station_id = std::string(f[0]);
    w.name = printable_text(f[1]);
    w.region = printable_text(f[2]);
    w.country = "USA";
    w.source = "TMY3";
    w.time_zone_hours = number(1, "time zone", f[3]);
    w.latitude_deg = number(1, "latitude", f[4]);
    w.longitude_deg = number(1, "longitude", f[5]);
    w.elevation_m = number(1, "elevation", f[6]);
    if (!(w.time_zone_hours >= -12 && w.time_zone_hours <= 14)) fail(1, "time zone", f[3], "outside -12..+14 hours");
    if (!(std::abs(w.latitude_deg) <= 90)) fail(1, "latitude", f[4], "outside -90..90 degrees");
    if (!(std::abs(w.longitude_deg) <= 180)) fail(1, "longitude", f[5], "outside -180..180 degrees");
    if (!(w.elevation_m >= -1000 && w.elevation_m < 9999.9)) fail(1, "elevation", f[6], "outside -1000..9999.9 m");
    return w;
  }

  void columns(const std::pair<std::size_t, std::string_view>& l) {
    split_line(l.first, l.second, names_);
    const auto find = [&](std::string_view name, bool required) {
      for (std::size_t i = 0; i < names_.size(); ++i)
        if (names_[i] == name) return int(i);
      if (required) throw InputError(name_ + ":2: no column '" + std::string(name) + "' (TMY3 column names, User's Manual §3)");
      return -1;
    };
    date_ = find("Date (MM/DD/YYYY)", true);
    time_ = find("Time (HH:MM)", true);
    ghi_ = find("GHI (W/m^2)", true);
    dni_ = find("DNI (W/m^2)", true);
    dhi_ = find("DHI (W/m^2)", true);
    gh_lux_ = find("GH illum (lx)", false);
    dn_lux_ = find("DN illum (lx)", false);
    dh_lux_ = find("DH illum (lx)", false);
    dew_ = find("Dew-point (C)", false);
    albedo_ = find("Alb (unitless)", false);
    albedo_source_ = find("Alb source", false);
  }

  double radiation(std::size_t line, int c) const {
    const double v = number(line, names_[std::size_t(c)], fields_[std::size_t(c)]);
    if (v <= kMissing) fail(line, names_[std::size_t(c)], fields_[std::size_t(c)], "missing; irradiance is required");
    if (v < 0) fail(line, names_[std::size_t(c)], fields_[std::size_t(c)], "negative");
    if (v > kMaxRadiation_Wh_m2) fail(line, names_[std::size_t(c)], fields_[std::size_t(c)], "above 1400 Wh/m2 in an hour");
    return v;
  }

  std::optional<double> illuminance(std::size_t line, int c) const {
    if (c < 0) return std::nullopt;
    const double v = number(line, names_[std::size_t(c)], fields_[std::size_t(c)]);
    if (v <= kMissing) return std::nullopt;
    if (v < 0 || v > kMaxIlluminance_lux) fail(line, names_[std::size_t(c)], fields_[std::size_t(c)], "outside 0..150000 lux");
    return v;
  }

  WeatherRecord record(std::size_t line, std::string_view text) {
    split_line(line, text, fields_);
    if (fields_.size() != names_.size())
      throw InputError(name_ + ":" + std::to_string(line) + ": " + std::to_string(fields_.size()) + " fields for " +
                       std::to_string(names_.size()) + " columns");
    WeatherRecord r;
    r.line = line;
    const std::string_view d = fields_[std::size_t(date_)], t = fields_[std::size_t(time_)];
    int mm = 0, dd = 0, yyyy = 0, hh = 0, mi = 0;
    if (std::sscanf(std::string(d).c_str(), "%2d/%2d/%4d", &mm, &dd, &yyyy) != 3 || d.size() != 10)
      fail(line, names_[std::size_t(date_)], d, "not a date MM/DD/YYYY");
    if (std::sscanf(std::string(t).c_str(), "%2d:%2d", &hh, &mi) != 2 || t.size() != 5)
      fail(line, names_[std::size_t(time_)], t, "not a time HH:MM");
    if (mm < 1 || mm > 12 || dd < 1 || dd > max_month_length_days(mm) || yyyy < 1)
      fail(line, names_[std::size_t(date_)], d, "no such date");
    if (hh < 1 || hh > 24 || mi != 0)
      fail(line, names_[std::size_t(time_)], t, "not an hour's end 01:00..24:00 (TMY3 records end at full hours)");
    r.year = yyyy, r.month = mm, r.day = dd, r.hour = hh, r.interval_hours = 1;
    sequence(line, r);
    r.ghi_Wh_m2 = radiation(line, ghi_);
    r.dni_Wh_m2 = radiation(line, dni_);
    r.dhi_Wh_m2 = radiation(line, dhi_);
    r.global_illuminance_lux = illuminance(line, gh_lux_);
    r.direct_illuminance_lux = illuminance(line, dn_lux_);
    r.diffuse_illuminance_lux = illuminance(line, dh_lux_);
    if (dew_ >= 0) {
      const double v = number(line, names_[std::size_t(dew_)], fields_[std::size_t(dew_)]);
      if (v > kMissing) {
        if (!(v > -70 && v < 70))
          fail(line, names_[std::size_t(dew_)], fields_[std::size_t(dew_)], "outside (-70, 70) degrees C");
        r.dew_point_C = v;
      }
    }
    if (albedo_ >= 0) {
      const double v = number(line, names_[std::size_t(albedo_)], fields_[std::size_t(albedo_)]);
      if (v > kMissing) {
        const std::size_t missing_before = unknown_source_albedo_ + zero_albedo_ + invalid_albedo_;
        if (albedo_source_ >= 0 && fields_[std::size_t(albedo_source_)] == "?")
          ++unknown_source_albedo_;  // TMY3 files write 0.00 flagged '?' where they have no albedo
        else if (v == 0)
          ++zero_albedo_;  // no ground reflects nothing: files write 0 where the albedo is unknown
        else if (v > 0 && v <= 1)
          r.albedo = v;
        else
          ++invalid_albedo_;
        if (missing_before == 0 && !r.albedo) first_missing_albedo_line_ = line;
      }
    }
    if (r.ghi_Wh_m2 > 0 || r.dhi_Wh_m2 > 0) daylight_ = true;
    return r;
  }

  // Consecutive hours: the next hour of the day, or 01:00 of the next day (after February 28,
  // February 29 or March 1; after 12/31, 01/01).
  void sequence(std::size_t line, const WeatherRecord& r) {
    if (have_previous_) {
      const WeatherRecord& p = previous_;
      bool ok = false;
      if (p.hour < 24)
        ok = r.month == p.month && r.day == p.day && r.hour == p.hour + 1;
      else if (r.hour == 1) {
        const bool month_end =
            p.day >= max_month_length_days(p.month) || (p.month == 2 && p.day == 28 && !(r.month == 2 && r.day == 29));
        ok = month_end ? r.month == p.month % 12 + 1 && r.day == 1 : r.month == p.month && r.day == p.day + 1;
      }
      if (!ok)
        fail(line, names_[std::size_t(date_)], fields_[std::size_t(date_)],
             "the record does not follow the one on line " + std::to_string(previous_line_) + " by one hour");
    }
    previous_ = r, previous_line_ = line, have_previous_ = true;
  }

  std::filesystem::path file_;
  std::string name_;
  std::vector<std::pair<std::size_t, std::string_view>> lines_;
  std::vector<std::string> names_, fields_;
  int date_ = -1, time_ = -1, ghi_ = -1, dni_ = -1, dhi_ = -1, gh_lux_ = -1, dn_lux_ = -1, dh_lux_ = -1, dew_ = -1, albedo_ = -1,
      albedo_source_ = -1;
  WeatherRecord previous_;
  std::size_t previous_line_ = 0, unknown_source_albedo_ = 0, zero_albedo_ = 0, invalid_albedo_ = 0,
              first_missing_albedo_line_ = 0;
  bool have_previous_ = false, daylight_ = false;
};

}  // namespace

WeatherSeries read_tmy3_csv(const std::filesystem::path& file) {
  const std::string text = slurp(file);
  refuse_wide_text(file.string(), text, "TMY3");
  return Tmy3Parser(file, text).parse();
}

WeatherSeries read_weather_file(const std::filesystem::path& file) {
  const std::string text = slurp(file);
  refuse_wide_text(file.string(), text, "a weather file");
  const std::size_t first_end = text.find_first_of("\r\n");
  const std::string_view first = std::string_view(text).substr(0, first_end);
  if (trim(first).rfind("LOCATION", 0) == 0) return read_epw(file);
  std::size_t second = first_end == std::string::npos ? text.size() : first_end + 1;
  if (second < text.size() && text[second - 1] == '\r' && text[second] == '\n') ++second;
  if (std::string_view(text).substr(second).rfind("Date (MM/DD/YYYY)", 0) == 0) return Tmy3Parser(file, text).parse();
  throw InputError(file.string() +
                   ": neither an EPW file (first line LOCATION,...) nor a TMY3 CSV file (second line "
                   "Date (MM/DD/YYYY),Time (HH:MM),...)");
}

}  // namespace skyband
