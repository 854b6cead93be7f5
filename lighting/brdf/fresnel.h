#pragma once
// Fresnel reflectance of a smooth interface for unpolarised light (method.md §5; reference-notes
// §4.1). The argument is cos θ, θ the angle between the incident direction and the (micro)facet
// normal H: in a microfacet BRDF, cos θ = V·H = L·H (Cook & Torrance 1982, "θ = angle between L
// and H").
//
//   fresnel_dielectric  real relative index n (glass, paint, glaze): Cook & Torrance 1982's g/c
//                       form, exact for real n; total internal reflection (g² < 0) gives 1.
//   fresnel_conductor   complex index η = n + ik (metals): the exact amplitude coefficients
//                       r_∥, r_⊥ of the Fresnel equations with complex cos θ_t (Born & Wolf §13.2).
//   FresnelTable        either one sampled on the 41-wavelength grid against cos θ, for the hot
//                       loops of the sky integrals (no complex arithmetic per sample).
#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "lighting/spectrum/spectrum.h"

namespace skyband {

// Cook & Torrance 1982 (ACM TOG 1(1), the appendix formula):
//   F = ½ (g − c)²/(g + c)² · {1 + [c(g + c) − 1]² / [c(g − c) + 1]²},  c = cos θ, g² = n² + c² − 1.
// Domain: cos θ ∈ [0, 1] (clamped), n > 0. Dimensionless.
inline double fresnel_dielectric(double cos_theta, double n) {
  const double c = std::clamp(cos_theta, 0.0, 1.0);
  const double g2 = n * n + c * c - 1.0;
  if (g2 <= 0.0) return 1.0;  // total internal reflection (n < 1 beyond the critical angle)
  const double g = std::sqrt(g2);
  const double a = (g - c) / (g + c);
  const double b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
  return 0.5 * a * a * (1.0 + b * b);
}

// Exact unpolarised reflectance of a conductor with complex relative index η = n + ik:
//   cos θ_t = √(1 − sin²θ/η²) (principal branch),
//   r_∥ = (η cos θ − cos θ_t)/(η cos θ + cos θ_t),  r_⊥ = (cos θ − η cos θ_t)/(cos θ + η cos θ_t),
//   F = (|r_∥|² + |r_⊥|²)/2.
// With k = 0 this is the dielectric formula above. Domain: cos θ ∈ [0, 1] (clamped).
inline double fresnel_conductor(double cos_theta, std::complex<double> eta) {
  const double c = std::clamp(cos_theta, 0.0, 1.0);
  const double sin2 = 1.0 - c * c;
  const std::complex<double> cos_t = std::sqrt(1.0 - sin2 / (eta * eta));
  const std::complex<double> r_par = (eta * c - cos_t) / (eta * c + cos_t);
  const std::complex<double> r_perp = (c - eta * cos_t) / (c + eta * cos_t);
  return 0.5 * (std::norm(r_par) + std::norm(r_perp));
}

// Normal-incidence reflectance of a conductor, ((n − 1)² + k²)/((n + 1)² + k²).
inline double fresnel_conductor_normal(double n, double k) {
  return ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
}

// F(λ, cos θ) tabulated on kNodes equally spaced cos θ ∈ [0, 1] for every wavelength sample and
// interpolated linearly. With 257 nodes the interpolation error is below 10⁻⁴ (aluminium, max
// 3.4·10⁻⁵) and 2·10⁻⁴ (n = 1.5, max 7·10⁻⁵ near grazing), measured in fresnel_test.
class FresnelTable {
 public:
  static constexpr int kNodes = 257;

  // F = 1 everywhere (the white-furnace test's ideal reflector).
  static FresnelTable one() {
    FresnelTable t;
    std::fill(t.f_.begin(), t.f_.end(), 1.0);
    return t;
  }
  static FresnelTable dielectric(double n) {
    FresnelTable t;
    for (int j = 0; j < kNodes; ++j) {
      const double f = fresnel_dielectric(node_cos(j), n);
      for (int i = 0; i < kSpectrumSamples; ++i) t.at(j, i) = f;
    }
    return t;
  }
  static FresnelTable conductor(const Spectrum& n, const Spectrum& k) {
    FresnelTable t;
    for (int j = 0; j < kNodes; ++j)
      for (int i = 0; i < kSpectrumSamples; ++i) t.at(j, i) = fresnel_conductor(node_cos(j), std::complex<double>(n[i], k[i]));
    return t;
  }

  // out(λ) = F(λ, cos θ), cos θ clamped to [0, 1].
  void eval(double cos_theta, Spectrum& out) const {
    const double x = std::clamp(cos_theta, 0.0, 1.0) * (kNodes - 1);
    const int j = std::min(static_cast<int>(x), kNodes - 2);
    const double t = x - j;
    const double* a = &f_[static_cast<std::size_t>(j) * kSpectrumSamples];
    const double* b = a + kSpectrumSamples;
    for (int i = 0; i < kSpectrumSamples; ++i) out[i] = a[i] + t * (b[i] - a[i]);
  }
  Spectrum eval(double cos_theta) const {
    Spectrum s;
    eval(cos_theta, s);
    return s;
  }
  // The tabulated value at node j (cos θ = j/(kNodes − 1)) and wavelength sample i.
  double node_value(int j, int i) const {
    return f_[static_cast<std::size_t>(j) * kSpectrumSamples + static_cast<std::size_t>(i)];
  }

 private:
  FresnelTable() : f_(static_cast<std::size_t>(kNodes) * kSpectrumSamples, 0.0) {}
  static double node_cos(int j) { return static_cast<double>(j) / (kNodes - 1); }
  double& at(int j, int i) { return f_[static_cast<std::size_t>(j) * kSpectrumSamples + static_cast<std::size_t>(i)]; }

  std::vector<double> f_;  // [node][wavelength]
};

}  // namespace skyband
