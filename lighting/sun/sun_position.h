#pragma once
// Sun position: the NREL Solar Position Algorithm (SPA) of I. Reda & A. Andreas, "Solar position
// algorithm for solar radiation applications", Solar Energy 76(5) 577–589 (2004), corrigendum
// Solar Energy 81 (2007) 838, and NREL/TP-560-34302 (rev. 2008). Implemented from the paper's
// description, equations (numbered as in section 3 of the paper) and its tables A4.2 (Earth
// periodic terms, VSOP87 truncated) and A4.3 (nutation terms). Stated uncertainty ±0.0003° for
// years −2000…6000.
//
// Conventions (everywhere in skyband): world x east, y north, z up; azimuth in degrees clockwise
// from north (0 = N, 90 = E); the sun direction is
//   dir = (sin az·cos alt, cos az·cos alt, sin alt),   alt = 90° − zenith.
// Time: a local civil date-time plus its offset from UTC in hours (east positive, e.g. +2 for
// CEST); ΔT = TT − UT1 in seconds.
#include <optional>
#include <string>
#include <string_view>

#include "geometry/core/vec3.h"

namespace skyband {

struct LocalDateTime {
  int year = 2000, month = 1, day = 1, hour = 0, minute = 0;
  double second = 0;
  double utc_offset_hours = 0;  // local time − UTC (hours), east positive
};

// Parses an ISO-8601 date-time "YYYY-MM-DDThh:mm[:ss[.fff]]" followed by "Z", "±hh:mm", "±hhmm"
// or "±hh" (a space may replace the 'T'). When the text carries no offset, `utc_offset_hours`
// supplies it (the CLI's --tz); when it carries one and an explicit offset is also given, they
// must agree. Anything that does not parse, an impossible date or time, or a missing offset
// throws InputError naming `flag` and the text.
LocalDateTime parse_iso8601(std::string_view text, std::string_view flag, std::optional<double> utc_offset_hours = std::nullopt);

struct SpaInput {
  double latitude_deg = 0;   // geodetic, north positive, [−90, 90]
  double longitude_deg = 0;  // east positive, [−180, 180]
  double elevation_m = 0;    // above mean sea level
  LocalDateTime time;
  double delta_t_s = 69.0;               // TT − UT1 (s); ~69 s in the 2020s (IERS)
  double pressure_mbar = 1013.25;        // annual mean local pressure, for refraction
  double temperature_C = 15.0;           // annual mean local temperature, for refraction
  double atmos_refraction_deg = 0.5667;  // refraction at sunrise/sunset (SPA's default)
};

// Intermediate and final quantities of the SPA (degrees unless named otherwise), so that tests
// can check them against the paper's worked example (Table A5.2).
struct SpaResult {
  double julian_day = 0;
  double heliocentric_longitude_deg = 0;       // L (eq. 9–12)
  double heliocentric_latitude_deg = 0;        // B
  double earth_radius_au = 0;                  // R
  double nutation_longitude_deg = 0;           // Δψ (eq. 22)
  double nutation_obliquity_deg = 0;           // Δε (eq. 23)
  double true_obliquity_deg = 0;               // ε (eq. 25)
  double apparent_longitude_deg = 0;           // λ (eq. 27)
  double right_ascension_deg = 0;              // α (eq. 31)
  double declination_deg = 0;                  // δ (eq. 32)
  double hour_angle_deg = 0;                   // H (eq. 33)
  double topocentric_right_ascension_deg = 0;  // α′ (eq. 38)
  double topocentric_declination_deg = 0;      // δ′ (eq. 39)
  double topocentric_hour_angle_deg = 0;       // H′ (eq. 40)
  double elevation_no_refraction_deg = 0;      // e0 (eq. 41)
  double refraction_correction_deg = 0;        // Δe (eq. 42)
  double zenith_deg = 0;                       // θ (eq. 44), topocentric, refracted
  double azimuth_deg = 0;                      // Φ (eq. 46), clockwise from north, [0, 360)
};

// Throws InputError for parameters outside the SPA's domain (latitude, longitude, year
// −2000…6000, pressure, temperature, |ΔT| ≤ 8000 s, refraction), naming the field and value.
SpaResult sun_position_spa(const SpaInput& in);

// Incidence angle (degrees) of the sun on a surface tilted `slope_deg` from horizontal whose
// azimuth rotation `azm_rotation_deg` is measured from SOUTH, positive towards west (the SPA's
// own convention, eq. 47): cos I = cos θ cos ω + sin ω sin θ cos(Γ − γ), Γ = azimuth − 180°.
double surface_incidence_deg(const SpaResult& sun, double slope_deg, double azm_rotation_deg);

// Julian day (UT) of a local date-time (SPA eq. 4, Gregorian from 1582-10-15).
double julian_day(const LocalDateTime& t);

// World direction of a point on the sky from altitude/azimuth in degrees (convention above).
Vec3 direction_from_altitude_azimuth_deg(double altitude_deg, double azimuth_deg);

}  // namespace skyband
