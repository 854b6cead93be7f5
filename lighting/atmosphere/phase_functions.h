#pragma once
// Scattering phase functions, normalised over the sphere: ∫ p(μ) dω = 1 (unit sr⁻¹), μ = cos of
// the scattering angle (angle between the propagation directions, so μ = 1 is forward).
// Source: reference-notes §2.4 (Bruneton atmosphere/functions.glsl; Blender sky_nishita.cpp).
#include "geometry/core/vec3.h"

namespace skyband {

// Rayleigh: p_R(μ) = 3/(16π)·(1 + μ²)   (Chandrasekhar 1950; Nishita et al. 1993 F(θ)/4π).
inline double rayleigh_phase(double mu) {
  return 3.0 / (16.0 * kPi) * (1.0 + mu * mu);
}

// Cornette & Shanks (1992) eq. 4: p_CS(μ) = 3/(8π)·(1−g²)/(2+g²)·(1+μ²)/(1+g²−2gμ)^{3/2}.
// Its mean cosine is not g (0.810 at g = 0.76, reference-notes §2.4). Valid for |g| < 1.
inline double cornette_shanks_phase(double mu, double g) {
  const double g2 = g * g;
  const double denom = 1.0 + g2 - 2.0 * g * mu;
  return 3.0 / (8.0 * kPi) * (1.0 - g2) / (2.0 + g2) * (1.0 + mu * mu) / (denom * std::sqrt(denom));
}

// Henyey & Greenstein (1941): p_HG(μ) = (1−g²)/(4π(1+g²−2gμ)^{3/2}); mean cosine g.
inline double henyey_greenstein_phase(double mu, double g) {
  const double g2 = g * g;
  const double denom = 1.0 + g2 - 2.0 * g * mu;
  return (1.0 - g2) / (4.0 * kPi * denom * std::sqrt(denom));
}

// Isotropic: 1/(4π).
inline constexpr double kIsotropicPhase = 1.0 / (4.0 * kPi);

}  // namespace skyband
