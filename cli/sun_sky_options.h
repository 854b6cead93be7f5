#pragma once
// The sun and sky options shared by `skyband sky` and `skyband irradiance`: the sun from an
// altitude/azimuth or from place and time (NREL SPA), the atmosphere (aerosol, ozone, site
// elevation) and the sky model (physical single/multiple scattering or CIE). Validation in one
// place: every bad value ends in an InputError naming the flag and the value.
//
// Conventions: world x east, y north, z up; azimuth in degrees clockwise from north; sun
// direction = (sin az·cos alt, cos az·cos alt, sin alt); altitudes are apparent (refracted).
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "lighting/sky/sky_model.h"
#include "lighting/sun/sun_position.h"

namespace skyband::cli {

// "%g" of a value, for messages.
std::string fmt(double v);
void require_finite(const char* flag, double v);
void require_range(const char* flag, double v, double lo, double hi, const char* what);

struct SunPlacement {
  double altitude_deg = 0, azimuth_deg = 0;  // apparent altitude; azimuth in [0, 360)
  nlohmann::json source;                     // how it was obtained (for JSON/provenance)
  Vec3 direction() const;                    // unit world direction towards the sun
};

class SunSkyOptions {
 public:
  // Adds --sun-altitude, --sun-azimuth, --lat, --lon, --time, --tz, --elevation, --delta-t,
  // --pressure-mbar, --temperature-c, --aod550, --angstrom-alpha, --ozone-du, --model,
  // --zenith-luminance to `cmd`. The object must outlive the command's callback.
  void add_to(CLI::App* cmd);

  // The sun (throws InputError: no sun given, both ways given, values out of range).
  SunPlacement place_sun() const;
  // True if any of --sun-altitude, --sun-azimuth, --time was given (a single moment).
  bool moment_given() const;
  // The first of all these options that was given on the command line ("" if none).
  std::string first_given() const;
  // The sun at local time `time` (ISO 8601; --tz is the UTC offset of a time without one) at
  // --lat/--lon (required: InputError naming `where` and the missing flag) with the SPA options;
  // `where` prefixes messages (e.g. "times.csv:3").
  SunPlacement sun_at(const std::string& time, const std::string& where) const;
  // The same for a parsed local time (its own UTC offset).
  SunPlacement sun_at(const LocalDateTime& time, const std::string& where) const;
  // --tz when given.
  std::optional<double> utc_offset_given() const;
  // --time parsed (with --tz for a time without an offset); InputError when --time is missing.
  LocalDateTime local_time(const std::string& needed_by) const;
  // Atmosphere parameters (validated) and the sky model spec (validated).
  AtmosphereParams atmosphere() const;
  SkyModelSpec sky_spec() const;

  // The sky model for `sun` (all of the above validated first).
  SkyModel make_sky(const SunPlacement& sun) const { return SkyModel(atmosphere(), sun.direction(), sky_spec()); }

 private:
  double sun_altitude_deg_ = 0, sun_azimuth_deg_ = 180;
  double lat_deg_ = 0, lon_deg_ = 0, elevation_m_ = 0;
  std::string time_;
  double tz_hours_ = 0, delta_t_s_ = 69.0, pressure_mbar_ = 1013.25, temperature_C_ = 15.0;
  double aod550_ = AtmosphereParams{}.aod550;
  double angstrom_alpha_ = AtmosphereParams{}.angstrom_alpha;
  double ozone_du_ = AtmosphereParams{}.ozone_du;
  std::string model_ = "multiple";
  double zenith_luminance_ = 0;
  CLI::Option *o_alt_ = nullptr, *o_az_ = nullptr, *o_lat_ = nullptr, *o_lon_ = nullptr, *o_time_ = nullptr, *o_tz_ = nullptr,
              *o_zl_ = nullptr;
  std::vector<CLI::Option*> all_;
};

}  // namespace skyband::cli
