#pragma once
// Analytic skies and view directions shared by the specular tests and bench_specular
// (header-only: tests/lighting/support/*.h are not compiled into other suites).
#include <algorithm>
#include <cmath>

#include "geometry/core/vec3.h"
#include "lighting/spectrum/spectrum.h"

namespace skyband::test {

// CIE general sky type 12, the standard clear sky (reference-notes §3.3), relative to its
// zenith-independent normalisation, tinted towards blue at the zenith so that spectral channels
// differ: L(λ, ω) = f(χ)·φ(Z)·(1 + 0.6·(1 − i/40)·cos Z), i the spectral sample index.
inline void clear_sky_radiance(const Vec3& sun, const Vec3& d, Spectrum& out) {
  const double cz = std::max(d.z(), 0.0);
  const double chi = std::acos(std::clamp(d.dot(sun), -1.0, 1.0));
  const double f = 1 + 10 * (std::exp(-3 * chi) - std::exp(-3 * kPi / 2)) + 0.45 * std::cos(chi) * std::cos(chi);
  const double phi = cz > 0 ? 1 - std::exp(-0.32 / cz) : 1.0;
  for (int i = 0; i < kSpectrumSamples; ++i) out[i] = f * phi * (1.0 + 0.6 * (1.0 - i / 40.0) * cz);
}

inline double channel_sum(const Spectrum& s) {
  double t = 0;
  for (double x : s.v) t += x;
  return t;
}

// Unit view direction at polar angle θ from the unit normal n and azimuth φ around it.
inline Vec3 view_at(const Vec3& n, double theta, double phi) {
  const Vec3 t1 = (std::abs(n.z()) < 0.9 ? n.cross(Vec3(0, 0, 1)) : n.cross(Vec3(1, 0, 0))).normalized();
  const Vec3 t2 = n.cross(t1);
  return std::cos(theta) * n + std::sin(theta) * (std::cos(phi) * t1 + std::sin(phi) * t2);
}

}  // namespace skyband::test
