#define BOOST_TEST_MODULE irradiance_cli
#include <boost/test/unit_test.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include <netcdf.h>
#include <nlohmann/json.hpp>

#include "cli/support/cli_runner.h"
#include "io/support/tmy3_csv.h"
#include "lighting/support/spencer_sun.h"
#include "shared_data.h"

namespace tt = boost::test_tools;
namespace fs = std::filesystem;
using skyband::test::run_skyband;

namespace {

std::string q(const fs::path& p) {
  return skyband::test::shell_quote(p);
}
void write_cube(const fs::path& file) {
  skyband::test::write_cube_obj(file);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string c;
  while (std::getline(ss, c, ',')) cells.push_back(c);
  return cells;
}

// Rows of a CSV without quoted cells, as column name → text.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& file) {
  std::ifstream f(file);
  std::string line;
  std::getline(f, line);
  const auto header = split(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(f, line)) {
    const auto cells = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

double num(const std::map<std::string, std::string>& row, const std::string& column) {
  const auto it = row.find(column);
  BOOST_TEST_REQUIRE((it != row.end()), "missing column " << column);
  return std::stod(it->second);
}

}  // namespace

// End to end against `skyband sky --json` (an independent path: the sky's horizontal diffuse
// irradiance by hemisphere quadrature, no visibility) and closed-form geometry: the cube's top
// face is open (sky = horizontal diffuse within 3e-3, the two quadratures' resolution of the
// circumsolar peak; sun = E_n·sin 30°); a ground point 17 m north of the cube is in its shadow
// (shadow length 10 m / tan 30° = 17.32 m); columns appended after the pass-through ones.
BOOST_AUTO_TEST_CASE(end_to_end_against_the_sky_command) {
  const fs::path d = skyband::test::test_folder("irradiance_cli_e2e");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "id,x,y,z,nx,ny,nz\n"
                                  "top,5,5,10,0,0,1\n"
                                  "shadow,5,27,0,0,0,1\n"
                                  "southwall,5,0,5,0,-1,0\n";
  const std::string sun = " --sun-altitude 30 --sun-azimuth 180";
  const auto r = run_skyband("irradiance --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --out " +
                             q(d / "out.csv") + sun + " --threads 2");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  std::ifstream f(d / "out.csv");
  std::string header;
  std::getline(f, header);
  BOOST_TEST(header ==
             "id,x,y,z,nx,ny,nz,svf,sky_exposure,cos_incidence,sun_visible,sky_W_m2,sun_W_m2,global_W_m2,sky_lx,sun_lx,"
             "global_lx,sky_ratio");
  const auto rows = read_csv(d / "out.csv");
  BOOST_TEST_REQUIRE(rows.size() == 3u);

  const auto s = run_skyband("sky" + sun + " --json");
  BOOST_TEST_REQUIRE(s.exit_code == 0, s.err);
  const auto j = nlohmann::json::parse(s.out);
  const double diffuse = j["sky"]["horizontal_diffuse_irradiance_W_m2"].get<double>();
  const double diffuse_lx = j["sky"]["horizontal_diffuse_illuminance_lx"].get<double>();
  const double dn = j["sun"]["direct_normal_irradiance_W_m2"].get<double>();
  const double sin30 = 0.5, cos30 = std::sqrt(3.0) / 2;

  const auto& top = rows[0];
  BOOST_TEST(num(top, "svf") == 1.0, tt::tolerance(1e-12));
  BOOST_TEST(num(top, "sky_W_m2") == diffuse, tt::tolerance(3e-3));
  BOOST_TEST(num(top, "sky_lx") == diffuse_lx, tt::tolerance(3e-3));
  BOOST_TEST(num(top, "sky_ratio") == 1.0, tt::tolerance(1e-12));
  BOOST_TEST(num(top, "sun_visible") == 1.0);
  BOOST_TEST(num(top, "sun_W_m2") == dn * sin30, tt::tolerance(1e-9));
  BOOST_TEST(num(top, "global_W_m2") == num(top, "sky_W_m2") + num(top, "sun_W_m2"), tt::tolerance(1e-12));
  BOOST_TEST(num(top, "global_lx") == num(top, "sky_lx") + num(top, "sun_lx"), tt::tolerance(1e-12));

  const auto& shadow = rows[1];
  BOOST_TEST(num(shadow, "sun_visible") == 0.0);
  BOOST_TEST(num(shadow, "sun_W_m2") == 0.0);
  BOOST_TEST(num(shadow, "sky_W_m2") > 0.0);
  BOOST_TEST(num(shadow, "sky_W_m2") < num(top, "sky_W_m2"));

  const auto& wall = rows[2];
  BOOST_TEST(num(wall, "cos_incidence") == cos30, tt::tolerance(1e-9));
  BOOST_TEST(num(wall, "sun_W_m2") == dn * cos30, tt::tolerance(1e-9));
  BOOST_TEST(num(wall, "svf") == 0.5, tt::tolerance(1e-9));
  // The cube (a closed box) is a column scene: every point went by the exact horizon, and stderr
  // says so; with --method bands none does, and the results agree within the band method's error.
  BOOST_TEST(r.err.find("3 points exact by the horizon of closed buildings;") != std::string::npos, r.err);
  const auto rb = run_skyband("irradiance --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --out " +
                              q(d / "out_bands.csv") + sun + " --method bands");
  BOOST_TEST_REQUIRE(rb.exit_code == 0, rb.err);
  BOOST_TEST(rb.err.find("3 points by the band method;") != std::string::npos, rb.err);
  const auto rows_b = read_csv(d / "out_bands.csv");
  BOOST_TEST_REQUIRE(rows_b.size() == 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    BOOST_TEST(std::abs(num(rows_b[i], "svf") - num(rows[i], "svf")) <= 1e-3);  // the band method's target
    BOOST_TEST(num(rows_b[i], "sky_W_m2") == num(rows[i], "sky_W_m2"), tt::tolerance(2e-3));
    BOOST_TEST(num(rows_b[i], "sun_visible") == num(rows[i], "sun_visible"));
  }
}

// The sun from place and time (NREL SPA) gives the same sun as `skyband sky` for that moment:
// a horizontal open face receives E_n·sin(altitude) with the altitude `sky` reports.
BOOST_AUTO_TEST_CASE(sun_from_place_and_time) {
  const fs::path d = skyband::test::test_folder("irradiance_cli_spa");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "x,y,z\n5,5,10\n";
  const std::string when = " --lat 48.14 --lon 11.58 --time 2026-06-21T15:00:00+02:00";
  const auto r = run_skyband("irradiance --quiet --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --out " +
                             q(d / "out.csv") + when);
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.empty());
  const auto s = run_skyband("sky" + when + " --json");
  BOOST_TEST_REQUIRE(s.exit_code == 0, s.err);
  const auto j = nlohmann::json::parse(s.out);
  const double alt = j["sun"]["altitude_deg"].get<double>() * M_PI / 180;
  const double dn = j["sun"]["direct_normal_irradiance_W_m2"].get<double>();
  const auto rows = read_csv(d / "out.csv");
  BOOST_TEST_REQUIRE(rows.size() == 1u);
  BOOST_TEST(num(rows[0], "cos_incidence") == std::sin(alt), tt::tolerance(1e-9));
  BOOST_TEST(num(rows[0], "sun_W_m2") == dn * std::sin(alt), tt::tolerance(1e-9));
}

// Bad input: one line naming the flag, file or value, exit code 2, no output file left.
BOOST_AUTO_TEST_CASE(bad_input_errors) {
  const fs::path d = skyband::test::test_folder("irradiance_cli_errors");
  write_cube(d / "cube.obj");
  std::ofstream(d / "ok.csv") << "x,y,z\n1,2,30\n";
  std::ofstream(d / "nan.csv") << "x,y,z\n1,nan,3\n";
  const std::string base = "irradiance --mesh " + q(d / "cube.obj") + " --out " + q(d / "out.csv");
  const std::string pts = " --points " + q(d / "ok.csv");
  skyband::test::check_bad_input(
      {
          {base + pts, "no sun"},
          {base + pts + " --sun-altitude 95", "--sun-altitude 95"},
          {base + pts + " --sun-altitude 30 --lat 10 --lon 10 --time 2026-01-01T12:00:00Z", "not both"},
          {base + pts + " --lat 10 --time 2026-01-01T12:00:00Z", "--lon"},
          {base + pts + " --sun-altitude 30 --aod550 -1", "--aod550"},
          {base + pts + " --sun-altitude 30 --model cie-16", "cie-16"},
          {base + pts + " --sun-altitude 30 --zenith-luminance 5000", "--zenith-luminance"},
          {base + pts + " --sun-altitude 30 --bands 0", "--bands"},
          {base + " --points " + q(d / "absent.csv") + " --sun-altitude 30", "absent.csv"},
          {base + " --points " + q(d / "nan.csv") + " --sun-altitude 30", "nan.csv"},
          {"irradiance --mesh " + q(d / "cube.obj") + pts + " --sun-altitude 30", "--out"},
      },
      d / "out.csv");
}

// The built-in demo prints its table; the open roof of the tower has sky_ratio 1 (it is an
// unobstructed horizontal face) and the street centre is in a building's shadow at this sun.
BOOST_AUTO_TEST_CASE(demo_runs) {
  const auto r = run_skyband("irradiance --demo --sun-altitude 35 --sun-azimuth 200");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  const auto tower = r.out.find("roof of the tower");
  BOOST_TEST_REQUIRE(tower != std::string::npos);
  const std::string line = r.out.substr(tower, r.out.find('\n', tower) - tower);
  BOOST_TEST(line.find(" yes ") != std::string::npos);
  BOOST_TEST(line.substr(line.size() - 6) == "1.0000");
  const auto demo_without_sun = run_skyband("irradiance --demo");
  BOOST_TEST(demo_without_sun.exit_code == 2);
  BOOST_TEST(demo_without_sun.err.find("no sun") != std::string::npos);
  const auto demo_with_times = run_skyband("irradiance --demo --times whatever.csv");
  BOOST_TEST(demo_with_times.exit_code == 2);
  BOOST_TEST(demo_with_times.err.find("--times") != std::string::npos);
}

// --times: sums over moments equal the hours-weighted sums of single-moment runs of the same
// command (sky within 1e-5: one quadrature of the summed sky grids; sun exactly), and sun_hours
// counts the hours in sun: the ground point 17 m north of the cube is shadowed by the southern
// sun (shadow 17.3 m) and lit by the northern one.
BOOST_AUTO_TEST_CASE(times_sum_the_moments) {
  const fs::path d = skyband::test::test_folder("irradiance_cli_times");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "x,y,z\n5,5,10\n5,27,0\n";
  std::ofstream(d / "times.csv") << "sun_altitude,sun_azimuth,hours\n30,180,0.5\n45,0,1.5\n";
  const std::string base = "irradiance --quiet --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv");
  const auto r = run_skyband(base + " --out " + q(d / "sum.csv") + " --times " + q(d / "times.csv"));
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  const auto sum = read_csv(d / "sum.csv");
  BOOST_TEST_REQUIRE(sum.size() == 2u);
  std::vector<double> sky(2, 0.0), sun(2, 0.0), hours(2, 0.0);
  const double w[] = {0.5, 1.5};
  const char* suns[] = {" --sun-altitude 30 --sun-azimuth 180", " --sun-altitude 45 --sun-azimuth 0"};
  for (int t = 0; t < 2; ++t) {
    const auto s = run_skyband(base + " --out " + q(d / "one.csv") + suns[t]);
    BOOST_TEST_REQUIRE(s.exit_code == 0, s.err);
    const auto one = read_csv(d / "one.csv");
    for (std::size_t i = 0; i < 2; ++i) {
      sky[i] += w[t] * num(one[i], "sky_W_m2");
      sun[i] += w[t] * num(one[i], "sun_W_m2");
      hours[i] += w[t] * num(one[i], "sun_visible");
    }
  }
  for (std::size_t i = 0; i < 2; ++i) {
    BOOST_TEST(num(sum[i], "sky_Wh_m2") == sky[i], tt::tolerance(1e-5));
    BOOST_TEST(num(sum[i], "sun_Wh_m2") == sun[i], tt::tolerance(1e-9));
    BOOST_TEST(num(sum[i], "sun_hours") == hours[i]);
    BOOST_TEST(num(sum[i], "global_Wh_m2") == num(sum[i], "sky_Wh_m2") + num(sum[i], "sun_Wh_m2"), tt::tolerance(1e-12));
  }
  BOOST_TEST(num(sum[0], "sun_hours") == 2.0);
  BOOST_TEST(num(sum[1], "sun_hours") == 1.5);
}

// Bad times files and flags: one line naming the file:line or flag, exit 2, no output file.
BOOST_AUTO_TEST_CASE(times_errors) {
  const fs::path d = skyband::test::test_folder("irradiance_cli_times_errors");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "x,y,z\n5,5,10\n";
  std::ofstream(d / "both.csv") << "time,sun_altitude,sun_azimuth\n2026-06-21T12:00:00Z,30,180\n";
  std::ofstream(d / "half.csv") << "sun_altitude,hours\n30,1\n";
  std::ofstream(d / "neg.csv") << "sun_altitude,sun_azimuth,hours\n30,180,1\n20,90,-2\n";
  std::ofstream(d / "alt.csv") << "sun_altitude,sun_azimuth\n95,180\n";
  std::ofstream(d / "time.csv") << "time\n2026-06-21T12:00:00Z\n";
  std::ofstream(d / "empty.csv") << "sun_altitude,sun_azimuth\n";
  const std::string base =
      "irradiance --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --out " + q(d / "out.csv") + " --times ";
  skyband::test::check_bad_input(
      {
          {base + q(d / "both.csv"), "either a 'time' column"},
          {base + q(d / "half.csv"), "come together"},
          {base + q(d / "neg.csv"), "neg.csv:3"},
          {base + q(d / "alt.csv"), "sun_altitude 95"},
          {base + q(d / "time.csv"), "--lat and --lon"},
          {base + q(d / "empty.csv"), "no moments"},
          {base + q(d / "absent.csv"), "absent.csv"},
          {base + q(d / "alt.csv") + " --sun-altitude 20", "--times"},
      },
      d / "out.csv");
}

// --weather on a shared EPW file: the cube's open top receives the file's diffuse and direct
// light (the README of ../shared/data/weather gives Chicago's annual sums: GHI 1406.6, DHI 660.3
// kWh/m²; the components with the sun at mid-interval add up to the GHI column within 1.5 %), no
// ground; its south wall sees half the ground, ρ·GHI/2 with the file's albedo; a period is a
// part of the year; the timing check warns on a file whose radiation comes early (Heino, ~58
// min per the README).
BOOST_AUTO_TEST_CASE(a_year_of_weather, *skyband::test::needs_shared_data()) {
  const fs::path d = skyband::test::test_folder("irradiance_cli_weather");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "id,x,y,z,nx,ny,nz\n"
                                  "top,5,5,10,0,0,1\n"
                                  "southwall,5,0,5,0,-1,0\n";
  const fs::path shared(SKYBAND_SHARED_DATA);
  const fs::path chicago = shared / "weather" / "USA_IL_Chicago-OHare.725300_TMY3.epw";
  const std::string base = "irradiance --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --weather ";
  const auto r = run_skyband(base + q(chicago) + " --out " + q(d / "year.csv"));
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("warning") == std::string::npos, r.err);  // Chicago is centred on its sun
  std::ifstream f(d / "year.csv");
  std::string header;
  std::getline(f, header);
  BOOST_TEST(header ==
             "id,x,y,z,nx,ny,nz,svf,sky_exposure,ground_view,global_kWh_m2,sky_kWh_m2,sun_kWh_m2,ground_kWh_m2,"
             "global_klxh,sun_hours");
  const auto rows = read_csv(d / "year.csv");
  BOOST_TEST_REQUIRE(rows.size() == 2u);
  const auto& top = rows[0];
  BOOST_TEST(num(top, "sky_kWh_m2") == 660.3, tt::tolerance(1e-4));
  BOOST_TEST(num(top, "global_kWh_m2") == 1406.6, tt::tolerance(0.015));
  BOOST_TEST(num(top, "ground_kWh_m2") == 0.0);
  BOOST_TEST(num(top, "sun_hours") > 4300.0);  // about half the year's 8760 h, more at this latitude's summer
  BOOST_TEST(num(top, "sun_hours") < 4500.0);
  const auto& wall = rows[1];
  BOOST_TEST(num(wall, "ground_view") == 0.5, tt::tolerance(1e-9));
  BOOST_TEST(num(wall, "global_kWh_m2") == num(wall, "sky_kWh_m2") + num(wall, "sun_kWh_m2") + num(wall, "ground_kWh_m2"),
             tt::tolerance(1e-12));
  BOOST_TEST(num(wall, "sun_hours") < num(top, "sun_hours"));

  const auto june = run_skyband(base + q(chicago) + " --from 06-01 --to 06-30 --albedo 0.3 --out " + q(d / "june.csv"));
  BOOST_TEST_REQUIRE(june.exit_code == 0, june.err);
  const auto jr = read_csv(d / "june.csv");
  BOOST_TEST(num(jr[0], "sun_hours") < 31 * 16.0);
  BOOST_TEST(num(jr[0], "sun_hours") > 30 * 14.0);  // 41.98 N in June: ~15 h of daylight
  BOOST_TEST(num(jr[1], "ground_kWh_m2") > 0.0);

  const auto heino =
      run_skyband(base + q(shared / "weather" / "NLD_OV_Heino.062780_TMYx.2007-2021.epw") + " --out " + q(d / "heino.csv"));
  BOOST_TEST_REQUIRE(heino.exit_code == 0, heino.err);
  BOOST_TEST(heino.err.find("earlier than the sun") != std::string::npos, heino.err);
}

// The same weather as TMY3 CSV gives the same output, byte for byte: Chicago O'Hare is NREL TMY3
// data in EPW form, written back as TMY3 CSV (tests/io/support/tmy3_csv.h); the readers must give
// the same records, the same site and the same timing.
BOOST_AUTO_TEST_CASE(tmy3_csv_weather_gives_the_epw_result, *skyband::test::needs_shared_data()) {
  const fs::path d = skyband::test::test_folder("irradiance_cli_tmy3");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "id,x,y,z,nx,ny,nz\n"
                                  "top,5,5,10,0,0,1\n"
                                  "southwall,5,0,5,0,-1,0\n";
  const fs::path chicago = fs::path(SKYBAND_SHARED_DATA) / "weather" / "USA_IL_Chicago-OHare.725300_TMY3.epw";
  std::ofstream(d / "chicago.csv") << skyband::test::epw_as_tmy3(chicago.string(),
                                                                 "725300,CHICAGO OHARE INTL AP,IL,-6.0,41.98,-87.92,201.0\n");
  const std::string base =
      "irradiance --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --from 03-01 --to 03-03 --weather ";
  const auto epw = run_skyband(base + q(chicago) + " --out " + q(d / "epw.csv"));
  const auto tmy3 = run_skyband(base + q(d / "chicago.csv") + " --out " + q(d / "tmy3.csv"));
  BOOST_TEST_REQUIRE(epw.exit_code == 0, epw.err);
  BOOST_TEST_REQUIRE(tmy3.exit_code == 0, tmy3.err);
  const auto a = read_csv(d / "epw.csv"), b = read_csv(d / "tmy3.csv");
  BOOST_TEST_REQUIRE(a.size() == 2u);
  BOOST_TEST_REQUIRE(b.size() == a.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    for (const char* c : {"svf", "global_kWh_m2", "sky_kWh_m2", "sun_kWh_m2", "ground_kWh_m2", "global_klxh", "sun_hours"})
      BOOST_TEST(num(a[i], c) == num(b[i], c), "row " << i << " " << c << ": " << num(a[i], c) << " against " << num(b[i], c));
  BOOST_TEST(num(a[0], "global_kWh_m2") > 0.0);
}

BOOST_AUTO_TEST_CASE(bad_weather_input, *skyband::test::needs_shared_data()) {
  const fs::path d = skyband::test::test_folder("irradiance_cli_weather_bad");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "x,y,z\n5,5,10\n";
  std::ofstream(d / "short.epw") << "LOCATION,Nowhere,,,,,10,10,0,0\n";
  const fs::path chicago = fs::path(SKYBAND_SHARED_DATA) / "weather" / "USA_IL_Chicago-OHare.725300_TMY3.epw";
  const std::string base =
      "irradiance --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --out " + q(d / "out.csv");
  skyband::test::check_bad_input(
      {
          {base + " --weather " + q(chicago) + " --sun-altitude 30", "--sun-altitude"},
          {base + " --weather " + q(chicago) + " --albedo 1.5", "--albedo"},
          {base + " --weather " + q(chicago) + " --from 02-30 --to 03-01", "02-30"},
          {base + " --weather " + q(chicago) + " --from 02-01", "--to"},
          {base + " --weather " + q(d / "absent.epw"), "absent.epw"},
          {base + " --weather " + q(d / "short.epw"), "short.epw"},
          {base + " --albedo 0.3 --sun-altitude 30", "--weather"},
          {base + " --weather " + q(chicago) + " --times " + q(d / "pts.csv"), "--times"},
          {base + " --weather " + q(chicago) + " --sun-at noon", "--sun-at"},
          {base + " --sun-at end --sun-altitude 30", "--weather"},
      },
      d / "out.csv");
}

// June 2019 as an EPW file whose radiation follows the Spencer sun (tests/lighting/support/
// spencer_sun.h) at 40° N, 105° W, UTC−7 at the middle of each hour, c = cos z there: DNI =
// 900·(1 − e^(−3c)), DHI = 40 + 120·c, GHI = DHI + DNI·c (0 when c ≤ 0), so that the records close
// for that sun; the header says `header_latitude_deg`.
void write_closed_june_epw(const fs::path& file, double header_latitude_deg) {
  std::ofstream out(file, std::ios::binary);
  char line[512];
  std::snprintf(line, sizeof line, "LOCATION,Closure,,XYZ,synthetic,0,%.1f,-105.0,-7.0,1600\n", header_latitude_deg);
  out << line << "DESIGN CONDITIONS,0\nTYPICAL/EXTREME PERIODS,0\nGROUND TEMPERATURES,0\n"
      << "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\nCOMMENTS 1,closed-form synthetic\nCOMMENTS 2,\n"
      << "DATA PERIODS,1,1,Data,Saturday, 6/ 1, 6/30\n";
  for (int day = 1; day <= 30; ++day)
    for (int h = 1; h <= 24; ++h) {
      const int n = 151 + day;  // day of the year: June 1 is day 152 of 2019
      const double c = skyband::test::spencer_cos_zenith(40.0, -105.0, -7.0, n, h - 0.5);
      const double dni = c > 0 ? 900 * (1 - std::exp(-3 * c)) : 0, dhi = c > 0 ? 40 + 120 * c : 0;
      std::snprintf(line, sizeof line,
                    "2019,6,%d,%d,0,?9?9?9?9E0?9?9?9?9*9?9?9?9?9?9?9*9?9*9*9?9*9,20.0,10.0,50,101325,0,0,300,"
                    "%.3f,%.3f,%.3f,999999,999999,999999,9999,180,2.0,0,0,777.7,77777,9,999999999,11,0.0850,0,88,"
                    "0.200,0.0,0.0\n",
                    day, h, dhi + dni * c, dni, dhi);
      out << line;
    }
}

// The closure check: the closed-form June is consistent under its own latitude (no closure
// warning); under the header's latitude of the wrong sign the sun is in the wrong sky and the
// command warns once, naming the file and the worst month, and still computes.
BOOST_AUTO_TEST_CASE(radiation_inconsistent_with_the_sun_is_warned) {
  const fs::path d = skyband::test::test_folder("irradiance_cli_weather_closure");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "id,x,y,z,nx,ny,nz\ntop,5,5,10,0,0,1\n";
  write_closed_june_epw(d / "north.epw", 40.0);
  write_closed_june_epw(d / "south.epw", -40.0);
  const std::string base = "irradiance --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --weather ";
  const auto good = run_skyband(base + q(d / "north.epw") + " --out " + q(d / "north.csv"));
  BOOST_TEST_REQUIRE(good.exit_code == 0, good.err);
  BOOST_TEST(good.err.find("does not equal diffuse") == std::string::npos, good.err);
  BOOST_TEST(good.err.find("earlier than the sun") == std::string::npos, good.err);  // centred by construction

  const auto bad = run_skyband(base + q(d / "south.epw") + " --out " + q(d / "south.csv"));
  BOOST_TEST_REQUIRE(bad.exit_code == 0, bad.err);  // suspicious, not malformed: computed with a warning
  const std::string expected = "skyband: warning: " + (d / "south.epw").string() +
                               ": global horizontal radiation does not equal diffuse + direct normal*cos(zenith): in June "
                               "(month 6)";
  BOOST_TEST(bad.err.find(expected) != std::string::npos, bad.err);
  std::size_t lines = 0;
  for (std::size_t at = 0; (at = bad.err.find("does not equal diffuse", at)) != std::string::npos; ++at) ++lines;
  BOOST_TEST(lines == 1u);
  BOOST_TEST(fs::exists(d / "south.csv"));
}

// A terrain sheet with a material the defaults do not know hides the ground from the facade
// points: the command warns, and naming the material with --ground-materials gives the wall its
// ground again (half the lower hemisphere: ground_view 0.5 for a wall on an open plane).
BOOST_AUTO_TEST_CASE(unnamed_terrain_is_reported, *skyband::test::needs_shared_data()) {
  const fs::path d = skyband::test::test_folder("irradiance_cli_weather_terrain");
  std::ofstream(d / "block.obj") << "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nv 0 0 10\nv 10 0 10\nv 10 10 10\nv 0 10 10\n"
                                    "v -500 -500 0\nv 500 -500 0\nv 500 500 0\nv -500 500 0\n"
                                    "usemtl Wall\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\nf 5 6 7 8\n"
                                    "usemtl Meadow\nf 9 10 11 12\n";
  std::ofstream(d / "pts.csv") << "x,y,z,nx,ny,nz\n5,-0.01,5,0,-1,0\n-0.01,5,3,-1,0,0\n";
  const fs::path chicago = fs::path(SKYBAND_SHARED_DATA) / "weather" / "USA_IL_Chicago-OHare.725300_TMY3.epw";
  const std::string base = "irradiance --mesh " + q(d / "block.obj") + " --points " + q(d / "pts.csv") + " --weather " +
                           q(chicago) + " --from 03-01 --to 03-02 --out ";
  const auto unnamed = run_skyband(base + q(d / "a.csv"));
  BOOST_TEST_REQUIRE(unnamed.exit_code == 0, unnamed.err);
  BOOST_TEST(unnamed.err.find("2 of the 2 points that face the ground see less than 5 % of it") != std::string::npos,
             unnamed.err);
  const auto named = run_skyband(base + q(d / "b.csv") + " --ground-materials meadow");
  BOOST_TEST_REQUIRE(named.exit_code == 0, named.err);
  BOOST_TEST(named.err.find("points that face the ground") == std::string::npos, named.err);
  const auto rows = read_csv(d / "b.csv");
  BOOST_TEST_REQUIRE(rows.size() == 2u);
  BOOST_TEST(num(rows[0], "ground_view") == 0.5, tt::tolerance(1e-6));
}

// Moments from --date/--step/--zone instead of a times file: --sun-only gives the same sun hours
// as the full sums (which build a sky per moment) and as a hand-written times file holding the
// same moments; on the equinox at the equator the open roof sees the sun's centre (refracted) for
// a little over 12 h, so 12 or 13 of the 24 hourly moments.
BOOST_AUTO_TEST_CASE(generated_moments_and_the_sun_only_path) {
  const fs::path d = skyband::test::test_folder("irradiance_cli_dates");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "id,x,y,z,nx,ny,nz\ntop,5,5,10,0,0,1\nwall,5,0,5,0,-1,0\n";
  const std::string base = "irradiance --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --lat 0 --lon 0 ";
  const auto fast = run_skyband(base + "--date 2026-03-20 --step 60 --zone UTC --sun-only --out " + q(d / "fast.csv"));
  BOOST_TEST_REQUIRE(fast.exit_code == 0, fast.err);
  const auto full = run_skyband(base + "--date 2026-03-20 --step 60 --zone UTC --out " + q(d / "full.csv"));
  BOOST_TEST_REQUIRE(full.exit_code == 0, full.err);
  {
    std::ofstream t(d / "times.csv");
    t << "time,hours\n";
    for (int k = 0; k < 24; ++k) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "2026-03-20T%02d:30:00Z,1\n", k);
      t << buf;
    }
  }
  const auto file = run_skyband(base + "--times " + q(d / "times.csv") + " --sun-only --out " + q(d / "file.csv"));
  BOOST_TEST_REQUIRE(file.exit_code == 0, file.err);
  const auto a = read_csv(d / "fast.csv"), b = read_csv(d / "full.csv"), c = read_csv(d / "file.csv");
  BOOST_TEST_REQUIRE(a.size() == 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    BOOST_TEST(num(a[i], "sun_hours") == num(b[i], "sun_hours"));
    BOOST_TEST(num(a[i], "sun_hours") == num(c[i], "sun_hours"));
  }
  BOOST_TEST(num(a[0], "sun_hours") >= 12.0);  // hourly steps: 12 or 13 moments have the sun up
  BOOST_TEST(num(a[0], "sun_hours") <= 13.0);
  BOOST_TEST(a[0].count("sky_Wh_m2") == 0u);  // the sun-only columns
  skyband::test::check_bad_input(
      {
          {base + "--date 2026-03-20 --out " + q(d / "bad.csv"), "--zone"},
          {base + "--date 2026-03-20 --zone Mars/Olympus --out " + q(d / "bad.csv"), "Mars/Olympus"},
          {base + "--date 2026-13-01 --zone UTC --out " + q(d / "bad.csv"), "2026-13-01"},
          {base + "--date 2026-03-20 --zone UTC --step 0 --out " + q(d / "bad.csv"), "--step"},
          {base + "--step 10 --out " + q(d / "bad.csv"), "--date"},
          {base + "--sun-only --sun-altitude 30 --out " + q(d / "bad.csv"), "--sun-only"},
          {base + "--date 2026-03-20 --zone UTC --times " + q(d / "times.csv") + " --out " + q(d / "bad.csv"), "--times"},
      },
      d / "bad.csv");
}

// --hourly: the NetCDF-4 file holds one series per point and interval; summed over the intervals
// (each 1 h) it gives the CSV's sums — exactly for the sun and the ground (the same terms), and for
// the sky within 1 % (daylight coefficients on a coarse grid, normalised per hour on the open
// horizontal face, against the time-integrated sky's quadrature). Time runs forward in UTC: the
// first interval of Chicago (UTC−6) on June 1st ends at 07:00 UTC.
BOOST_AUTO_TEST_CASE(hourly_netcdf, *skyband::test::needs_shared_data()) {
  const fs::path d = skyband::test::test_folder("irradiance_cli_hourly");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "id,x,y,z,nx,ny,nz\ntop,5,5,10,0,0,1\nsouthwall,5,0,5,0,-1,0\n";
  const fs::path chicago = fs::path(SKYBAND_SHARED_DATA) / "weather" / "USA_IL_Chicago-OHare.725300_TMY3.epw";
  const auto r =
      run_skyband("irradiance --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --weather " + q(chicago) +
                  " --from 06-01 --to 06-07 --out " + q(d / "week.csv") + " --hourly " + q(d / "week.nc"));
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(!fs::exists(d / "week.nc.partial"));
  int nc = -1;
  BOOST_TEST_REQUIRE(nc_open((d / "week.nc").c_str(), NC_NOWRITE, &nc) == NC_NOERR);
  int dim_point, dim_time;
  std::size_t points = 0, times = 0;
  BOOST_TEST_REQUIRE(nc_inq_dimid(nc, "point", &dim_point) == NC_NOERR);
  BOOST_TEST_REQUIRE(nc_inq_dimid(nc, "time", &dim_time) == NC_NOERR);
  nc_inq_dimlen(nc, dim_point, &points);
  nc_inq_dimlen(nc, dim_time, &times);
  BOOST_TEST(points == 2u);
  BOOST_TEST(times == 7u * 24u);
  int v_time, v_bounds;
  BOOST_TEST_REQUIRE(nc_inq_varid(nc, "time", &v_time) == NC_NOERR);
  BOOST_TEST_REQUIRE(nc_inq_varid(nc, "time_bounds", &v_bounds) == NC_NOERR);
  std::vector<double> t(times), b(2 * times);
  nc_get_var_double(nc, v_time, t.data());
  nc_get_var_double(nc, v_bounds, b.data());
  for (std::size_t k = 1; k < times; ++k) BOOST_TEST(t[k] - t[k - 1] == 1.0, tt::tolerance(1e-9));
  // (whatever year the file's June comes from: hour 1 ends at 01:00 UTC−6 = 07:00 UTC)
  BOOST_TEST(std::fmod(b[1], 24.0) == 7.0, tt::tolerance(1e-9));
  const auto rows = read_csv(d / "week.csv");
  const char* vars[3] = {"sky_W_m2", "sun_W_m2", "ground_W_m2"};
  const char* cols[3] = {"sky_kWh_m2", "sun_kWh_m2", "ground_kWh_m2"};
  for (int v = 0; v < 3; ++v) {
    int id;
    BOOST_TEST_REQUIRE(nc_inq_varid(nc, vars[v], &id) == NC_NOERR);
    std::vector<float> x(points * times);
    nc_get_var_float(nc, id, x.data());
    for (std::size_t p = 0; p < points; ++p) {
      double sum = 0;
      for (std::size_t k = 0; k < times; ++k) sum += x[p * times + k];
      const double expected = 1000 * num(rows[p], cols[v]);
      BOOST_TEST(sum == expected, tt::tolerance(v == 0 ? 1e-2 : 1e-5));
    }
  }
  // The illuminance: summed over the intervals, the CSV's global_klxh (the same terms in lx·h; the
  // sky within 1 % as above). Hour by hour the open top face (no ground in view) receives the
  // file's own illuminances: the sky normalised to the diffuse horizontal illuminance (field 20)
  // and the sun's direct normal illuminance (field 19) times cos z, the cosine that the file's
  // direct normal irradiance (field 15) gives with the face's sun_W_m2 of the same interval.
  int v_lx = -1, v_sun = -1;
  BOOST_TEST_REQUIRE(nc_inq_varid(nc, "global_lx", &v_lx) == NC_NOERR);
  BOOST_TEST_REQUIRE(nc_inq_varid(nc, "sun_W_m2", &v_sun) == NC_NOERR);
  char units[8] = {};
  BOOST_TEST_REQUIRE(nc_get_att_text(nc, v_lx, "units", units) == NC_NOERR);
  BOOST_TEST(std::string(units) == "lx");
  std::vector<float> lx(points * times), sun(points * times);
  nc_get_var_float(nc, v_lx, lx.data());
  nc_get_var_float(nc, v_sun, sun.data());
  for (std::size_t p = 0; p < points; ++p) {
    double sum = 0;
    for (std::size_t k = 0; k < times; ++k) sum += lx[p * times + k];
    BOOST_TEST(sum == 1000 * num(rows[p], "global_klxh"), tt::tolerance(1e-2));
  }
  std::vector<std::array<double, 3>> file;  // June 1–7: DNI (W m-2), direct normal and diffuse horizontal illuminance (lx)
  {
    std::ifstream in(chicago);
    std::string line;
    for (int k = 0; k < 8; ++k) std::getline(in, line);
    while (std::getline(in, line)) {
      std::vector<std::string> f;
      std::stringstream ss(line);
      for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
      if (f.size() > 19 && std::stoi(f[1]) == 6 && std::stoi(f[2]) <= 7)
        file.push_back({std::stod(f[14]), std::stod(f[17]), std::stod(f[18])});
    }
  }
  BOOST_TEST_REQUIRE(file.size() == times);
  int lit = 0, with_sun = 0;
  for (std::size_t k = 0; k < times; ++k) {
    const double dni = file[k][0], dni_lx = file[k][1], dhi_lx = file[k][2];
    if (!(dhi_lx > 0) || (dni == 0 && dni_lx > 0)) continue;
    ++lit;
    with_sun += sun[k] > 0;
    const double expected = dhi_lx + (dni > 0 ? dni_lx * sun[k] / dni : 0.0);
    BOOST_TEST(lx[k] == expected, tt::tolerance(1e-3));  // point 0: the top face
  }
  BOOST_TEST(lit >= 100);
  BOOST_TEST(with_sun >= 50);
  // One worker gives the same series, value for value (each point and each hour computed alone).
  const auto one =
      run_skyband("irradiance --threads 1 --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --weather " +
                  q(chicago) + " --from 06-01 --to 06-07 --out " + q(d / "week1.csv") + " --hourly " + q(d / "week1.nc"));
  BOOST_TEST_REQUIRE(one.exit_code == 0, one.err);
  int nc1 = -1;
  BOOST_TEST_REQUIRE(nc_open((d / "week1.nc").c_str(), NC_NOWRITE, &nc1) == NC_NOERR);
  for (const char* v : {"sky_W_m2", "sun_W_m2", "ground_W_m2", "global_W_m2", "global_lx"}) {
    int a = -1, b = -1;
    BOOST_TEST_REQUIRE(nc_inq_varid(nc, v, &a) == NC_NOERR);
    BOOST_TEST_REQUIRE(nc_inq_varid(nc1, v, &b) == NC_NOERR);
    std::vector<float> x(points * times), y(points * times);
    nc_get_var_float(nc, a, x.data());
    nc_get_var_float(nc1, b, y.data());
    BOOST_TEST((x == y), v);
  }
  nc_close(nc1);
  nc_close(nc);
}

// Times files at the edges of the format: `hours` is bounded (two rows of 1e308 would sum to inf),
// `sun_azimuth` has a range (1e308 is refused), the SPA's range errors name the file and line, and
// a NUL in a time does not cut the message short: one line naming file:line and the value, exit 2.
BOOST_AUTO_TEST_CASE(times_file_bounds_and_sun_errors_name_the_line) {
  const fs::path d = skyband::test::test_folder("irradiance_cli_times_bounds");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "x,y,z\n5,5,10\n5,27,0\n";
  std::ofstream(d / "huge.csv") << "sun_altitude,sun_azimuth,hours\n30,180,1e308\n30,180,1e308\n";
  std::ofstream(d / "over.csv") << "sun_altitude,sun_azimuth,hours\n30,180,8784.5\n";
  std::ofstream(d / "az.csv") << "sun_altitude,sun_azimuth\n30,180\n30,1e308\n";
  std::ofstream(d / "year.csv") << "time\n2026-06-21T12:00:00Z\n9999-06-21T12:00:00Z\n";
  std::ofstream(d / "nul.csv", std::ios::binary) << std::string("time\n2026-06-21T12:00\0:00Z\n", 27);
  const std::string base =
      "irradiance --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --out " + q(d / "out.csv") + " --times ";
  skyband::test::check_bad_input(
      {
          {base + q(d / "huge.csv"), "huge.csv:2: hours 1e+308 must be in [0, 8784]"},
          {base + q(d / "over.csv"), "over.csv:2: hours 8784.5"},
          {base + q(d / "az.csv"), "az.csv:3: sun_azimuth 1e+308 must be in [-360, 360]"},
          {base + q(d / "year.csv") + " --lat 52 --lon 4",
           "year.csv:3: column 'time': value '9999-06-21T12:00:00Z': sun position: year = 9999"},
          {base + q(d / "nul.csv") + " --lat 52 --lon 4", "nul.csv:2: column 'time': value '2026-06-21T12:00\\x00:00Z'"},
      },
      d / "out.csv");
  // The bounds are inclusive and the azimuth is taken modulo 360 (as --sun-azimuth and the scene
  // file do): a row of 8784 h at azimuth -90 gives the output of one at 270, bit for bit.
  std::ofstream(d / "west_neg.csv") << "sun_altitude,sun_azimuth,hours\n30,-90,8784\n";
  std::ofstream(d / "west_pos.csv") << "sun_altitude,sun_azimuth,hours\n30,270,8784\n";
  const std::string ok =
      "irradiance --quiet --sun-only --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --times ";
  const auto neg = run_skyband(ok + q(d / "west_neg.csv") + " --out " + q(d / "neg.csv"));
  const auto pos = run_skyband(ok + q(d / "west_pos.csv") + " --out " + q(d / "pos.csv"));
  BOOST_TEST_REQUIRE(neg.exit_code == 0, neg.err);
  BOOST_TEST_REQUIRE(pos.exit_code == 0, pos.err);
  BOOST_TEST(skyband::test::slurp(d / "neg.csv") == skyband::test::slurp(d / "pos.csv"));
  // The top face of the cube sees the sun for all 8784 h (closed form: nothing above it).
  BOOST_TEST(num(read_csv(d / "neg.csv")[0], "sun_hours") == 8784.0);
}
