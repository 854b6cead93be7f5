// Sun and sky options shared by the sky and irradiance commands (sun_sky_options.h).
#include "cli/sun_sky_options.h"

#include <cmath>
#include <cstdio>
#include <optional>

#include "geometry/core/input_error.h"
#include "lighting/sun/sun.h"
#include "lighting/sun/sun_position.h"

namespace skyband::cli {

namespace {
constexpr double kDeg = kPi / 180.0;
}  // namespace

std::string fmt(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

void require_finite(const char* flag, double v) {
  if (!std::isfinite(v)) throw InputError(std::string(flag) + " " + fmt(v) + ": not a finite number");
}

void require_range(const char* flag, double v, double lo, double hi, const char* what) {
  require_finite(flag, v);
  if (v < lo || v > hi) throw InputError(std::string(flag) + " " + fmt(v) + ": " + what);
}

Vec3 SunPlacement::direction() const {
  return direction_from_altitude_azimuth(altitude_deg * kDeg, azimuth_deg * kDeg);
}

void SunSkyOptions::add_to(CLI::App* sub) {
  const auto add = [&](CLI::Option* o) {
    all_.push_back(o);
    return o;
  };
  o_alt_ = add(sub->add_option("--sun-altitude", sun_altitude_deg_, "Apparent sun altitude, degrees [-90, 90]"));
  o_az_ =
      add(sub->add_option("--sun-azimuth", sun_azimuth_deg_, "Sun azimuth, degrees clockwise from north (default 180 = south)"));
  o_lat_ = add(sub->add_option("--lat", lat_deg_, "Latitude, degrees north (with --lon, --time: NREL SPA)"));
  o_lon_ = add(sub->add_option("--lon", lon_deg_, "Longitude, degrees east"));
  o_time_ =
      add(sub->add_option("--time", time_, "Local time, ISO 8601: 2026-06-21T12:00:00+02:00, ...Z, or without offset plus --tz"));
  o_tz_ = add(sub->add_option("--tz", tz_hours_, "UTC offset of --time in hours (east positive), when --time has none"));
  add(sub->add_option("--elevation", elevation_m_,
                      "Site elevation above sea level, metres (SPA parallax and atmosphere ground)"));
  add(sub->add_option("--delta-t", delta_t_s_, "Delta T = TT - UT1, seconds (default 69)"));
  add(sub->add_option("--pressure-mbar", pressure_mbar_, "Mean local pressure for SPA refraction, mbar (default 1013.25)"));
  add(sub->add_option("--temperature-c", temperature_C_, "Mean local temperature for SPA refraction, deg C (default 15)"));
  add(sub->add_option("--aod550", aod550_, "Aerosol optical depth at 550 nm (default 0.1)"));
  add(sub->add_option("--angstrom-alpha", angstrom_alpha_, "Angstrom exponent (default 1.3)"));
  add(sub->add_option("--ozone-du", ozone_du_, "Ozone column, Dobson units (default 300)"));
  add(sub->add_option("--model", model_, "Sky model: single | multiple | cie-1 ... cie-15 | cie-overcast (default multiple)"));
  o_zl_ = add(sub->add_option("--zenith-luminance", zenith_luminance_,
                              "CIE skies: zenith luminance cd/m2 (default gensky-style formula)"));
}

SunPlacement SunSkyOptions::place_sun() const {
  const bool by_angle = o_alt_->count() > 0 || o_az_->count() > 0;
  const bool by_place = o_lat_->count() > 0 || o_lon_->count() > 0 || o_time_->count() > 0 || o_tz_->count() > 0;
  if (by_angle && by_place) throw InputError("give either --sun-altitude [--sun-azimuth] or --lat --lon --time, not both");
  if (by_angle) {
    if (o_alt_->count() == 0) throw InputError("--sun-azimuth needs --sun-altitude");
    require_range("--sun-altitude", sun_altitude_deg_, -90.0, 90.0, "altitude must be in [-90, 90] degrees");
    require_range("--sun-azimuth", sun_azimuth_deg_, -360.0, 360.0,
                  "azimuth must be in [-360, 360] degrees (clockwise from north)");
    double az = std::fmod(sun_azimuth_deg_, 360.0);
    if (az < 0) az += 360.0;
    return {sun_altitude_deg_, az, {{"method", "given"}}};
  }
  if (!by_place) throw InputError("no sun: give --sun-altitude DEG [--sun-azimuth DEG] or --lat DEG --lon DEG --time ISO8601");
  if (o_lat_->count() == 0 || o_lon_->count() == 0 || o_time_->count() == 0)
    throw InputError("sun from place and time needs all of --lat, --lon and --time");
  return sun_at(time_, "--time");
}

std::string SunSkyOptions::first_given() const {
  for (const CLI::Option* o : all_)
    if (o->count() > 0) return o->get_name();
  return "";
}

bool SunSkyOptions::moment_given() const {
  return o_alt_->count() > 0 || o_az_->count() > 0 || o_time_->count() > 0;
}

SunPlacement SunSkyOptions::sun_at(const std::string& time, const std::string& where) const {
  if (o_lat_->count() == 0 || o_lon_->count() == 0) throw InputError(where + ": a sun from a time needs --lat and --lon");
  require_range("--tz", tz_hours_, -18.0, 18.0, "UTC offset must be in [-18, 18] hours");
  SunPlacement p = sun_at(parse_iso8601(time, where, o_tz_->count() ? std::optional<double>(tz_hours_) : std::nullopt), where);
  p.source["time"] = time;
  return p;
}

LocalDateTime SunSkyOptions::local_time(const std::string& needed_by) const {
  if (o_time_->count() == 0) throw InputError(needed_by + " needs --time (its date, with --lat and --lon)");
  return parse_iso8601(time_, "--time", utc_offset_given());
}

std::optional<double> SunSkyOptions::utc_offset_given() const {
  return o_tz_->count() ? std::optional<double>(tz_hours_) : std::nullopt;
}

SunPlacement SunSkyOptions::sun_at(const LocalDateTime& time, const std::string& where) const {
  if (o_lat_->count() == 0 || o_lon_->count() == 0) throw InputError(where + ": a sun from a time needs --lat and --lon");
  require_range("--lat", lat_deg_, -90.0, 90.0, "latitude must be in [-90, 90] degrees");
  require_range("--lon", lon_deg_, -180.0, 180.0, "longitude must be in [-180, 180] degrees (east positive)");
  require_range("--delta-t", delta_t_s_, -8000.0, 8000.0, "ΔT must be in [-8000, 8000] s");
  require_range("--pressure-mbar", pressure_mbar_, 1e-3, 5000.0, "pressure must be in (0, 5000] mbar");
  require_range("--temperature-c", temperature_C_, -272.0, 6000.0, "temperature must be above -273 °C");
  SpaInput in;
  in.latitude_deg = lat_deg_;
  in.longitude_deg = lon_deg_;
  in.elevation_m = elevation_m_;
  in.time = time;
  in.delta_t_s = delta_t_s_;
  in.pressure_mbar = pressure_mbar_;
  in.temperature_C = temperature_C_;
  const SpaResult r = sun_position_spa(in);
  nlohmann::json src = {{"method", "NREL SPA (Reda & Andreas 2004)"},
                        {"latitude_deg", lat_deg_},
                        {"longitude_deg", lon_deg_},
                        {"elevation_m", elevation_m_},
                        {"utc_offset_hours", in.time.utc_offset_hours},
                        {"delta_t_s", delta_t_s_},
                        {"julian_day", r.julian_day},
                        {"zenith_deg_refracted", r.zenith_deg},
                        {"declination_deg", r.topocentric_declination_deg}};
  return {90.0 - r.zenith_deg, r.azimuth_deg, src};
}

AtmosphereParams SunSkyOptions::atmosphere() const {
  AtmosphereParams ap;
  require_finite("--aod550", aod550_);
  require_finite("--angstrom-alpha", angstrom_alpha_);
  require_finite("--ozone-du", ozone_du_);
  require_finite("--elevation", elevation_m_);
  if (aod550_ < 0) throw InputError("--aod550 " + fmt(aod550_) + ": optical depth must be >= 0");
  if (ozone_du_ < 0) throw InputError("--ozone-du " + fmt(ozone_du_) + ": ozone column must be >= 0");
  ap.aod550 = aod550_;
  ap.angstrom_alpha = angstrom_alpha_;
  ap.ozone_du = ozone_du_;
  ap.ground_elevation_m = elevation_m_;
  try {
    ap.validate();
  } catch (const InputError& e) {
    throw InputError(std::string("atmosphere (--aod550/--angstrom-alpha/--ozone-du/--elevation): ") + e.what());
  }
  return ap;
}

SkyModelSpec SunSkyOptions::sky_spec() const {
  SkyModelSpec spec = parse_sky_model(model_, "--model");
  if (o_zl_->count()) {
    if (spec.physical) throw InputError("--zenith-luminance applies to CIE skies only, not --model " + model_);
    require_range("--zenith-luminance", zenith_luminance_, 0.0, 1e7, "zenith luminance must be in [0, 1e7] cd/m2");
    spec.zenith_luminance_cd_m2 = zenith_luminance_;
  }
  return spec;
}

}  // namespace skyband::cli
