#pragma once
// The sun as seen from the ground: disc size, atmospheric refraction, direction from
// altitude/azimuth. Sun *position* (date, place → altitude/azimuth) lives elsewhere (SPA).
//
// Conventions (everywhere in skyband): world x east, y north, z up; azimuth in radians measured
// clockwise from north (east = +π/2); altitude above the horizon in radians.
// "True" altitude is geometric (no atmosphere); "apparent" is where the sun is seen, raised by
// refraction. Refraction is not traced through the shell: the atmosphere model uses straight rays
// along the apparent direction, which gives the air mass along the actually observed direction
// to within the bending of the path (a few % of the slant column at the horizon, far less above
// 4°).
#include <cmath>

#include "geometry/core/vec3.h"

namespace skyband {

// Mean angular radius of the solar disc: 959.6″ at 1 AU = 0.2666° = 4.653e-3 rad
// (Astronomical Almanac semidiameter; varies ±1.7% over the year).
inline constexpr double kSunAngularRadius_rad = 0.2666 * kPi / 180.0;
// Solid angle of the disc, sr: 2π(1 − cos r) ≈ 6.80e-5 sr.
inline const double kSunSolidAngle_sr = 2.0 * kPi * (1.0 - std::cos(kSunAngularRadius_rad));

// Unit direction towards altitude/azimuth: (sin az·cos alt, cos az·cos alt, sin alt).
inline Vec3 direction_from_altitude_azimuth(double altitude_rad, double azimuth_rad) {
  return {std::sin(azimuth_rad) * std::cos(altitude_rad), std::cos(azimuth_rad) * std::cos(altitude_rad), std::sin(altitude_rad)};
}
// Inverse of direction_from_altitude_azimuth for a unit vector; azimuth in [0, 2π).
double altitude_of(const Vec3& dir);
double azimuth_of(const Vec3& dir);

// Atmospheric refraction R = apparent − true altitude, radians, from the TRUE altitude:
// Sæmundsson (1986), R[arcmin] = 1.02 / tan(h + 10.3/(h + 5.11)), h in degrees, for 1010 hPa and
// 10 °C (Meeus, Astronomical Algorithms, eq. 16.4). 28.9′ at h = 0; for h < −1° (sun well below
// the horizon) it is evaluated at −1°, where the formula stops being meaningful; 0 at the zenith
// to within 0.002′ (the formula's own offset is removed so R(90°) = 0 exactly).
double refraction_rad(double true_altitude_rad);
// Refraction from the APPARENT altitude: Bennett (1982), R[arcmin] = 1/tan(h0 + 7.31/(h0 + 4.4))
// (Meeus eq. 16.3), 34.5′ at h0 = 0; accurate to 0.07′ for 0–90°. Same clamp and zenith offset.
double refraction_from_apparent_rad(double apparent_altitude_rad);
inline double apparent_altitude_rad(double true_altitude_rad) {
  return true_altitude_rad + refraction_rad(true_altitude_rad);
}
inline double true_altitude_rad(double apparent_altitude) {
  return apparent_altitude - refraction_from_apparent_rad(apparent_altitude);
}

}  // namespace skyband
