#define BOOST_TEST_MODULE tmy3_reader
#include <boost/test/unit_test.hpp>

// NREL TMY3 CSV input (io/tmy3_reader.h). The shared Chicago O'Hare file is NREL TMY3 data in
// EPW form: written back here as TMY3 CSV (the User's Manual's column names and -9900 missing
// code, by a plain field copy independent of both readers), it must give the EPW reader's series
// record for record. Then the format's own rules and every refused input.

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/core/input_error.h"
#include "input_error_of.h"
#include "io/epw_reader.h"
#include "io/support/tmy3_csv.h"
#include "io/tmy3_reader.h"
#include "shared_data.h"

using namespace skyband;
namespace fs = std::filesystem;

namespace {

const fs::path kChicago = fs::path(SKYBAND_SHARED_DATA) / "weather" / "USA_IL_Chicago-OHare.725300_TMY3.epw";

fs::path temp_dir() {
  const fs::path p = fs::temp_directory_path() / ("skyband_tmy3_reader_test_" + std::to_string(::getpid()));
  fs::create_directories(p);
  return p;
}

fs::path write_text(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

using skyband::test::error_of;

const std::string kSite = "725300,\"CHICAGO OHARE INTL AP\",IL,-6.0,41.983,-87.917,201\n";

}  // namespace

BOOST_AUTO_TEST_CASE(chicago_as_tmy3_csv_gives_the_epw_series, *skyband::test::needs_shared_data()) {
  const fs::path f =
      write_text("chicago_tmy3.csv", test::epw_as_tmy3(kChicago, "725300,CHICAGO OHARE INTL AP,IL,-6.0,41.98,-87.92,201.0\n"));
  const WeatherSeries a = read_epw(kChicago), b = read_weather_file(f);
  BOOST_TEST(b.location.time_zone_hours == a.location.time_zone_hours);
  BOOST_TEST(b.location.latitude_deg == a.location.latitude_deg);
  BOOST_TEST(b.location.longitude_deg == a.location.longitude_deg);
  BOOST_TEST(b.location.source == "TMY3");
  BOOST_TEST_REQUIRE(b.records.size() == a.records.size());
  BOOST_TEST(b.records.size() == 8760u);
  for (std::size_t i = 0; i < a.records.size(); ++i) {
    const WeatherRecord &x = a.records[i], &y = b.records[i];
    BOOST_TEST_REQUIRE((x.month == y.month && x.day == y.day && x.hour == y.hour && x.year == y.year), "record " << i);
    BOOST_TEST_REQUIRE((x.ghi_Wh_m2 == y.ghi_Wh_m2 && x.dni_Wh_m2 == y.dni_Wh_m2 && x.dhi_Wh_m2 == y.dhi_Wh_m2), "record " << i);
    BOOST_TEST_REQUIRE(
        (x.global_illuminance_lux == y.global_illuminance_lux && x.direct_illuminance_lux == y.direct_illuminance_lux &&
         x.diffuse_illuminance_lux == y.diffuse_illuminance_lux),
        "record " << i);
    BOOST_TEST_REQUIRE((x.dew_point_C == y.dew_point_C && x.albedo == y.albedo), "record " << i);
  }
  BOOST_TEST(b.warnings.empty());
}

BOOST_AUTO_TEST_CASE(hour_ending_records_and_missing_codes) {
  // Two hours of 1 January: hour 01:00 covers 00:00–01:00, its sun at 00:30 (mid_hour 0.5).
  const std::string csv = kSite + test::kTmy3Header +
                          "01/01/1990,01:00,0,0,0,1,0,0,1,0,0,1,0,-9900,1,0,-9900,1,0,-9900,1,0,-5.0,A,7,-9900,A,7,-9900,F,8\n"
                          "01/01/1990,02:00,0,0,12,1,8,30,1,8,5,1,8,1200,1,8,2000,1,8,600,1,8,-5.0,A,7,-7.5,A,7,1.5,F,8\n";
  const WeatherSeries s = read_tmy3_csv(write_text("two.csv", csv));
  BOOST_TEST(s.location.name == "CHICAGO OHARE INTL AP");  // the manual's quotes removed
  BOOST_TEST_REQUIRE(s.records.size() == 2u);
  BOOST_TEST(s.records[0].mid_hour() == 0.5);
  BOOST_TEST(!s.records[0].global_illuminance_lux.has_value());
  BOOST_TEST(!s.records[0].dew_point_C.has_value());
  BOOST_TEST(s.records[1].ghi_Wh_m2 == 12.0);
  BOOST_TEST(s.records[1].dni_Wh_m2 == 30.0);
  BOOST_TEST(s.records[1].dhi_Wh_m2 == 5.0);
  BOOST_TEST(*s.records[1].direct_illuminance_lux == 2000.0);
  BOOST_TEST(*s.records[1].dew_point_C == -7.5);
  BOOST_TEST(!s.records[1].albedo.has_value());  // 1.5: invalid, warned
  BOOST_TEST(s.warnings.size() == 2u);           // a partial year, an invalid albedo
}

BOOST_AUTO_TEST_CASE(day_month_and_year_wrap) {
  std::string csv = kSite + test::kTmy3Header;
  const auto row = [](const char* date, const char* time) {
    return std::string(date) + "," + time + ",0,0,1,1,8,0,1,8,1,1,8,0,1,8,0,1,8,0,1,8,0,A,7,0,A,7,0.2,F,8\n";
  };
  // After February 28 comes February 29 (a leap-year file) or March 1; after December 31,
  // January 1 (of the next year: typical years mix years).
  BOOST_TEST(
      read_tmy3_csv(write_text("leap.csv", csv + row("02/28/1988", "24:00") + row("02/29/1988", "01:00"))).records.size() == 2u);
  BOOST_TEST(
      read_tmy3_csv(write_text("march.csv", csv + row("02/28/1987", "24:00") + row("03/01/1987", "01:00"))).records.size() == 2u);
  BOOST_TEST(
      read_tmy3_csv(write_text("wrap.csv", csv + row("12/31/1988", "24:00") + row("01/01/1975", "01:00"))).records.size() == 2u);
  // 03/01 01:00 → 12/31 24:00 is not one hour on.
  const std::string m =
      error_of([&] { read_tmy3_csv(write_text("gap.csv", csv + row("03/01/1988", "01:00") + row("12/31/1988", "24:00"))); });
  BOOST_TEST(
      m.find("gap.csv:4: Date (MM/DD/YYYY) = '12/31/1988': the record does not follow the one on line 3") != std::string::npos,
      m);
}

BOOST_AUTO_TEST_CASE(refused_files_name_file_line_column_and_value) {
  const std::string ok = "01/01/1990,01:00,0,0,0,1,0,0,1,0,0,1,0,0,1,0,0,1,0,0,1,0,-5.0,A,7,-6,A,7,0.2,F,8\n";
  const auto with = [&](const std::string& record) { return kSite + test::kTmy3Header + record; };
  struct Case {
    std::string name, text, message;
  };
  const std::vector<Case> cases{
      {"empty.csv", "", "a site line and a column line"},
      {"site.csv", "725300,CHICAGO\n" + std::string(test::kTmy3Header) + ok, "site.csv:1: the site line has 2 fields"},
      {"nocol.csv", kSite + "Date (MM/DD/YYYY),Time (HH:MM)\n01/01/1990,01:00\n", "no column 'GHI (W/m^2)'"},
      {"norec.csv", kSite + test::kTmy3Header, "no weather records"},
      {"ghi.csv", with("01/01/1990,01:00,0,0,-9900,1,0,0,1,0,0,1,0,0,1,0,0,1,0,0,1,0,-5.0,A,7,-6,A,7,0.2,F,8\n"),
       "ghi.csv:3: GHI (W/m^2) = '-9900': missing"},
      {"neg.csv", with("01/01/1990,01:00,0,0,0,1,0,-3,1,0,0,1,0,0,1,0,0,1,0,0,1,0,-5.0,A,7,-6,A,7,0.2,F,8\n"),
       "neg.csv:3: DNI (W/m^2) = '-3': negative"},
      {"nan.csv", with("01/01/1990,01:00,0,0,0,1,0,0,1,0,nan,1,0,0,1,0,0,1,0,0,1,0,-5.0,A,7,-6,A,7,0.2,F,8\n"),
       "nan.csv:3: DHI (W/m^2) = 'nan': not a number"},
      {"lux.csv", with("01/01/1990,01:00,0,0,0,1,0,0,1,0,0,1,0,200000,1,0,0,1,0,0,1,0,-5.0,A,7,-6,A,7,0.2,F,8\n"),
       "GH illum (lx) = '200000'"},
      {"date.csv", with("13/01/1990,01:00,0,0,0,1,0,0,1,0,0,1,0,0,1,0,0,1,0,0,1,0,-5.0,A,7,-6,A,7,0.2,F,8\n"),
       "'13/01/1990': no such date"},
      {"time.csv", with("01/01/1990,00:30,0,0,0,1,0,0,1,0,0,1,0,0,1,0,0,1,0,0,1,0,-5.0,A,7,-6,A,7,0.2,F,8\n"), "'00:30'"},
      {"short.csv", with("01/01/1990,01:00,0,0\n"), "short.csv:3: 4 fields for 31 columns"},
      {"tz.csv", "725300,X,IL,-26,41.98,-87.92,201\n" + std::string(test::kTmy3Header) + ok, "time zone = '-26'"},
  };
  for (const Case& c : cases) {
    const std::string m = error_of([&] { read_tmy3_csv(write_text(c.name, c.text)); });
    BOOST_TEST(m.find(c.message) != std::string::npos, c.name << ": " << m);
  }
  // Neither format.
  BOOST_TEST(error_of([&] { read_weather_file(write_text("other.csv", "a,b\n1,2\n")); }).find("neither an EPW file") !=
             std::string::npos);
  BOOST_TEST(error_of([&] { read_weather_file(temp_dir() / "missing.csv"); }).find("missing.csv: no such weather file") !=
             std::string::npos);
}

// Fields are RFC 4180 on every line: quotes may enclose commas ("" is a quote), spaces outside
// them are trimmed. The site line below is Greensboro's as NREL writes it, with a comma added to
// its name.
BOOST_AUTO_TEST_CASE(quoted_fields_may_hold_commas) {
  const std::string record = "01/01/1990,01:00,0,0,0,1,0,0,1,0,0,1,0,0,1,0,0,1,0,0,1,0,-5.0,A,7,-6,A,7,0.2,F,8\n";
  const std::string site = "723170,\"GREENSBORO, PIEDMONT TRIAD INT\",NC,-5.0,36.100,-79.950,273\n";
  const WeatherSeries s = read_weather_file(write_text("comma.csv", site + test::kTmy3Header + record));
  BOOST_TEST(s.location.station_id == "723170");
  BOOST_TEST(s.location.name == "GREENSBORO, PIEDMONT TRIAD INT");
  BOOST_TEST(s.location.region == "NC");
  BOOST_TEST(s.location.time_zone_hours == -5.0);
  BOOST_TEST(s.location.latitude_deg == 36.1);
  BOOST_TEST(s.location.longitude_deg == -79.95);
  BOOST_TEST(s.location.elevation_m == 273.0);
  BOOST_TEST(s.records.size() == 1u);

  // "" inside quotes is one quote; spaces around the quotes are not part of the field; a quoted
  // number or date in a record is read as the unquoted one.
  const std::string odd_site = "1, \"O\"\"HARE \"\"X\"\", IL\" ,IL,-6.0,41.983,-87.917,201\n";
  const std::string quoted_record =
      "\"01/01/1990\",\"01:00\",0,0,\"12\",1,8,30,1,8,5,1,8,0,1,0,0,1,0,0,1,0,-5.0,A,7,-6,A,7,\"0.25\",F,8\n";
  const WeatherSeries q = read_tmy3_csv(write_text("quotes.csv", odd_site + test::kTmy3Header + quoted_record));
  BOOST_TEST(q.location.name == "O\"HARE \"X\", IL");
  BOOST_TEST(q.location.latitude_deg == 41.983);
  BOOST_REQUIRE(q.records.size() == 1u);
  BOOST_TEST(q.records[0].ghi_Wh_m2 == 12.0);
  BOOST_TEST(*q.records[0].albedo == 0.25);

  // A quote never closed on its line, or text after a closing quote, names the line and field.
  struct Case {
    std::string name, text, message;
  };
  const std::vector<Case> cases{
      {"open_site.csv",
       "723170,\"GREENSBORO, PIEDMONT TRIAD INT,NC,-5.0,36.100,-79.950,273\n" + std::string(test::kTmy3Header) + record,
       "open_site.csv:1: field 2 = '\"GREENSBORO, PIEDMONT TRIAD INT,NC,-5.0,…': the quoted field is never closed on its line"},
      {"after.csv", "723170,\"GREENSBORO\" INT,NC,-5.0,36.100,-79.950,273\n" + std::string(test::kTmy3Header) + record,
       "after.csv:1: field 2 = '\"GREENSBORO\" INT,NC,-5.0,36.100,-79.950,…': text after the closing quote"},
      {"open_record.csv", kSite + test::kTmy3Header + "01/01/1990,\"01:00,0\n",
       "open_record.csv:3: field 2 = '\"01:00,0': the quoted field is never closed on its line"},
  };
  for (const Case& c : cases) {
    const std::string m = error_of([&] { read_tmy3_csv(write_text(c.name, c.text)); });
    BOOST_TEST(m.find(c.message) != std::string::npos, c.name << ": " << m);
  }
}

// An albedo flagged '?' (no known source: TMY3 files write 0.00 so flagged where they have no
// albedo) or of exactly 0 (no ground reflects nothing) is missing, as one outside [0, 1] is: the
// ground albedo there is --albedo or the default. One warning line counts them for the file.
BOOST_AUTO_TEST_CASE(unknown_albedos_are_missing_with_one_warning) {
  const auto row = [](int hour, const char* albedo, const char* flag) {
    char b[160];
    std::snprintf(b, sizeof b, "01/01/1990,%02d:00,0,0,0,1,0,0,1,0,0,1,0,0,1,0,0,1,0,0,1,0,-5.0,A,7,-6,A,7,%s,%s,8\n", hour,
                  albedo, flag);
    return std::string(b);
  };
  const std::string csv = kSite + test::kTmy3Header + row(1, "0.00", "?") + row(2, "0.17", "?") + row(3, "0.00", "F") +
                          row(4, "0.17", "F") + row(5, "1.5", "F") + row(6, "-9900", "?") + row(7, "0.170", "E");
  const fs::path p = write_text("flags.csv", csv);
  const WeatherSeries s = read_tmy3_csv(p);
  BOOST_REQUIRE(s.records.size() == 7u);
  BOOST_TEST(!s.records[0].albedo.has_value());  // 0.00 flagged '?'
  BOOST_TEST(!s.records[1].albedo.has_value());  // flagged '?': no source, whatever the value
  BOOST_TEST(!s.records[2].albedo.has_value());  // 0 with a source flag
  BOOST_TEST(*s.records[3].albedo == 0.17);
  BOOST_TEST(!s.records[4].albedo.has_value());  // outside [0, 1]
  BOOST_TEST(!s.records[5].albedo.has_value());  // the missing code: not counted
  BOOST_TEST(*s.records[6].albedo == 0.17);
  std::vector<std::string> albedo_lines;
  for (const auto& w : s.warnings)
    if (w.find("albedo value(s)") != std::string::npos) albedo_lines.push_back(w);
  BOOST_REQUIRE_EQUAL(albedo_lines.size(), 1u);
  const std::string& w = albedo_lines[0];
  BOOST_TEST(w.find(p.string() + ": 4 albedo value(s) in column 'Alb (unitless)' treated as missing: ") == 0u, w);
  BOOST_TEST(w.find("2 with source flag '?'") != std::string::npos, w);
  BOOST_TEST(w.find("1 of 0 (no ground reflects nothing") != std::string::npos, w);
  BOOST_TEST(w.find("1 outside [0, 1]") != std::string::npos, w);
  BOOST_TEST(w.find("first on line 3") != std::string::npos, w);
  BOOST_TEST(w.find("--albedo or the default 0.2") != std::string::npos, w);

  // A whole day of the usual 0.00 '?' gives one line, not one per record.
  std::string day = kSite + test::kTmy3Header;
  for (int h = 1; h <= 24; ++h) day += row(h, "0.00", "?");
  const WeatherSeries d = read_tmy3_csv(write_text("flags_day.csv", day));
  std::size_t lines = 0;
  for (const auto& m : d.warnings) lines += m.find("albedo value(s)") != std::string::npos;
  BOOST_TEST(lines == 1u);
  BOOST_TEST(d.warnings.size() == 3u);  // that line, the partial year and a day without radiation
}
