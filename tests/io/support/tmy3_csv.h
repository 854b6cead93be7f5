#pragma once
// An EPW file's records written back as NREL TMY3 CSV (the User's Manual's column names, -9900 for
// missing values), so that tests can compare the TMY3 path with the EPW path on the same data.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace skyband::test {

inline const char* kTmy3Header =
    "Date (MM/DD/YYYY),Time (HH:MM),ETR (W/m^2),ETRN (W/m^2),GHI (W/m^2),GHI source,GHI uncert (%),DNI (W/m^2),"
    "DNI source,DNI uncert (%),DHI (W/m^2),DHI source,DHI uncert (%),GH illum (lx),GH illum source,"
    "Global illum uncert (%),DN illum (lx),DN illum source,DN illum uncert (%),DH illum (lx),DH illum source,"
    "DH illum uncert (%),Dry-bulb (C),Dry-bulb source,Dry-bulb uncert (code),Dew-point (C),Dew-point source,"
    "Dew-point uncert (code),Alb (unitless),Alb source,Alb uncert (code)\n";

// An EPW record's line as a TMY3 record: EPW fields (1-based) 2, 3, 1 date; 4 hour; 11, 12 ETR,
// ETRN; 14–16 radiation; 17–19 illuminance; 7 dry bulb; 8 dew point; 33 albedo. EPW missing
// codes (999999 lux, 99.9 °C, 999 albedo) become -9900.
inline std::string tmy3_line(const std::string& epw_line) {
  std::vector<std::string> f;
  std::stringstream ss(epw_line);
  for (std::string v; std::getline(ss, v, ',');) f.push_back(v);
  const auto at = [&](int k) { return f[std::size_t(k - 1)]; };
  const auto lux = [&](int k) { return std::stod(at(k)) >= 999900 ? std::string("-9900") : at(k); };
  char date[32];
  std::snprintf(date, sizeof date, "%02d/%02d/%04d,%02d:00", std::stoi(at(2)), std::stoi(at(3)), std::stoi(at(1)),
                std::stoi(at(4)));
  const std::string dew = std::stod(at(8)) >= 99.9 ? "-9900" : at(8);
  const std::string albedo = std::stod(at(33)) >= 999 ? "-9900" : at(33);
  return std::string(date) + "," + at(11) + "," + at(12) + "," + at(14) + ",1,8," + at(15) + ",1,8," + at(16) + ",1,8," +
         lux(17) + ",1,8," + lux(18) + ",1,8," + lux(19) + ",1,8," + at(7) + ",A,7," + dew + ",A,7," + albedo + ",F,8\n";
}

// The whole TMY3 CSV of an EPW file: `site` (the first line: USAF id, name, state, time zone,
// latitude, longitude, elevation), the header, then every record.
inline std::string epw_as_tmy3(const std::string& epw_path, const std::string& site) {
  std::ifstream in(epw_path);
  std::string line, csv = site + kTmy3Header;
  for (int k = 0; std::getline(in, line); ++k)
    if (k >= 8) csv += tmy3_line(line);
  return csv;
}

}  // namespace skyband::test
