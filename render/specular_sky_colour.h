#pragma once
// The specular sky integral of specular_sky.h evaluated directly in CIE XYZ, for the renderer.
//
// The renderer keeps only XYZ (→ linear sRGB) of the reflected spectrum I(λ), a linear map, so
//     XYZ_c = Σ_i W_c(λ_i)·I(λ_i) = ∫ dω k(ω) Σ_j U_j(V·H) · [Σ_i W_c(λ_i) V_j(λ_i) L(λ_i, ω)]
// with W_c the CIE weights (colour.h: xyz_weights), k(ω) = w_s f_s/F · sin²α the lobe factor and
// F ≈ Σ_j U_j V_j the Fresnel table's low-rank separation (fresnel_factors.h). The bracket is a
// sky pre-projected onto 3·r spectra (ProjectedSkyGrid), so each direction costs 3·r look-ups
// and r Fresnel values instead of 41 of each. Exact up to the separation's tolerance (10⁻⁴ in F)
// and identical in quadrature to the spectral path: the same march, the same nodes. Only the
// truncation measure G differs: the luminance channel Y of the integrand here, the channel mean
// there (both non-negative measures of the same integrand).
#include <algorithm>
#include <array>
#include <memory>

#include "lighting/brdf/fresnel_factors.h"
#include "lighting/integrals/specular_sky.h"
#include "lighting/sky/sky_radiance_grid.h"
#include "lighting/spectrum/colour.h"

namespace skyband {

// Accumulator of the colour march: channel c·R + j holds XYZ component c through Fresnel
// factor j (R = the Fresnel rank).
template <int N>
struct ColourChannels {
  std::array<double, N> v{};
  ColourChannels& operator+=(const ColourChannels& o) {
    for (int k = 0; k < N; ++k) v[k] += o.v[k];
    return *this;
  }
  friend ColourChannels operator*(ColourChannels a, double s) {
    for (double& x : a.v) x *= s;
    return a;
  }
};

// One specular material under one sky: its Fresnel separation and the sky projected for it.
class ColourSpecularSky {
 public:
  // `fresnel` nullptr: F = 1. The grid is only read during construction.
  ColourSpecularSky(const SkyRadianceGrid& sky, const FresnelTable* fresnel);

  // XYZ (W·m⁻²·sr⁻¹, CIE-weighted) of the ε-truncated specular sky integral toward view_dir.
  // lobe.fresnel must be the table this object was built for (else std::logic_error).
  Xyz radiance_xyz(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                   const SpecularSkyOptions& opt = {}, SpecularSkyStats* stats = nullptr) const;

  int rank() const { return rank_; }

  // Whether radiance_xyz runs the AVX2 + FMA build of the march on this processor (runtime
  // dispatch: results are deterministic on a given machine but may differ in the last bits
  // between machines with and without it, FMA rounding once where the other rounds twice).
  static bool uses_avx2();
  // radiance_xyz on the default (portable) build whatever the processor: for tests and benchmarks.
  Xyz radiance_xyz_portable(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                            const SpecularSkyOptions& opt = {}, SpecularSkyStats* stats = nullptr) const;

  // The reflection policy of specular_sky.h for Fresnel rank R (public for the march template);
  // Avx2: the instantiation of the AVX2 + FMA build (specular_sky.h, lobe_factor3_avx2).
  template <int R, bool Avx2 = false>
  struct Policy {
    using Value = ColourChannels<3 * R>;
    static constexpr bool kAvx2 = Avx2;
    const ColourSpecularSky* self;
#if SKYBAND_LOBE_AVX2
    // eval for the three Gauss–Legendre nodes of a piece at once (the AVX2 build only):
    // w_n = cos_a[n]·x + sin_a[n]·u (unit), its grid cell as sky_grid_cell_unit computes it, in
    // AVX2 lanes; then per node with k[n] > 0 the bilinear look-up and the Fresnel factors as in
    // eval (out[n], g[n] set only for those nodes).
    __attribute__((target("avx2,fma"))) void eval3(const double (&cos_a)[3], const double (&sin_a)[3], const Vec3& x,
                                                   const Vec3& u, const double (&v_dot_h)[3], const double (&k)[3],
                                                   Value (&out)[3], double (&g)[3]) const {
      const __m256d c = _mm256_setr_pd(cos_a[0], cos_a[1], cos_a[2], cos_a[2]);
      const __m256d s = _mm256_setr_pd(sin_a[0], sin_a[1], sin_a[2], sin_a[2]);
      const __m256d wx = _mm256_add_pd(_mm256_mul_pd(c, _mm256_set1_pd(x.x())), _mm256_mul_pd(s, _mm256_set1_pd(u.x())));
      const __m256d wy = _mm256_add_pd(_mm256_mul_pd(c, _mm256_set1_pd(x.y())), _mm256_mul_pd(s, _mm256_set1_pd(u.y())));
      const __m256d wz = _mm256_add_pd(_mm256_mul_pd(c, _mm256_set1_pd(x.z())), _mm256_mul_pd(s, _mm256_set1_pd(u.z())));
      const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
      const __m256d above = _mm256_cmp_pd(wz, zero, _CMP_GT_OQ);  // ω_z > 0 (false for NaN)
      const __m256d half = _mm256_set1_pd(0.5 * kSkyGridCells);
      const __m256d kk = _mm256_div_pd(half, _mm256_add_pd(one, _mm256_blendv_pd(zero, wz, above)));
      const __m256d uu = _mm256_max_pd(_mm256_add_pd(_mm256_mul_pd(wx, kk), half), zero);
      const __m256d vv = _mm256_max_pd(_mm256_add_pd(_mm256_mul_pd(wy, kk), half), zero);
      const __m128i last = _mm_set1_epi32(kSkyGridCells - 1);
      const __m128i ix = _mm_min_epi32(_mm256_cvttpd_epi32(uu), last), iy = _mm_min_epi32(_mm256_cvttpd_epi32(vv), last);
      const __m256d fx = _mm256_sub_pd(uu, _mm256_cvtepi32_pd(ix)), fy = _mm256_sub_pd(vv, _mm256_cvtepi32_pd(iy));
      alignas(32) double fxs[4], fys[4];
      alignas(16) int ixs[4], iys[4];
      _mm256_store_pd(fxs, fx);
      _mm256_store_pd(fys, fy);
      _mm_store_si128(reinterpret_cast<__m128i*>(ixs), ix);
      _mm_store_si128(reinterpret_cast<__m128i*>(iys), iy);
      const int up = _mm256_movemask_pd(above);
      for (int n = 0; n < 3; ++n) {
        if (!(k[n] > 0.0)) continue;
        double l[3 * R];
        if (up >> n & 1) {
          self->grid_.template lookup_cell_n<3 * R>(ixs[n], iys[n], fxs[n], fys[n], l);
        } else {
          for (int i = 0; i < 3 * R; ++i) l[i] = 0.0;
        }
        g[n] = combine(l, v_dot_h[n], k[n], out[n]);
      }
    }
#endif
    // w: unit (the march's directions are).
    double eval(const Vec3& w, double v_dot_h, double k, Value& out) const {
      double l[3 * R];
      self->grid_.template lookup_unit_n<3 * R>(w, l);
      return combine(l, v_dot_h, k, out);
    }
    // out = k·U(cos θ)·l channel by channel; returns the luminance channel Σ_j of component Y, ≥ 0.
    double combine(const double* l, double cos_theta, double k, Value& out) const {
      double u[FresnelFactors::kMaxRank] = {1.0, 1.0, 1.0, 1.0};
      if (self->factors_) self->factors_->u(cos_theta, u);
      for (int c = 0; c < 3; ++c)
        for (int j = 0; j < R; ++j) out.v[c * R + j] = k * u[j] * l[c * R + j];
      double y = 0;
      for (int j = 0; j < R; ++j) y += out.v[R + j];
      return std::max(y, 0.0);
    }
    void mirror(const Vec3& q, double n_dot_v, double weight, Value& out) const {
      eval(q, n_dot_v, weight, out);
    }
    double measure(const Value& x) const {
      double y = 0;
      for (int j = 0; j < R; ++j) y += x.v[R + j];
      return std::abs(y);
    }
  };

 private:
  template <int R>
  Xyz integrate(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe, const SpecularSkyOptions& opt,
                SpecularSkyStats& stats) const;
  // The same march compiled for AVX2 + FMA (specular_sky_colour.cpp), used when the processor
  // has them (checked once at run time).
  template <int R>
  Xyz integrate_avx2(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                     const SpecularSkyOptions& opt, SpecularSkyStats& stats) const;
  Xyz dispatch(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe, const SpecularSkyOptions& opt,
               SpecularSkyStats* stats_out, bool avx2) const;

  const FresnelTable* fresnel_ = nullptr;
  std::shared_ptr<const FresnelFactors> factors_;  // nullptr: F = 1
  ProjectedSkyGrid grid_;
  int rank_ = 1;
};

}  // namespace skyband
