#define BOOST_TEST_MODULE epw_reader
#include <boost/test/unit_test.hpp>

#include <unistd.h>
#include <array>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geometry/core/input_error.h"
#include "io/epw_reader.h"
#include "lighting/climate/weather_series.h"
#include "shared_data.h"

using namespace skyband;
namespace fs = std::filesystem;
namespace tt = boost::test_tools;

namespace {

const fs::path kWeather = fs::path(SKYBAND_SHARED_DATA) / "weather";
const fs::path kChicago = kWeather / "USA_IL_Chicago-OHare.725300_TMY3.epw";
const fs::path kHeino = kWeather / "NLD_OV_Heino.062780_TMYx.2007-2021.epw";
const fs::path kCloncurry = kWeather / "AUS_QLD_Cloncurry.AP.943350_TMYx.epw";

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("skyband_epw_reader_test_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

// A synthetic EPW file: the 8 header lines and hourly records of 35 fields, each editable.
using Fields = std::array<std::string, 35>;

struct EpwText {
  std::vector<std::string> header = {"LOCATION,Testville,ST,XYZ,synthetic,012345,40.0,-105.0,-7.0,1600.0",
                                     "DESIGN CONDITIONS,0",
                                     "TYPICAL/EXTREME PERIODS,0",
                                     "GROUND TEMPERATURES,0",
                                     "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0",
                                     "COMMENTS 1,synthetic test file",
                                     "COMMENTS 2,",
                                     "DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31"};
  std::vector<Fields> records;
  std::string eol = "\n";

  // Field k (1-based) of record i.
  std::string& field(std::size_t i, int k) { return records.at(i)[static_cast<std::size_t>(k - 1)]; }

  std::string text() const {
    std::string s;
    for (const auto& h : header) s += h + eol;
    for (const auto& r : records) {
      for (std::size_t k = 0; k < r.size(); ++k) s += (k ? "," : "") + r[k];
      s += eol;
    }
    return s;
  }
};

// One record with the other fields as in a real TMYx record (Heino, line 9), radiation zero.
Fields record(int year, int month, int day, int hour) {
  return {std::to_string(year),
          std::to_string(month),
          std::to_string(day),
          std::to_string(hour),
          "0",
          "?9?9?9?9E0?9?9?9?9*9?9?9?9?9?9?9*9?9*9*9?9*9",
          "2.80",
          "0.90",
          "87",
          "101280",
          "0",
          "0",
          "229",
          "0",
          "0",
          "0",
          "0",
          "0",
          "0",
          "0",
          "220",
          "4.00",
          "7",
          "9",
          "777.7",
          "77777",
          "9",
          "999999999",
          "11",
          "0.0850",
          "0",
          "88",
          "0.140",
          "0.0",
          "0.0"};
}

// `hours` consecutive hourly records from (year, month, day) hour 1, the year advancing at the
// new year; February has 29 days in leap years.
void add_hours(EpwText& e, int year, int month, int day, int hours) {
  int hour = 1;
  for (int i = 0; i < hours; ++i) {
    e.records.push_back(record(year, month, day, hour));
    if (++hour > 24) {
      hour = 1;
      if (++day > month_length_days(year, month)) {
        day = 1;
        if (++month > 12) {
          month = 1;
          ++year;
        }
      }
    }
  }
}

fs::path write(const TempDir& d, const std::string& name, const std::string& text) {
  const fs::path p = d.path / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

std::string error_of(const fs::path& p) {
  try {
    read_epw(p);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// Two days of records with a sunny noon, the base of the error cases (lines 9..56).
EpwText two_days() {
  EpwText e;
  add_hours(e, 2019, 6, 1, 48);
  e.field(12, 14) = "800";  // 06-01 hour 13, line 21
  e.field(12, 15) = "700";
  e.field(12, 16) = "150";
  return e;
}

double annual_sum_kWh_m2(const WeatherSeries& s, double WeatherRecord::*field) {
  double sum = 0;
  for (const auto& r : s.records) sum += r.*field;
  return sum / 1000.0;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The shared real files.

BOOST_AUTO_TEST_CASE(shared_files_read_with_their_locations_and_annual_sums, *skyband::test::needs_shared_data()) {
  struct Expected {
    fs::path file;
    const char* name;
    const char* region;
    const char* country;
    const char* source;
    const char* station;
    double latitude_deg, longitude_deg, time_zone_hours, elevation_m;
    double ghi_kWh_m2, dni_kWh_m2, dhi_kWh_m2;
  };
  // Location: each file's LOCATION line. Annual sums: the README of shared/data/weather, which
  // gives the sums of the files' columns 14/15/16 in kWh/m² to 0.1 — so the tolerance is half of
  // that last digit.
  const Expected files[] = {
      {kChicago, "Chicago Ohare Intl Ap", "IL", "USA", "TMY3", "725300", 41.98, -87.92, -6.0, 201.0, 1406.6, 1294.3, 660.3},
      {kHeino, "Heino", "OV", "NLD", "SRC-TMYx", "062780", 52.4344, 6.2589, 1.0, 3.6, 1088.4, 1221.2, 460.1},
      {kCloncurry, "Cloncurry.AP", "QLD", "AUS", "SRC-TMYx", "943350", -20.6664, 140.505, 10.0, 187.0, 2232.5, 2693.0, 458.1},
  };
  for (const auto& f : files) {
    BOOST_TEST_CONTEXT(f.file.filename().string()) {
      const auto start = std::chrono::steady_clock::now();
      const WeatherSeries s = read_epw(f.file);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      BOOST_TEST_MESSAGE(f.file.filename().string() << ": read in " << ms << " ms");
      // Typical years of 365 days × 24 hours (the files have 8 + 8760 lines).
      BOOST_TEST(s.records.size() == 8760u);
      BOOST_TEST(s.location.name == f.name);
      BOOST_TEST(s.location.region == f.region);
      BOOST_TEST(s.location.country == f.country);
      BOOST_TEST(s.location.source == f.source);
      BOOST_TEST(s.location.station_id == f.station);
      // The file's decimal text parsed correctly rounded, as the literal is.
      BOOST_TEST(s.location.latitude_deg == f.latitude_deg);
      BOOST_TEST(s.location.longitude_deg == f.longitude_deg);
      BOOST_TEST(s.location.time_zone_hours == f.time_zone_hours);
      BOOST_TEST(s.location.elevation_m == f.elevation_m);
      BOOST_TEST(annual_sum_kWh_m2(s, &WeatherRecord::ghi_Wh_m2) == f.ghi_kWh_m2, tt::tolerance(0.05 / f.ghi_kWh_m2));
      BOOST_TEST(annual_sum_kWh_m2(s, &WeatherRecord::dni_Wh_m2) == f.dni_kWh_m2, tt::tolerance(0.05 / f.dni_kWh_m2));
      BOOST_TEST(annual_sum_kWh_m2(s, &WeatherRecord::dhi_Wh_m2) == f.dhi_kWh_m2, tt::tolerance(0.05 / f.dhi_kWh_m2));
      // Whole calendar years, diffuse never above global: nothing to warn about in the file alone.
      BOOST_TEST(s.warnings.empty());
      BOOST_TEST(s.records.front().line == 9u);
      BOOST_TEST((s.records.front().month == 1 && s.records.front().day == 1 && s.records.front().hour == 1));
      BOOST_TEST((s.records.back().month == 12 && s.records.back().day == 31 && s.records.back().hour == 24));
      for (const auto& r : s.records) BOOST_TEST_REQUIRE(r.interval_hours == 1.0);
    }
  }
}

BOOST_AUTO_TEST_CASE(chicago_records_hold_the_fields_of_their_lines, *skyband::test::needs_shared_data()) {
  const WeatherSeries s = read_epw(kChicago);
  // Line 9: "1986,1,1,1,0,…,-12.2,-16.1,73,…,999.000,999.0,99.0" — dew point −16.1, albedo 999 (missing).
  const WeatherRecord& first = s.records.front();
  BOOST_TEST(first.year == 1986);
  BOOST_TEST(*first.dew_point_C == -16.1);
  BOOST_TEST(!first.albedo.has_value());
  // Line 4125: "1979,6,21,13,0,…,30.6,13.3,35,99000,1240,1322,405,895,734,205,96600,75500,25700,…,999.000,…"
  // (index 4125 − 9 = 4116 = (31+28+31+30+31+20)·24 + 12).
  const WeatherRecord& r = s.records.at(4116);
  BOOST_TEST(r.line == 4125u);
  BOOST_TEST((r.year == 1979 && r.month == 6 && r.day == 21 && r.hour == 13));
  BOOST_TEST(r.mid_hour() == 12.5);  // hour 13 covers 12:00–13:00
  BOOST_TEST(*r.dew_point_C == 13.3);
  BOOST_TEST(r.ghi_Wh_m2 == 895.0);
  BOOST_TEST(r.dni_Wh_m2 == 734.0);
  BOOST_TEST(r.dhi_Wh_m2 == 205.0);
  BOOST_TEST(*r.global_illuminance_lux == 96600.0);
  BOOST_TEST(*r.direct_illuminance_lux == 75500.0);
  BOOST_TEST(*r.diffuse_illuminance_lux == 25700.0);
  BOOST_TEST(!r.albedo.has_value());
  // Heino line 9 ends "…,0.140,0.0,0.0": albedo 0.14, dew point 0.90.
  const WeatherSeries h = read_epw(kHeino);
  BOOST_TEST(*h.records.front().albedo == 0.14);
  BOOST_TEST(*h.records.front().dew_point_C == 0.9);
}

// ---------------------------------------------------------------------------------------------
// Synthetic files: accepted variants.

BOOST_AUTO_TEST_CASE(crlf_bom_and_trailing_empty_lines_are_accepted) {
  TempDir d;
  EpwText e = two_days();
  e.eol = "\r\n";
  e.field(12, 14) = "123.5";
  const fs::path p = write(d, "crlf.epw", "\xEF\xBB\xBF" + e.text() + "\r\n\r\n");
  const WeatherSeries s = read_epw(p);
  BOOST_TEST(s.records.size() == 48u);
  BOOST_TEST(s.location.name == "Testville");
  BOOST_TEST(s.location.latitude_deg == 40.0);
  BOOST_TEST(s.records[12].ghi_Wh_m2 == 123.5);
  BOOST_TEST(s.records[12].line == 21u);
  // Two days are not a calendar year: one warning saying so, naming the file and the span.
  BOOST_REQUIRE_EQUAL(s.warnings.size(), 1u);
  BOOST_TEST(contains(s.warnings[0], p.string()));
  BOOST_TEST(contains(s.warnings[0], "06-01 hour 1 to 06-02 hour 24"));
  // The same file with LF line ends and lone CR line ends reads the same.
  e.eol = "\n";
  BOOST_TEST(read_epw(write(d, "lf.epw", e.text())).records[12].ghi_Wh_m2 == 123.5);
  e.eol = "\r";
  BOOST_TEST(read_epw(write(d, "cr.epw", e.text())).records.size() == 48u);
}

BOOST_AUTO_TEST_CASE(leap_year_file_has_february_29_and_8784_records) {
  TempDir d;
  EpwText e;
  add_hours(e, 2020, 1, 1, 8784);  // 366 days × 24 h
  e.field(12, 14) = "300";         // some radiation (a file without any is warned about)
  const WeatherSeries s = read_epw(write(d, "leap.epw", e.text()));
  BOOST_TEST(s.records.size() == 8784u);
  // Record (31 + 28)·24 = 1416 is February 29, hour 1.
  BOOST_TEST((s.records[1416].month == 2 && s.records[1416].day == 29 && s.records[1416].hour == 1));
  BOOST_TEST((s.records.back().month == 12 && s.records.back().day == 31));
  BOOST_TEST(s.warnings.empty());  // 2020 is a leap year; a whole calendar year

  // A common year goes from February 28 straight to March 1: 8760 records.
  EpwText c;
  add_hours(c, 2019, 1, 1, 8760);
  c.field(12, 14) = "300";
  const WeatherSeries cs = read_epw(write(d, "common.epw", c.text()));
  BOOST_TEST(cs.records.size() == 8760u);
  BOOST_TEST((cs.records[1416].month == 3 && cs.records[1416].day == 1));
  BOOST_TEST(cs.warnings.empty());
  // The same year without any radiation: a warning.
  c.field(12, 14) = "0";
  const WeatherSeries dark = read_epw(write(d, "dark.epw", c.text()));
  BOOST_REQUIRE_EQUAL(dark.warnings.size(), 1u);
  BOOST_TEST(contains(dark.warnings[0], "no solar radiation"), dark.warnings[0]);

  // February 29 labelled with a common year reads, with a warning.
  EpwText w;
  add_hours(w, 2020, 2, 28, 72);
  for (auto& r : w.records) r[0] = "1986";
  const WeatherSeries ws = read_epw(write(d, "false_leap.epw", w.text()));
  BOOST_TEST(ws.records.size() == 72u);
  bool warned = false;
  for (const auto& m : ws.warnings) warned |= contains(m, "February 29") && contains(m, "year 1986");
  BOOST_TEST(warned);
}

BOOST_AUTO_TEST_CASE(years_may_change_between_records_and_wrap_at_new_year) {
  TempDir d;
  EpwText e;
  add_hours(e, 1999, 12, 31, 48);                                                    // 12-31 of 1999, then 01-01 of 2000
  for (int i = 24; i < 48; ++i) e.records[static_cast<std::size_t>(i)][0] = "1977";  // a typical year's months
  const WeatherSeries s = read_epw(write(d, "wrap.epw", e.text()));
  BOOST_TEST(s.records.size() == 48u);
  BOOST_TEST((s.records[23].year == 1999 && s.records[24].year == 1977 && s.records[24].month == 1));
}

BOOST_AUTO_TEST_CASE(missing_codes_of_optional_fields_become_missing) {
  TempDir d;
  EpwText e = two_days();
  e.field(12, 17) = "999999";  // illuminance missing code (data dictionary: missing if >= 999900)
  e.field(12, 18) = "999900";
  e.field(12, 19) = "25000";
  e.field(12, 8) = "99.9";  // dew point missing code
  e.field(12, 33) = "999";  // albedo missing code
  e.field(13, 33) = "1.5";  // albedo outside [0, 1]: invalid, treated as missing with a warning
  e.field(14, 33) = "0.25";
  e.field(15, 33) = "0.000";  // albedo 0: unknown (IWEC files write it in every record), missing with a warning
  e.field(14, 8) = "-12.5";
  const fs::path p = write(d, "missing.epw", e.text());
  const WeatherSeries s = read_epw(p);
  BOOST_TEST(!s.records[12].global_illuminance_lux.has_value());
  BOOST_TEST(!s.records[12].direct_illuminance_lux.has_value());
  BOOST_TEST(*s.records[12].diffuse_illuminance_lux == 25000.0);
  BOOST_TEST(!s.records[12].dew_point_C.has_value());
  BOOST_TEST(!s.records[12].albedo.has_value());
  BOOST_TEST(!s.records[13].albedo.has_value());
  BOOST_TEST(*s.records[14].albedo == 0.25);
  BOOST_TEST(*s.records[14].dew_point_C == -12.5);
  BOOST_TEST(!s.records[15].albedo.has_value());
  BOOST_TEST(*s.records[0].global_illuminance_lux == 0.0);  // present zero, not missing
  bool warned = false;
  for (const auto& m : s.warnings) warned |= contains(m, p.string()) && contains(m, "albedo") && contains(m, "line 22");
  BOOST_TEST(warned);
  bool zero_warned = false;
  for (const auto& m : s.warnings) zero_warned |= contains(m, p.string()) && contains(m, "1 albedo value(s) (field 33) of 0");
  BOOST_TEST(zero_warned);
}

// The file's text with every record cut to its first `fields` fields, and `suffix` appended to the
// first `suffixed` records.
std::string edited_text(const EpwText& e, std::size_t fields, std::size_t suffixed = 0, const std::string& suffix = "") {
  std::string text;
  for (const auto& h : e.header) text += h + "\n";
  for (std::size_t i = 0; i < e.records.size(); ++i) {
    for (std::size_t k = 0; k < fields; ++k) text += (k ? "," : "") + e.records[i][k];
    text += (i < suffixed ? suffix : "") + "\n";
  }
  return text;
}

BOOST_AUTO_TEST_CASE(older_records_of_32_fields_are_read_without_albedo) {
  // EPW files of older converters end each record after field 32 (present weather codes); the
  // EnergyPlus data dictionary's fields 33-35 (albedo, precipitation) are then absent.
  TempDir d;
  EpwText e = two_days();
  e.field(3, 14) = "120", e.field(3, 15) = "300", e.field(3, 16) = "80";
  const fs::path p = write(d, "old32.epw", edited_text(e, 32));
  const WeatherSeries s = read_epw(p);
  BOOST_TEST(s.records.size() == e.records.size());
  BOOST_TEST(s.records[3].ghi_Wh_m2 == 120.0);
  BOOST_TEST(s.records[3].dni_Wh_m2 == 300.0);
  BOOST_TEST(!s.records[3].albedo.has_value());
  bool warned = false;
  for (const auto& m : s.warnings)
    warned |= contains(m, p.string()) && contains(m, "48 record(s) without fields 33-35") && contains(m, "line 9: 32 fields");
  BOOST_TEST(warned);
}

BOOST_AUTO_TEST_CASE(records_ending_in_a_comma_are_read_with_a_warning) {
  // Spreadsheet exports end each line with a separator: an empty 36th field (or more), dropped;
  // the values are those of the same file without it.
  TempDir d;
  EpwText e = two_days();
  e.field(3, 14) = "120", e.field(3, 15) = "300", e.field(3, 16) = "80";
  const fs::path p = write(d, "comma.epw", edited_text(e, 35, 5, ","));
  const WeatherSeries s = read_epw(p);
  const WeatherSeries plain = read_epw(write(d, "plain.epw", e.text()));
  BOOST_TEST(s.records.size() == plain.records.size());
  BOOST_TEST(s.records[3].ghi_Wh_m2 == 120.0);
  BOOST_TEST(s.records[3].dni_Wh_m2 == 300.0);
  BOOST_TEST((s.records[3].albedo == plain.records[3].albedo));
  bool warned = false;
  for (const auto& m : s.warnings)
    warned |= contains(m, p.string()) && contains(m, "5 record(s) with empty fields after field 35") &&
              contains(m, "line 9: 36 fields");
  BOOST_TEST(warned);
}

BOOST_AUTO_TEST_CASE(a_location_line_with_an_extra_field_reads_the_nine_named_ones) {
  // Some writers append a climate zone to LOCATION (e.g. "...,-8.0,30.0,Csb").
  TempDir d;
  EpwText e = two_days();
  e.header[0] += ",Csb";
  const fs::path p = write(d, "extra.epw", e.text());
  const WeatherSeries s = read_epw(p);
  BOOST_TEST(s.location.latitude_deg == 40.0);
  BOOST_TEST(s.location.elevation_m == 1600.0);
  bool warned = false;
  for (const auto& m : s.warnings) warned |= contains(m, p.string() + ":1:") && contains(m, "'Csb' ignored");
  BOOST_TEST(warned);
}

BOOST_AUTO_TEST_CASE(diffuse_above_global_in_many_records_is_a_warning) {
  TempDir d;
  EpwText e = two_days();
  // Ten daylight hours on 06-02 with diffuse 300 above global 200 (50 % over): a file whose
  // columns 14 and 16 look swapped.
  for (std::size_t i = 30; i < 40; ++i) {
    e.field(i, 14) = "200";
    e.field(i, 16) = "300";
  }
  const fs::path p = write(d, "swapped.epw", e.text());
  const WeatherSeries s = read_epw(p);
  bool warned = false;
  for (const auto& m : s.warnings) warned |= contains(m, p.string()) && contains(m, "10 of 11 daylight records");
  BOOST_TEST(warned);

  // Diffuse 4 % above global stays within the 5 % margin: no such warning.
  for (std::size_t i = 30; i < 40; ++i) e.field(i, 16) = "208";
  for (const auto& m : read_epw(write(d, "close.epw", e.text())).warnings) BOOST_TEST(!contains(m, "diffuse"));
}

// ---------------------------------------------------------------------------------------------
// Synthetic files: errors. Each names file:line, the field by number and name, and the value.

BOOST_AUTO_TEST_CASE(errors_name_file_line_field_and_value) {
  TempDir d;
  struct Case {
    const char* what;
    int record;  // index of the record to edit (line = record + 9), −1: header line 1
    int field;   // 1-based field to set
    const char* value;
    std::vector<std::string> expected;  // parts of the message besides the file name
  };
  const std::vector<Case> cases = {
      {"non-numeric", 12, 15, "abc", {":21: field 15 (direct normal radiation) = 'abc'", "not a finite number"}},
      {"not a number", 12, 14, "nan", {":21: field 14 (global horizontal radiation) = 'nan'", "not a finite number"}},
      {"infinite", 12, 16, "inf", {":21: field 16 (diffuse horizontal radiation) = 'inf'", "not a finite number"}},
      {"trailing text", 12, 14, "80x", {":21: field 14 (global horizontal radiation) = '80x'"}},
      {"negative global", 12, 14, "-5", {":21: field 14 (global horizontal radiation) = '-5'", "negative"}},
      {"diffuse too large", 12, 16, "1500", {":21: field 16 (diffuse horizontal radiation) = '1500'", "1400"}},
      {"direct too large", 12, 15, "1401", {":21: field 15 (direct normal radiation) = '1401'", "1400"}},
      {"global missing", 12, 14, "9999", {":21: field 14 (global horizontal radiation) = '9999'", "missing"}},
      {"direct missing", 3, 15, "9999", {":12: field 15 (direct normal radiation) = '9999'", "missing"}},
      {"negative illuminance", 12, 17, "-1", {":21: field 17 (global horizontal illuminance) = '-1'", "negative"}},
      {"illuminance too large", 12, 18, "200000", {":21: field 18 (direct normal illuminance) = '200000'"}},
      {"dew point out of range", 5, 8, "75", {":14: field 8 (dew point temperature) = '75'", "(-70, 70)"}},
      {"month 13", 0, 2, "13", {":9: field 2 (month) = '13'", "1..12"}},
      {"month 0", 0, 2, "0", {":9: field 2 (month) = '0'"}},
      {"June 31", 0, 3, "31", {":9: field 3 (day) = '31'", "month 6 has no such day"}},
      {"hour 25", 0, 4, "25", {":9: field 4 (hour) = '25'", "1..24"}},
      {"hour 0", 0, 4, "0", {":9: field 4 (hour) = '0'", "1..24"}},
      {"fractional hour", 0, 4, "1.5", {":9: field 4 (hour) = '1.5'", "not an integer"}},
      {"minute 61", 0, 5, "61", {":9: field 5 (minute) = '61'"}},
      {"hour skipped",
       6,
       4,
       "8",
       {":15: field 4 (hour) = '8'", "06-01 hour 8 does not follow 06-01 hour 6 on line 14", "expected 06-01 hour 7"}},
      {"hour repeated", 6, 4, "6", {":15: field 4 (hour) = '6'", "does not follow 06-01 hour 6"}},
      {"day skipped", 24, 3, "3", {":33: field 3 (day) = '3'", "does not follow 06-01 hour 24", "expected 06-02 hour 1"}},
      {"month jumps", 24, 2, "7", {":33: field 2 (month) = '7'", "does not follow 06-01 hour 24"}},
      {"latitude", -1, 6, "95", {":1: LOCATION field 6 (latitude) = '95'", "[-90, 90]"}},
      {"longitude", -1, 7, "-181", {":1: LOCATION field 7 (longitude) = '-181'", "[-180, 180]"}},
      {"time zone east", -1, 8, "15", {":1: LOCATION field 8 (time zone) = '15'", "[-12, +14]"}},
      {"time zone west", -1, 8, "-12.5", {":1: LOCATION field 8 (time zone) = '-12.5'"}},
      {"latitude text", -1, 6, "north", {":1: LOCATION field 6 (latitude) = 'north'", "not a finite number"}},
      {"elevation", -1, 9, "12000", {":1: LOCATION field 9 (elevation) = '12000'"}},
  };
  int n = 0;
  for (const auto& c : cases) {
    BOOST_TEST_CONTEXT(c.what) {
      EpwText e = two_days();
      if (c.record >= 0) {
        e.field(static_cast<std::size_t>(c.record), c.field) = c.value;
      } else {
        std::array<std::string, 10> loc = {"LOCATION", "Testville", "ST",     "XYZ",  "synthetic",
                                           "012345",   "40.0",      "-105.0", "-7.0", "1600.0"};
        loc[static_cast<std::size_t>(c.field)] = c.value;
        e.header[0].clear();
        for (std::size_t k = 0; k < loc.size(); ++k) e.header[0] += (k ? "," : "") + loc[k];
      }
      const fs::path p = write(d, "case" + std::to_string(n++) + ".epw", e.text());
      const std::string m = error_of(p);
      BOOST_TEST_MESSAGE(m);
      BOOST_TEST(contains(m, p.string() + ":"), m);
      for (const auto& part : c.expected) BOOST_TEST(contains(m, part), "'" << m << "' lacks '" << part << "'");
      BOOST_TEST(m.find('\n') == std::string::npos);  // one line
    }
  }

  // Time zones at the ends of the accepted range (UTC−12, UTC+14: Line Islands) are fine.
  for (const char* zone : {"-12", "+14", "5.75"}) {
    EpwText e = two_days();
    e.header[0] = std::string("LOCATION,Edge,,KIR,synthetic,0,1.9,-157.4,") + zone + ",2";
    BOOST_TEST(read_epw(write(d, "zone.epw", e.text())).records.size() == 48u);
  }
}

BOOST_AUTO_TEST_CASE(structural_errors_name_file_and_line) {
  TempDir d;
  const auto check = [&](const std::string& name, const std::string& text, const std::vector<std::string>& parts) {
    BOOST_TEST_CONTEXT(name) {
      const fs::path p = write(d, name, text);
      const std::string m = error_of(p);
      BOOST_TEST_MESSAGE(m);
      BOOST_TEST(contains(m, p.string() + ":"), m);
      for (const auto& part : parts) BOOST_TEST(contains(m, part), "'" << m << "' lacks '" << part << "'");
    }
  };
  EpwText e = two_days();
  const std::string full = e.text();

  // Short header: only 5 lines.
  EpwText shorter = e;
  shorter.header.resize(5);
  shorter.records.clear();
  check("short.epw", shorter.text(), {":6:", "ends after 5 line(s)", "8 header lines"});
  check("empty.epw", "", {":1:", "ends after 0 line(s)"});

  // No LOCATION line first.
  EpwText no_location = e;
  no_location.header[0] = "PLACE,Testville,ST,XYZ,synthetic,012345,40.0,-105.0,-7.0,1600.0";
  check("nolocation.epw", no_location.text(), {":1:", "LOCATION", "'PLACE,Testville"});

  // A header line short: the 8th line is then a record, not DATA PERIODS.
  EpwText seven = e;
  seven.header.erase(seven.header.begin() + 6);
  check("seven.epw", seven.text(), {":8:", "DATA PERIODS"});

  // Sub-hourly data periods are not read.
  EpwText sub = e;
  sub.header[7] = "DATA PERIODS,1,4,Data,Sunday, 1/ 1,12/31";
  check("subhourly.epw", sub.text(), {":8: DATA PERIODS field 2 (records per hour) = '4'"});

  // Header only.
  EpwText none = e;
  none.records.clear();
  check("norecords.epw", none.text(), {":9:", "no weather records"});

  // 31 and 36 fields (32 to 35 are read: older files end after field 32).
  std::string line31;
  {
    const Fields r = record(2019, 6, 1, 4);
    for (std::size_t k = 0; k < 31; ++k) line31 += (k ? "," : "") + r[k];
  }
  std::string text31 = full;
  const std::string line12 = [&] {
    std::string s;
    const Fields r = record(2019, 6, 1, 4);
    for (std::size_t k = 0; k < r.size(); ++k) s += (k ? "," : "") + r[k];
    return s;
  }();
  text31.replace(text31.find(line12), line12.size(), line31);
  check("fields31.epw", text31, {":12:", "has 31 fields", "35", "32 in older files"});
  std::string text36 = full;
  text36.replace(text36.find(line12), line12.size(), line12 + ",1");
  check("fields36.epw", text36, {":12:", "has 36 fields"});
  std::string text37 = full;
  text37.replace(text37.find(line12), line12.size(), line12 + ", ,2");
  check("fields37.epw", text37, {":12:", "has 37 fields"});

  // An empty line between records (empty lines at the end are fine, see above).
  std::string gap = full;
  gap.insert(gap.find(line12), "\n");
  check("gap.epw", gap, {":12:", "empty line"});

  // A file that does not exist.
  BOOST_TEST(contains(error_of(d.path / "absent.epw"), "cannot open weather file"));
}

// ---------------------------------------------------------------------------------------------
// Period selection.

BOOST_AUTO_TEST_CASE(month_day_parsing_accepts_dates_and_rejects_impossible_ones) {
  const MonthDay a = parse_month_day("12-01", "--from");
  BOOST_TEST((a.month == 12 && a.day == 1));
  const MonthDay b = parse_month_day("2-29", "--to");
  BOOST_TEST((b.month == 2 && b.day == 29));
  for (const char* bad : {"02-30", "13-01", "00-10", "04-31", "06-00", "12", "ab-cd", "12-1x", "-1-05", "", "123-01", "1-2-3"}) {
    BOOST_TEST_CONTEXT(bad) {
      std::string m;
      try {
        parse_month_day(bad, "--from");
      } catch (const InputError& e) {
        m = e.what();
      }
      BOOST_TEST(contains(m, std::string("--from '") + bad + "'"), m);
    }
  }
  BOOST_CHECK_THROW(select_period(WeatherSeries{}, MonthDay{2, 30}, MonthDay{3, 1}), InputError);
  BOOST_CHECK_THROW(select_period(WeatherSeries{}, MonthDay{1, 1}, MonthDay{0, 1}), InputError);
}

BOOST_AUTO_TEST_CASE(in_period_is_inclusive_and_wraps_over_new_year) {
  BOOST_TEST(in_period({3, 1}, {3, 1}, {3, 1}));
  BOOST_TEST(in_period({3, 31}, {3, 1}, {3, 31}));
  BOOST_TEST(!in_period({4, 1}, {3, 1}, {3, 31}));
  BOOST_TEST(!in_period({2, 28}, {3, 1}, {3, 31}));
  BOOST_TEST(in_period({12, 1}, {12, 1}, {2, 28}));
  BOOST_TEST(in_period({1, 15}, {12, 1}, {2, 28}));
  BOOST_TEST(in_period({2, 28}, {12, 1}, {2, 28}));
  BOOST_TEST(!in_period({2, 29}, {12, 1}, {2, 28}));
  BOOST_TEST(!in_period({11, 30}, {12, 1}, {2, 28}));
}

BOOST_AUTO_TEST_CASE(select_period_keeps_the_days_of_the_period_in_file_order, *skyband::test::needs_shared_data()) {
  const WeatherSeries s = read_epw(kChicago);
  // Winter, wrapping over the new year: December 31 + January 31 + February 28 days.
  const WeatherSeries winter = select_period(s, parse_month_day("12-01", "--from"), parse_month_day("02-28", "--to"));
  BOOST_TEST(winter.records.size() == (31u + 31u + 28u) * 24u);
  BOOST_TEST(winter.location.name == s.location.name);
  BOOST_TEST(winter.file == s.file);
  BOOST_TEST((winter.records.front().month == 1 && winter.records.front().day == 1 && winter.records.front().hour == 1));
  BOOST_TEST((winter.records.back().month == 12 && winter.records.back().day == 31 && winter.records.back().hour == 24));
  for (const auto& r : winter.records) BOOST_TEST_REQUIRE((r.month == 12 || r.month <= 2));
  // One day, a whole year, and February 29 in a common year (nothing).
  BOOST_TEST(select_period(s, {3, 1}, {3, 1}).records.size() == 24u);
  BOOST_TEST(select_period(s, {1, 1}, {12, 31}).records.size() == 8760u);
  BOOST_TEST(select_period(s, {2, 29}, {2, 29}).records.empty());
  // The selected June equals the June of the file: its records 3624 … 4343 ((31+28+31+30+31)·24 = 3624).
  const WeatherSeries june = select_period(s, {6, 1}, {6, 30});
  BOOST_REQUIRE_EQUAL(june.records.size(), 720u);
  BOOST_TEST(june.records.front().line == s.records[3624].line);
  BOOST_TEST(june.records.back().line == s.records[4343].line);

  // In a leap-year file, February 29 is one day of 24 records.
  TempDir d;
  EpwText e;
  add_hours(e, 2020, 2, 27, 96);
  const WeatherSeries leap = read_epw(write(d, "leap4.epw", e.text()));
  BOOST_TEST(select_period(leap, {2, 29}, {2, 29}).records.size() == 24u);
  BOOST_TEST(select_period(leap, {2, 28}, {3, 1}).records.size() == 72u);
}
