#pragma once
// A sun model independent of the SPA (lighting/sun/sun_position.h), for tests that build weather
// from a known sun (header-only: tests/lighting/support/*.h are not compiled into other suites).
#include <cmath>

#include "geometry/core/vec3.h"

namespace skyband::test {

// cos(zenith) of the sun from Spencer's (1971) Fourier series for the declination and the
// equation of time, as given by Iqbal, "An Introduction to Solar Radiation" (1983), eqs. 1.3.1
// and 1.4.1 (stated maximum errors 0.0006 rad in declination and about 35 s in the equation of
// time), and the hour angle of local apparent solar time. No refraction. `n` is the day of the
// year (1 = January 1), `t_h` local standard time in hours.
inline double spencer_cos_zenith(double latitude_deg, double longitude_deg, double time_zone_h, int n, double t_h) {
  const double g = 2 * kPi * (n - 1 + (t_h - 12) / 24) / 365;  // day angle, at the instant
  const double declination = 0.006918 - 0.399912 * std::cos(g) + 0.070257 * std::sin(g) - 0.006758 * std::cos(2 * g) +
                             0.000907 * std::sin(2 * g) - 0.002697 * std::cos(3 * g) + 0.00148 * std::sin(3 * g);
  const double eot_min = 229.18 * (0.000075 + 0.001868 * std::cos(g) - 0.032077 * std::sin(g) - 0.014615 * std::cos(2 * g) -
                                   0.040849 * std::sin(2 * g));
  const double solar_h = t_h + (longitude_deg - 15 * time_zone_h) / 15 + eot_min / 60;
  const double omega = (solar_h - 12) * 15 * kPi / 180;
  const double phi = latitude_deg * kPi / 180;
  return std::sin(phi) * std::sin(declination) + std::cos(phi) * std::cos(declination) * std::cos(omega);
}

}  // namespace skyband::test
