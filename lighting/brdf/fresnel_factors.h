#pragma once
// Low-rank separation of a spectral Fresnel table (fresnel.h) into functions of the angle times
// functions of the wavelength:
//     F(λ_i, cos θ) ≈ Σ_{j<r} U_j(cos θ)·V_j(λ_i),
// the truncated singular value decomposition of the table's 257 × 41 matrix (Eckart–Young: the
// best rank-r approximation), with r the smallest rank whose largest absolute deviation from the
// table is ≤ the tolerance. A dielectric with a real, wavelength-independent index (and F = 1)
// is exactly rank 1 (deviation ~10⁻¹⁵); aluminium's F needs rank 4 for the default 5·10⁻⁴
// (max deviation 2.7·10⁻⁴ where its reflectance dips near grazing incidence; rank 2: 1.6·10⁻²,
// rank 3: 2.6·10⁻³), measured in fresnel_factors_test. Against F ≈ 0.9 that is 3·10⁻⁴ relative.
//
// Why: the sky integrals weight the sky spectrum by F at every direction. With the separation,
// any linear projection P of the reflected spectrum (e.g. onto the CIE XYZ weights) becomes
//     P[F·L] = Σ_j U_j(cos θ)·P[V_j·L],
// so a sky pre-projected onto the r·3 spectra V_j·x̄, V_j·ȳ, V_j·z̄ and r scalar tables U_j
// replace 41 Fresnel values and 41 radiances per direction (specular_sky_colour.h).
#include <algorithm>
#include <array>
#include <vector>

#include "lighting/brdf/fresnel.h"
#include "lighting/spectrum/spectrum.h"

namespace skyband {

class FresnelFactors {
 public:
  static constexpr int kMaxRank = 4;

  // Throws std::invalid_argument when no rank ≤ kMaxRank meets `max_abs_error` (> 0).
  explicit FresnelFactors(const FresnelTable& table, double max_abs_error = 5e-4);

  int rank() const { return rank_; }
  double max_abs_error() const { return max_error_; }  // measured over every table entry
  const Spectrum& v(int j) const { return v_[static_cast<std::size_t>(j)]; }
  // out[j] = U_j(cos θ), j < rank, cos θ clamped to [0, 1] (linear between the table's nodes).
  void u(double cos_theta, double* out) const {
    const double x = std::clamp(cos_theta, 0.0, 1.0) * (FresnelTable::kNodes - 1);
    const int n = std::min(static_cast<int>(x), FresnelTable::kNodes - 2);
    const double t = x - n;
    const double* a = &u_[static_cast<std::size_t>(n) * kMaxRank];
    const double* b = a + kMaxRank;
    for (int j = 0; j < kMaxRank; ++j) out[j] = a[j] + t * (b[j] - a[j]);
  }

 private:
  int rank_ = 0;
  double max_error_ = 0;
  std::array<Spectrum, kMaxRank> v_{};
  std::vector<double> u_;  // [node][kMaxRank], zero beyond rank
};

}  // namespace skyband
