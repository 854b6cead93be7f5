#pragma once
// The Cook–Torrance lobe factor k(ω) of the specular sky march (specular_sky.h), scalar and, in
// code compiled for AVX2 + FMA, four directions at a time: the march's innermost evaluation.
#include <cmath>

#include "lighting/brdf/cook_torrance.h"
#include "lighting/integrals/fast_exp.h"

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif

namespace skyband::specular_detail {

// The constants of the lobe factor k(ω) = w_s·D_n(N·H)·G/(4(N·L)(N·V)) (×4 with paper_scale;
// cook_torrance.h, beckmann.h) at one point: everything that does not depend on ω.
struct LobeConstants {
  double inv_m2 = 0;  // 1/m²
  double scale = 0;   // w_s·(paper_scale ? 4 : 1)/(4·π·m²·(N·V)): D_n's 1/(π m²), f_s's 1/(4 N·V)
  double n_dot_v = 0;
};
LobeConstants lobe_constants(const SpecularLobe& lobe, double n_dot_v);

// k(ω) of SpecularLobe::factor_fast for a unit direction L = ω from its cosines N·L and V·L
// alone (unit N, V; N·V > 0 in `k`). With a = 1 + V·L = |L + V|²/2 and b = N·L + N·V
// (= |L + V|·N·H), H = (L + V)/|L + V|:
//     1/cos²θ_h = |L + V|²/b² = 2a/b²,   V·H = a/|L + V| = √(a/2),
//     D_n = e^{−x}/(π m² cos⁴θ_h),  x = tan²θ_h/m² = (1/cos²θ_h − 1)/m²             (Beckmann),
//     G/(N·L) = min{V·H, 2(N·H)·min(N·V, N·L)}/((V·H)(N·L))
//             = min{a, 2b·min(N·V, N·L)}/(a·N·L)        (|L + V| cancels)     (Cook–Torrance),
// the same formulas as cook_torrance_lobe_with with one division (r = 1/(b²·a·N·L) serves both
// quotients: 1/b² = r·a·N·L, 1/(a·N·L) = r·b²) and one square root (V·H, for the Fresnel
// factor). 0 where the BRDF is 0 (L or V at or below the surface, L = −V, N·H ≤ 0);
// *exponent = x where N·H > 0 (else untouched); *v_dot_h = V·H. (specular_sky_test checks it
// against cook_torrance_lobe.)
inline double lobe_factor(const LobeConstants& k, double n_dot_l, double v_dot_l, double& v_dot_h, double* exponent = nullptr) {
  if (!(n_dot_l > 0.0)) return 0.0;
  const double a = 1.0 + v_dot_l;
  const double b = n_dot_l + k.n_dot_v;
  if (!(a > 0.0) || !(b > 0.0)) return 0.0;
  v_dot_h = std::sqrt(0.5 * a);
  const double b2 = b * b;
  const double r = 1.0 / (b2 * a * n_dot_l);
  const double inv_c2 = 2.0 * a * (r * a * n_dot_l);
  const double x = std::max(inv_c2 - 1.0, 0.0) * k.inv_m2;  // ≥ 0 (rounding near the peak)
  if (exponent) *exponent = x;
  const double g_over_nl = std::min(a, 2.0 * b * std::min(k.n_dot_v, n_dot_l)) * (r * b2);
  return k.scale * exp_neg(x) * inv_c2 * inv_c2 * g_over_nl;
}

#if defined(__GNUC__) && defined(__x86_64__)
#define SKYBAND_LOBE_AVX2 1
// lobe_factor for three directions at once in the four lanes of AVX2 registers (the fourth lane
// a copy of the third): the same formulas in the same order, e^{−x} by exp_neg's table (a
// gather) and polynomial. Lanes whose x leaves exp_neg's table range [0, 64) are recomputed by
// the scalar lobe_factor (std::exp). k[n] = factor·sin²α_n; x[n] set where the factor's
// N·H > 0 (else left untouched), v_dot_h[n] where the factor is positive. Only called from code
// compiled for AVX2 + FMA (ColourSpecularSky's dispatched build); specular_sky_colour_test
// compares that build with the portable one.
__attribute__((target("avx2,fma"))) inline void lobe_factor3_avx2(const LobeConstants& lk, const double (&n_dot_l)[3],
                                                                  const double (&v_dot_l)[3], const double (&sin_a)[3],
                                                                  double (&k)[3], double (&v_dot_h)[3], double (&x)[3]) {
  using namespace fast_exp_detail;
  const __m256d nl = _mm256_setr_pd(n_dot_l[0], n_dot_l[1], n_dot_l[2], n_dot_l[2]);
  const __m256d vl = _mm256_setr_pd(v_dot_l[0], v_dot_l[1], v_dot_l[2], v_dot_l[2]);
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0), two = _mm256_set1_pd(2.0);
  const __m256d a = _mm256_add_pd(one, vl);
  const __m256d b = _mm256_add_pd(nl, _mm256_set1_pd(lk.n_dot_v));
  // N·L > 0, a > 0, b > 0 (ordered compares: false for NaN, as the scalar tests)
  const __m256d valid = _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(nl, zero, _CMP_GT_OQ), _mm256_cmp_pd(a, zero, _CMP_GT_OQ)),
                                      _mm256_cmp_pd(b, zero, _CMP_GT_OQ));
  const __m256d as = _mm256_blendv_pd(one, a, valid), bs = _mm256_blendv_pd(one, b, valid);
  const __m256d nls = _mm256_blendv_pd(one, nl, valid);
  const __m256d vh = _mm256_sqrt_pd(_mm256_mul_pd(_mm256_set1_pd(0.5), as));
  const __m256d b2 = _mm256_mul_pd(bs, bs);
  const __m256d r = _mm256_div_pd(one, _mm256_mul_pd(_mm256_mul_pd(b2, as), nls));
  const __m256d inv_c2 = _mm256_mul_pd(_mm256_mul_pd(two, as), _mm256_mul_pd(_mm256_mul_pd(r, as), nls));
  const __m256d xv = _mm256_mul_pd(_mm256_max_pd(_mm256_sub_pd(inv_c2, one), zero), _mm256_set1_pd(lk.inv_m2));
  const __m256d gnl =
      _mm256_mul_pd(_mm256_min_pd(as, _mm256_mul_pd(_mm256_mul_pd(two, bs), _mm256_min_pd(_mm256_set1_pd(lk.n_dot_v), nls))),
                    _mm256_mul_pd(r, b2));
  // exp_neg: e^{−j/64} from the table times the degree-4 Taylor polynomial of e^{−f}.
  const __m256d in_range = _mm256_cmp_pd(xv, _mm256_set1_pd(static_cast<double>(kEntries - 1) / kSteps), _CMP_LT_OQ);
  const __m256d xs = _mm256_blendv_pd(zero, xv, in_range);
  const __m256d sx = _mm256_mul_pd(xs, _mm256_set1_pd(static_cast<double>(kSteps)));
  const __m128i j = _mm256_cvttpd_epi32(sx);
  const __m256d f = _mm256_div_pd(_mm256_sub_pd(sx, _mm256_cvtepi32_pd(j)), _mm256_set1_pd(static_cast<double>(kSteps)));
  __m256d poly = _mm256_sub_pd(_mm256_set1_pd(1.0 / 6.0), _mm256_mul_pd(f, _mm256_set1_pd(1.0 / 24.0)));
  poly = _mm256_sub_pd(_mm256_set1_pd(0.5), _mm256_mul_pd(f, poly));
  poly = _mm256_sub_pd(one, _mm256_mul_pd(f, poly));
  poly = _mm256_sub_pd(one, _mm256_mul_pd(f, poly));
  // The masked gather with an explicit zero source and an all-ones mask is the plain gather;
  // GCC 12's _mm256_i32gather_pd leaves its source uninitialised and warns (-Wmaybe-uninitialized).
  const __m256d all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
  const __m256d e = _mm256_mul_pd(_mm256_mask_i32gather_pd(zero, table().data(), j, all, 8), poly);
  const __m256d s = _mm256_setr_pd(sin_a[0], sin_a[1], sin_a[2], sin_a[2]);
  __m256d kv = _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(lk.scale), e), _mm256_mul_pd(inv_c2, inv_c2)), gnl);
  kv = _mm256_mul_pd(_mm256_mul_pd(kv, s), s);
  alignas(32) double kk[4], xx[4], hh[4];
  _mm256_store_pd(kk, kv);
  _mm256_store_pd(xx, xv);
  _mm256_store_pd(hh, vh);
  const int ok = _mm256_movemask_pd(valid), fast = _mm256_movemask_pd(in_range);
  for (int n = 0; n < 3; ++n) {
    if (!(ok >> n & 1)) {
      k[n] = 0.0;
    } else if (!(fast >> n & 1)) {  // x beyond the table: the scalar path
      k[n] = lobe_factor(lk, n_dot_l[n], v_dot_l[n], v_dot_h[n], &x[n]) * sin_a[n] * sin_a[n];
    } else {
      k[n] = kk[n];
      x[n] = xx[n];
      v_dot_h[n] = hh[n];
    }
  }
}
#else
#define SKYBAND_LOBE_AVX2 0
#endif

// Whether a reflection policy asks for the AVX2 lobe factor (`static constexpr bool kAvx2 = true`,
// only in code compiled for AVX2 + FMA).
template <class P>
constexpr bool wants_avx2_lobe() {
  if constexpr (requires { P::kAvx2; })
    return P::kAvx2 && SKYBAND_LOBE_AVX2;
  else
    return false;
}

}  // namespace skyband::specular_detail
