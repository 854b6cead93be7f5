#pragma once
// Sky light reflected specularly toward the viewer, over the bands of a cached point
// (seed §3, eqs. 7–10; method.md §4; reference-notes §4.4):
//
//     I(λ) = ∫_visible sky w_s f_s(ω, V; λ) L(λ, ω) (N·ω) dω
//          = Σ_b ∫_{s0}^{s1} ds ∫_{visible α of b} w_s f_s L sin²α dα,     s = sin(δ − β),
//
// because N·ω dω = sin²α dα · cos(δ − β) dδ = sin²α dα ds (band_frame.h). The seed's eq. 7 is
// the one-line-per-band case (∫ ds → w_b at the band's sample plane). Result: spectral radiance
// W·m⁻²·sr⁻¹·nm⁻¹ toward V. Only the sky part of the face's hemisphere is integrated (the ground
// part, δ outside [δ_min, δ_max], is not sky). Visibility is the cache's: constant across a band.
//
// The partial-sky integration (seed §3, steps 1–6), with the changes method.md §4 asks for:
//  1. Q = 2(N·V)N − V, the mirror direction. The sample line nearest Q is found and α* (the
//     point of a line nearest Q) is computed per line: α* = atan2(Q·u, Q·x) clamped to [0, π].
//  2. Along a line, from α* toward each end in cells of dα = c_α·m (capped at
//     max_alpha_step_rad); occluded parts are skipped, every visible piece of a cell (the cell
//     cut by the visible intervals, whose ends are exact) gets 3-point Gauss–Legendre. The lobe
//     is close to a Gaussian of σ ≈ √2·m in ω (Beckmann, σ = m/√2 in the half-vector angle):
//     GL-3 on cells of 2·m ≈ 1.4σ errs by ~h⁷f⁽⁶⁾/2·10⁶ ≈ 10⁻⁴ of the lobe, and cut pieces
//     are smooth too, so no node is wasted on resolving a step (bench_specular measures it:
//     cells of 1.5·m give the same errors within ±0.03 % of the full-sky integral, with 20 % more
//     evaluations on the paper figure).
//     The march stops after the first cell whose largest G is ≤ ε·G_max (G_max the largest G
//     seen so far at this point) and no larger than the previous cell's (the seed stops at
//     G < ε alone; at grazing views and near the pencil axis G(α*) sits on a rising flank and
//     that loses several % of wide lobes). A wholly occluded cell costs one evaluation, at its
//     far end, for this test.
//  3. Lines are visited outward from Q's line in both δ directions while the line's largest G is
//     ≥ ε·G_max or still rising from line to line or the line added more than ε of the total
//     (seed: while G(α*) ≥ ε). Both sweeps end only after `stop_after` (2) consecutive cells or
//     lines met their test: at grazing views the integrand can dip and rise again. "Rising" is
//     judged by G, or by the Beckmann exponent where G has underflowed to 0 (Level, rising()).
//  4. Integration in δ: visibility is constant across a band, and consecutive bands with
//     identical visible intervals within the lobe window (open sky, typically) form one
//     *segment* over which the lobe is smooth. The window is α ∈ [α_Q − R, α_Q + R] with
//     R = lobe_window_per_m·m: it holds the whole cap of directions within R of Q (see the
//     code), and lines are integrated only inside it, so merging is exact for what is integrated. A segment at most c₁·m wide in
//     δ (single_line_per_m) is one line (a single band: its own sample plane and weight w_b, seed eq. 7; the midpoint rule's
//     error (h/σ)²/24 is ≤ 10⁻³); a wider one is split into pieces of equal δ width ≤ c_δ·m (or max_delta_step_rad) with three
//     Gauss–Legendre lines each (weights (h/2)·w_k·cos(δ − β)), the rule used along α, or two when the pieces are at most ⅔ of
//     that width. Merging matters: equal-weight bands crowd around the normal (a wall has 64 bands in 90° of δ, the first ones
//     0.9° wide), so band by band a lobe of m = 0.1 meets ~50 bands.
//  5. m below mirror_below_m: a perfect mirror, I = w_s F(N·V) L(Q) if Q is visible (the band
//     containing Q's δ, visible at α_Q), else 0.
//
// G is a non-negative scalar measure of the integrand w_s f_s L sin²α itself (the spectral
// integrator: its channel mean; the colour integrator, specular_sky_colour.h: its luminance),
// whereas seed eq. 10 writes L·R_s·sin α; using the integrand makes ε a bound on what each
// dropped sample contributes relative to the largest.
//
// The march is written once over a *reflection policy* that says what is integrated:
//     using Value = ...;                          zero-initialised, +=, * double
//     double eval(const Vec3& w, double v_dot_h, double k, Value& out);
//         out = k·F(V·H)·L(w) for unit sky direction w and scalar lobe factor k > 0; returns G.
//     void mirror(const Vec3& q, double n_dot_v, double weight, Value& out);
//         out = weight·F(N·V)·L(q)  (perfect mirror).
//     double measure(const Value& x) const;   the G measure of an accumulated value (≥ 0)
// SpectralReflection below integrates spectra (41 channels, the library's reference path);
// specular_sky_colour.h integrates a few colour channels for the renderer.
//
// specular_sky_reference() integrates the same quantity without truncation, with an independent
// rule (3-point Gauss–Legendre in δ per piece, 4-point Gauss–Legendre along α on every visible
// interval, both on pieces ≤ c·m and ≤ a cap): the oracle of tests and benchmarks.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <type_traits>

#include "geometry/bands/band_frame.h"
#include "geometry/bands/sky_integral.h"
#include "geometry/bands/visibility_cache.h"
#include "lighting/brdf/cook_torrance.h"
#include "lighting/integrals/fast_exp.h"
#include "lighting/spectrum/spectrum.h"

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif

namespace skyband {

struct SpecularSkyOptions {
  double epsilon = 1e-3;            // truncation threshold, relative to G_max (seed's ε)
  double alpha_step_per_m = 2.0;    // α cells ≤ alpha_step_per_m · m ...
  double max_alpha_step_rad = 0.1;  // ... and ≤ this (sky variation under wide lobes)
  double delta_step_per_m = 2.0;    // δ pieces ≤ delta_step_per_m · m ...
  double max_delta_step_rad = 0.2;  // ... and ≤ this
  double single_line_per_m = 0.5;   // a band ≤ this · m wide in δ is one line (seed eq. 7)
  double min_compression = 0.02;    // floor of N·V in the lobe's width across the plane of incidence
  int stop_after = 2;               // consecutive cells (lines) below ε that end a march (sweep)
  double lobe_window_per_m = 7.0;   // lines are integrated only within this · m of Q in α: step 4
  double mirror_below_m = 0.005;    // m below this: perfect mirror (single look-up)
};

struct SpecularSkyStats {
  std::size_t radiance_evals = 0;  // sky radiance evaluations
  std::size_t lines = 0;           // sample lines integrated
};

namespace specular_detail {

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

// One sample line: plane δ, its weight (the s-measure it represents) and the cached band whose
// visibility it uses; u = cos δ·h + sin δ·z spans the plane with x.
struct Line {
  double delta_rad = 0;
  double weight = 0;
  std::size_t band = 0;
  Vec3 u;
  double n_dot_u = 0, v_dot_u = 0;  // the point's N·u and V·u (with_dots): N·ω, V·ω in two products
};

// Per-point constants.
struct PointContext {
  const PointVisibilityView* view = nullptr;
  Vec3 n, v, q;  // normal, unit view direction, mirror direction
  double n_dot_v = 0;
  double n_dot_x = 0, v_dot_x = 0;      // N·x, V·x for the frame's axis x (N·x = 0: x lies in the face)
  LobeConstants lobe_k;                 // the lobe's per-point constants (lobe_factor)
  double alpha_lo = 0, alpha_hi = kPi;  // the lobe window in α (step 4)
  int stop_after = 2;                   // consecutive cells/lines below ε before stopping
  SpecularLobe lobe;
};

// A maximal run of consecutive bands [b0, b1] whose visible intervals are identical: visibility
// is constant across it, so the δ rule may span it (open sky is one segment however many bands
// it holds). Its δ rule: one line when it is at most `single_width_rad` wide (a single band: its
// own sample plane and weight, seed eq. 7; a merged run: the plane at its s-midpoint with the
// run's weight), else 3-point Gauss–Legendre lines on pieces of ≤ step_rad.
struct Segment {
  std::size_t b0 = 0, b1 = 0;
  double d0_rad = 0, d1_rad = 0;
  int count = 1;  // lines
  int nodes = 1;  // Gauss–Legendre lines per piece (count = nodes × pieces; 1 = one line in all)
};
// Whether bands a and b have the same visible intervals within [lo, hi] (radians).
bool same_visibility(const PointVisibilityView& v, std::size_t a, std::size_t b, double lo, double hi);
// The segment holding band b (visibility compared within the context's lobe window), extended
// toward lower bands if dir ≤ 0 and higher ones if dir ≥ 0.
Segment segment_at(const PointContext& c, std::size_t b, int dir, double step_rad, double single_width_rad);
// Line j of `count` lines of the segment, in increasing δ.
Line segment_line(const PointVisibilityView& v, const Segment& s, int j);
// The line of the segment nearest δ.
int nearest_line(const Segment& s, double delta_rad);
// Index of the band whose weight range holds s (clamped to the first/last band).
std::size_t band_of_s(const PointVisibilityView& v, double s);
// Weight coordinate s = sin(δ − β) of direction q, clamped to the face's sky range.
double s_of_direction(const BandFrame& f, const Vec3& q);
// The point of the line (x, u) nearest q: α* = atan2(q·u, q·x), clamped to [0, π]; also its
// cos α*, sin α* (from q·x, q·u without more trigonometry).
double nearest_alpha(const BandFrame& f, const Vec3& u, const Vec3& q, double& cos_a, double& sin_a);
// Whether α lies in one of the sorted visible intervals.
bool alpha_visible(std::span<const VisibleInterval> visible, double alpha_rad);
// Per-point setup; false when V is at or behind the surface (nothing reflected toward V).
bool make_context(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe, PointContext& c);

// The march's steps for one point (step 2 and 4 above) from the lobe's widths around Q; also
// sets the lobe window c.alpha_lo/alpha_hi.
struct MarchSteps {
  double alpha_rad = 0;        // α cell width
  double delta_rad = 0;        // δ piece width
  double single_line_rad = 0;  // a segment at most this wide in δ is one line
};
MarchSteps march_steps(PointContext& c, const SpecularSkyOptions& opt);

// The α cell of a point and the trigonometry every line's march shares: whole cells are
// [α* + j·step, α* + (j + 1)·step] on every line, so their 3 nodes' offsets from the midpoint
// (±d, d = (step/2)·x₃) and the rotation from one midpoint to the next are per-point constants.
struct AlphaCells {
  double step = 0, half = 0;
  double cos_half = 1, sin_half = 0;  // of step/2
  double cos_d = 1, sin_d = 0;        // of d
  double cos_step = 1, sin_step = 0;  // of step
};
AlphaCells alpha_cells(double step_rad);

// 3-point Gauss–Legendre on [−1, 1].
// 2-point Gauss–Legendre on [−1, 1].
inline constexpr double kGl2X[2] = {-0.5773502691896258, 0.5773502691896258};
inline constexpr double kGl2W[2] = {1.0, 1.0};
inline constexpr double kGl3X[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
inline constexpr double kGl3W[3] = {0.5555555555555556, 0.8888888888888888, 0.5555555555555556};

// How far into the lobe a sample is, for the stop tests: its G, and the Beckmann exponent
// x = tan²θ_h/m², which still orders samples where G has underflowed to 0 (e^{−x} < 10⁻³⁰⁸
// beyond x ≈ 708, i.e. θ_h > 29° for m = 0.02): a march must not take such a plateau for a
// decay when it is in fact approaching an off-specular peak.
struct Level {
  double g = 0;
  double x = std::numeric_limits<double>::infinity();
};
// Whether `now` lies further into the lobe than `before`.
inline bool rising(const Level& now, const Level& before) {
  return (now.g > 0.0 || before.g > 0.0) ? now.g > before.g : now.x < before.x;
}
inline void raise(Level& l, const Level& o) {
  l.g = std::max(l.g, o.g);
  l.x = std::min(l.x, o.x);
}

// Integrand w_s f_s L sin²α at the point (cos α, sin α) of `line` into `out`; returns its G
// (and the Beckmann exponent into *exponent when given).
// The line must carry its dot products (with_dots). ω = cos α·x + sin α·u is unit (x ⟂ u).
template <class Policy>
double integrand_cs(const PointContext& c, const Line& line, double cos_a, double sin_a, Policy& p, typename Policy::Value& out,
                    SpecularSkyStats& stats, double* exponent = nullptr) {
  const double n_dot_w = cos_a * c.n_dot_x + sin_a * line.n_dot_u;
  const double v_dot_w = cos_a * c.v_dot_x + sin_a * line.v_dot_u;
  double v_dot_h = 0;
  const double k = lobe_factor(c.lobe_k, n_dot_w, v_dot_w, v_dot_h, exponent) * sin_a * sin_a;
  if (!(k > 0.0)) {
    out = typename Policy::Value{};
    return 0.0;
  }
  ++stats.radiance_evals;
  const BandFrame& f = c.view->frame();
  return p.eval(cos_a * f.x + sin_a * line.u, v_dot_h, k, out);
}

// The three Gauss–Legendre nodes of one piece (weights half·w_k) added into `cell`, their
// levels raised into `level`: integrand_cs for each, with the three lobe factors computed
// side by side first (independent dependency chains the processor overlaps) and the sky looked
// up only where the factor is positive.
template <class Policy>
void integrate_nodes3(const PointContext& c, const Line& line, const double (&cos_a)[3], const double (&sin_a)[3], double half,
                      Policy& p, typename Policy::Value& scratch, typename Policy::Value& cell, Level& level,
                      SpecularSkyStats& stats) {
  double k[3], v_dot_h[3], n_dot_w[3], v_dot_w[3];
  Level l[3];
  for (int n = 0; n < 3; ++n) {
    n_dot_w[n] = cos_a[n] * c.n_dot_x + sin_a[n] * line.n_dot_u;
    v_dot_w[n] = cos_a[n] * c.v_dot_x + sin_a[n] * line.v_dot_u;
  }
  // The AVX2 build (wants_avx2_lobe) computes the three lobe factors in vector lanes and, where
  // the policy offers eval3, the three directions and grid cells too.
  constexpr bool kAvx2 = wants_avx2_lobe<Policy>();
  if constexpr (kAvx2) {
#if SKYBAND_LOBE_AVX2
    double x[3] = {l[0].x, l[1].x, l[2].x};
    lobe_factor3_avx2(c.lobe_k, n_dot_w, v_dot_w, sin_a, k, v_dot_h, x);
    for (int n = 0; n < 3; ++n) l[n].x = x[n];
#endif
  } else {
    for (int n = 0; n < 3; ++n) k[n] = lobe_factor(c.lobe_k, n_dot_w[n], v_dot_w[n], v_dot_h[n], &l[n].x) * sin_a[n] * sin_a[n];
  }
  const BandFrame& f = c.view->frame();
  if constexpr (kAvx2 && requires(typename Policy::Value(&o)[3], double(&g)[3]) {
                  p.eval3(cos_a, sin_a, f.x, line.u, v_dot_h, k, o, g);
                }) {
    typename Policy::Value out[3];
    double g[3];
    p.eval3(cos_a, sin_a, f.x, line.u, v_dot_h, k, out, g);
    for (int n = 0; n < 3; ++n) {
      if (k[n] > 0.0) {
        ++stats.radiance_evals;
        l[n].g = g[n];
        if (l[n].g > 0.0) cell += out[n] * (half * kGl3W[n]);
      }
      raise(level, l[n]);
    }
  } else {
    for (int n = 0; n < 3; ++n) {
      if (k[n] > 0.0) {
        ++stats.radiance_evals;
        l[n].g = p.eval(cos_a[n] * f.x + sin_a[n] * line.u, v_dot_h[n], k[n], scratch);
        if (l[n].g > 0.0) cell += scratch * (half * kGl3W[n]);
      }
      raise(level, l[n]);
    }
  }
}

// The line with the point's N·u and V·u filled in (integrand_cs needs them).
inline Line with_dots(const PointContext& c, Line line) {
  line.n_dot_u = c.n.dot(line.u);
  line.v_dot_u = c.v.dot(line.u);
  return line;
}

// The same at angle α.
template <class Policy>
double integrand(const PointContext& c, const Line& line, double alpha, Policy& p, typename Policy::Value& out,
                 SpecularSkyStats& stats, double* exponent = nullptr) {
  return integrand_cs(c, line, std::cos(alpha), std::sin(alpha), p, out, stats, exponent);
}
// The same, returning its Level.
template <class Policy>
Level level_at(const PointContext& c, const Line& line, double alpha, Policy& p, typename Policy::Value& out,
               SpecularSkyStats& stats) {
  Level l;
  l.g = integrand(c, line, alpha, p, out, stats, &l.x);
  return l;
}

// March from α* toward one end (dir = +1: to π, −1: to 0) over the visible parts of `line`;
// adds ∫ to `acc` (unweighted) and updates g_max / line_max. g_start: G at α*.
template <class Policy>
void march(const PointContext& c, const Line& line, double alpha_star, double cos_star, double sin_star, const Level& start,
           int dir, const AlphaCells& cells, double eps, double total, double& g_max, Level& line_max,
           typename Policy::Value& acc, Policy& p, SpecularSkyStats& stats) {
  const double step = cells.step;
  const std::span<const VisibleInterval> vis = c.view->visible(line.band);
  const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(vis.size());
  // Interval cursor: + direction, first interval ending after α*; − direction, last starting before.
  std::ptrdiff_t idx = 0;
  if (dir > 0) {
    while (idx < count && clamp_alpha(vis[idx].alpha1_rad) <= alpha_star) ++idx;
  } else {
    idx = count - 1;
    while (idx >= 0 && clamp_alpha(vis[idx].alpha0_rad) >= alpha_star) --idx;
  }
  typename Policy::Value f, cell;
  double a = alpha_star;
  Level prev = start;
  // The three nodes of a piece, mid − d, mid, mid + d (d = half·x₃), by angle addition from
  // (cos, sin) of mid and of d. Whole cells [α* + j·step, α* + (j + 1)·step] (in the march
  // direction) share d, and their midpoints follow each other by a rotation through the step:
  // no sin/cos per whole cell (the recurrence's rounding grows by ~10⁻¹⁶ per cell, far below
  // anything the quadrature resolves). Cut pieces and the last, shortened cell take sin/cos.
  const double full_half = cells.half, full_sin_d = cells.sin_d, full_cos_d = cells.cos_d;
  const double rot_cos = cells.cos_step, rot_sin = dir * cells.sin_step;
  const double half_sin = dir * cells.sin_half;
  double full_cm = cos_star * cells.cos_half - sin_star * half_sin;  // cos, sin of α* + dir·step/2
  double full_sm = sin_star * cells.cos_half + cos_star * half_sin;
  int quiet = 0;  // consecutive cells that met the stop test
  const double end = dir > 0 ? c.alpha_hi : c.alpha_lo;
  for (int j = 0; dir > 0 ? a < end : a > end; ++j) {
    const double a_full = alpha_star + dir * (j + 1) * step;  // this cell's far end if whole
    const bool whole = dir > 0 ? a_full <= end : a_full >= end;
    const double b = whole ? a_full : end;
    const double lo_cell = std::min(a, b), hi_cell = std::max(a, b);
    Level cell_l;
    bool any = false;
    cell = typename Policy::Value{};
    while (idx >= 0 && idx < count) {
      const double i0 = clamp_alpha(vis[idx].alpha0_rad), i1 = clamp_alpha(vis[idx].alpha1_rad);
      if (dir > 0 ? i0 >= hi_cell : i1 <= lo_cell) break;  // next interval starts beyond this cell
      const double lo = std::max(lo_cell, i0), hi = std::min(hi_cell, i1);
      if (hi > lo) {
        double half, sin_d, cos_d, sm, cm;
        if (whole && lo == lo_cell && hi == hi_cell) {
          half = full_half;
          sin_d = full_sin_d;
          cos_d = full_cos_d;
          sm = full_sm;
          cm = full_cm;
        } else {
          const double mid = 0.5 * (lo + hi);
          half = 0.5 * (hi - lo);
          sin_d = std::sin(half * kGl3X[2]);
          cos_d = std::cos(half * kGl3X[2]);
          sm = std::sin(mid);
          cm = std::cos(mid);
        }
        const double node_cos[3] = {cm * cos_d + sm * sin_d, cm, cm * cos_d - sm * sin_d};
        const double node_sin[3] = {sm * cos_d - cm * sin_d, sm, sm * cos_d + cm * sin_d};
        integrate_nodes3(c, line, node_cos, node_sin, half, p, f, cell, cell_l, stats);
        any = true;
      }
      // Move on only if the interval ends inside this cell (in the march direction).
      if (dir > 0 ? i1 <= hi_cell : i0 >= lo_cell)
        idx += dir;
      else
        break;
    }
    if (!any) {     // wholly occluded: G at the far end decides whether to go on
      if (whole) {  // cos, sin of b = mid + dir·step/2 by angle addition from the recurrence
        const double hs = dir * cells.sin_half;
        cell_l.g = integrand_cs(c, line, full_cm * cells.cos_half - full_sm * hs, full_sm * cells.cos_half + full_cm * hs, p, f,
                                stats, &cell_l.x);
      } else {
        cell_l = level_at(c, line, b, p, f, stats);
      }
    }
    acc += cell;
    g_max = std::max(g_max, cell_l.g);
    raise(line_max, cell_l);
    // Stop once G is negligible AND no longer rising (G at α* can sit on the rising flank: near
    // the pencil axis sin²α → 0, or off-specular peaks at grazing views) AND the cell carried
    // at most ε of what the point has gathered (at grazing views a low, wide tail under a sharp
    // peak passes the first two tests while still holding several % of the integral).
    const double mass = p.measure(cell) * line.weight;
    const bool negligible =
        cell_l.g <= eps * g_max && !rising(cell_l, prev) && mass <= eps * (total + p.measure(acc) * line.weight);
    quiet = negligible ? quiet + 1 : 0;
    a = b;
    prev = cell_l;
    if (quiet >= c.stop_after) break;
    const double next_cm = full_cm * rot_cos - full_sm * rot_sin;
    full_sm = full_sm * rot_cos + full_cm * rot_sin;
    full_cm = next_cm;
  }
}

// Integrates one line from its α* both ways into acc (times the line's weight); returns the
// largest G met on the line.
template <class Policy>
Level integrate_line(const PointContext& c, const Line& plain_line, const AlphaCells& cells, double eps, double& g_max,
                     typename Policy::Value& acc, Policy& p, SpecularSkyStats& stats, double* mass_out = nullptr) {
  const Line line = with_dots(c, plain_line);
  const double total = p.measure(acc);
  double cos_star, sin_star;
  const double nearest = nearest_alpha(c.view->frame(), line.u, c.q, cos_star, sin_star);
  const double a_star = std::clamp(nearest, c.alpha_lo, c.alpha_hi);
  if (a_star != nearest) {
    cos_star = std::cos(a_star);
    sin_star = std::sin(a_star);
  }
  typename Policy::Value f_star;
  Level star;  // for the stop tests only
  star.g = integrand_cs(c, line, cos_star, sin_star, p, f_star, stats, &star.x);
  g_max = std::max(g_max, star.g);
  Level line_max = star;
  typename Policy::Value line_sum;
  march(c, line, a_star, cos_star, sin_star, star, +1, cells, eps, total, g_max, line_max, line_sum, p, stats);
  march(c, line, a_star, cos_star, sin_star, star, -1, cells, eps, total, g_max, line_max, line_sum, p, stats);
  acc += line_sum * line.weight;
  if (mass_out) *mass_out = p.measure(line_sum) * line.weight;
  ++stats.lines;
  return line_max;
}

// The opening both integrators share: nothing to integrate (no bands, no lobe, the view behind
// the face), or a perfect mirror (one look-up of L in the mirror direction, if visible). True
// when `acc` is the answer.
template <class Policy>
bool trivial_case(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe, Policy& p,
                  const SpecularSkyOptions& opt, PointContext& c, SpecularSkyStats& stats, typename Policy::Value& acc) {
  if (view.band_count() == 0 || lobe.weight <= 0.0 || !make_context(view, view_dir, lobe, c)) return true;
  if (lobe.roughness_m < opt.mirror_below_m) {
    const BandFrame& f = view.frame();
    if (c.q.dot(f.z) < 0.0) return true;  // mirror direction below the horizon: not sky
    double alpha, delta;
    f.angles_of(c.q, alpha, delta);
    if (!alpha_visible(view.visible(band_of_s(view, s_of_direction(f, c.q))), alpha)) return true;
    ++stats.radiance_evals;
    p.mirror(c.q, c.n_dot_v, lobe.weight, acc);
    return true;
  }
  return false;
}

// The ε-truncated partial-sky integral over any reflection policy (see the top of this file).
template <class Policy>
typename Policy::Value specular_sky_integral(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                                             Policy& p, const SpecularSkyOptions& opt, SpecularSkyStats& stats) {
  typename Policy::Value acc;
  PointContext c;
  if (trivial_case(view, view_dir, lobe, p, opt, c, stats, acc)) return acc;
  const BandFrame& f = view.frame();
  const MarchSteps steps = march_steps(c, opt);
  const AlphaCells a_cells = alpha_cells(steps.alpha_rad);
  const double d_step = steps.delta_rad, single = steps.single_line_rad;
  const double eps = opt.epsilon;

  // Start: the line of Q's segment nearest δ_Q.
  const double s_q = s_of_direction(f, c.q);
  const Segment seg_q = segment_at(c, band_of_s(view, s_q), 0, d_step, single);
  const int k_q = nearest_line(seg_q, f.delta_at(s_q));

  c.stop_after = std::max(1, opt.stop_after);
  double g_max = 0;
  const Level first_max = integrate_line(c, segment_line(view, seg_q, k_q), a_cells, eps, g_max, acc, p, stats);
  // Outward in δ: lower lines/segments, then higher ones, each until a line's largest G is
  // below ε·G_max and no longer rising from line to line.
  for (int dir : {-1, +1}) {
    Segment seg = seg_q;
    int k = k_q;
    Level prev_max = first_max;
    int quiet = 0;
    for (;;) {
      k += dir;
      if (k < 0 || k >= seg.count) {
        if (dir < 0 ? seg.b0 == 0 : seg.b1 + 1 >= view.band_count()) break;
        seg = segment_at(c, dir < 0 ? seg.b0 - 1 : seg.b1 + 1, dir, d_step, single);
        k = dir > 0 ? 0 : seg.count - 1;
      }
      double mass = 0;
      const Level line_max = integrate_line(c, segment_line(view, seg, k), a_cells, eps, g_max, acc, p, stats, &mass);
      quiet = line_max.g <= eps * g_max && !rising(line_max, prev_max) && mass <= eps * p.measure(acc) ? quiet + 1 : 0;
      if (quiet >= c.stop_after) break;
      prev_max = line_max;
    }
  }
  return acc;
}

}  // namespace specular_detail

// The spectral reflection policy: L from `sky(const Vec3& world_dir, Spectrum& out)` in
// W·m⁻²·sr⁻¹·nm⁻¹, F from the lobe's Fresnel table (nullptr: F = 1); G = channel mean.
template <class Radiance>
struct SpectralReflection {
  using Value = Spectrum;
  Radiance& sky;
  const FresnelTable* fresnel = nullptr;

  double eval(const Vec3& w, double v_dot_h, double k, Spectrum& out) {
    reflected(w, v_dot_h, k, out);
    return std::max(channel_mean(out), 0.0);
  }
  double measure(const Spectrum& x) const { return std::abs(channel_mean(x)); }
  void mirror(const Vec3& q, double n_dot_v, double weight, Spectrum& out) { reflected(q, n_dot_v, weight, out); }

 private:
  // out = k·F(cos θ)·L(w).
  void reflected(const Vec3& w, double cos_theta, double k, Spectrum& out) {
    sky(w, out);
    if (fresnel) {
      Spectrum fr;
      fresnel->eval(cos_theta, fr);
      out *= fr;
    }
    out *= k;
  }
  static double channel_mean(const Spectrum& x) {
    double sum = 0;
    for (int i = 0; i < kSpectrumSamples; ++i) sum += x[i];
    return sum / kSpectrumSamples;
  }
};

// What the sky is like over a point's *lobe window*: the cap of directions within
// R = opt.lobe_window_per_m·m of the mirror direction Q (outside it the Beckmann factor is below
// e^{−R²/4m²} = 5·10⁻⁶ of its peak at R = 7m, specular_detail::march_steps). kOpen: every
// direction of the cap is visible sky (per the cache: the band lines that cross it have a visible
// interval holding the cap's whole α range, and the cap lies within the face's sky range
// [δ_min, δ_max], so neither the horizon nor the face plane cuts it); kClosed: none is (the
// lines that cross it see nothing of its α range, or the whole cap lies outside the sky range;
// also when nothing is reflected toward V at all); kMixed otherwise, and whenever the cap holds
// the pencil axis (sin α_Q ≤ sin R), where every band line meets. A point whose cap is open or
// closed has no visibility edge near its reflection: its specular sky is a smooth function of the
// view (specular_reuse.h uses this for near-mirrors). The cap's δ extent: a plane δ of the
// pencil is at angular distance asin(sin α_Q·|sin(δ − δ_Q)|) from Q, so the cap meets exactly
// the planes with |δ − δ_Q| ≤ asin(sin R / sin α_Q).
enum class LobeWindowSky { kOpen, kClosed, kMixed };
LobeWindowSky lobe_window_sky(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                              const SpecularSkyOptions& opt = {});

// The ε-truncated partial-sky integral (seed §3), spectral. `view_dir` points from the surface
// toward the eye (any length).
template <class Radiance>
Spectrum specular_sky_radiance(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe, Radiance&& sky,
                               const SpecularSkyOptions& opt = {}, SpecularSkyStats* stats_out = nullptr) {
  SpecularSkyStats stats;
  SpectralReflection<std::remove_reference_t<Radiance>> p{sky, lobe.fresnel};
  const Spectrum r = specular_detail::specular_sky_integral(view, view_dir, lobe, p, opt, stats);
  if (stats_out) *stats_out = stats;
  return r;
}

// Reference: the same integral over every band and visible interval without truncation.
// Pieces in δ and α are ≤ min(step_per_m·m, max_step_rad); 3-point GL in δ (weight cos(δ − β)),
// 4-point GL along α. Perfect mirrors (m < opt.mirror_below_m) use the same look-up as above.
template <class Radiance>
Spectrum specular_sky_reference(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe, Radiance&& sky,
                                double step_per_m = 0.5, double max_step_rad = 0.02, const SpecularSkyOptions& opt = {},
                                SpecularSkyStats* stats_out = nullptr) {
  using namespace specular_detail;
  static constexpr double x4[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  static constexpr double w4[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  SpecularSkyStats stats;
  Spectrum acc;
  PointContext c;
  SpectralReflection<std::remove_reference_t<Radiance>> p{sky, lobe.fresnel};
  if (trivial_case(view, view_dir, lobe, p, opt, c, stats, acc)) {
    if (stats_out) *stats_out = stats;
    return acc;
  }
  const BandFrame& f = view.frame();
  const double step = std::min(step_per_m * lobe.roughness_m, max_step_rad);
  Spectrum val;
  for (std::size_t b = 0; b < view.band_count(); ++b) {
    const double d0 = f.delta_at(view.band(b).s0), d1 = f.delta_at(view.band(b).s1);
    const int kd = std::max(1, static_cast<int>(std::ceil((d1 - d0) / step)));
    const double hd = (d1 - d0) / kd;
    for (int pc = 0; pc < kd; ++pc)
      for (int gd = 0; gd < 3; ++gd) {
        Line line;
        line.band = b;
        line.delta_rad = d0 + (pc + 0.5) * hd + 0.5 * hd * kGl3X[gd];
        line.u = std::cos(line.delta_rad) * f.h + std::sin(line.delta_rad) * f.z;
        line.weight = 0.5 * hd * kGl3W[gd] * std::cos(line.delta_rad - f.beta_rad);
        line = with_dots(c, line);
        Spectrum line_sum;
        for (const VisibleInterval& iv : view.visible(b)) {
          const double a0 = clamp_alpha(iv.alpha0_rad), a1 = clamp_alpha(iv.alpha1_rad);
          if (!(a1 > a0)) continue;
          const int ka = std::max(1, static_cast<int>(std::ceil((a1 - a0) / step)));
          const double ha = (a1 - a0) / ka;
          for (int q = 0; q < ka; ++q)
            for (int ga = 0; ga < 4; ++ga) {
              const double a = a0 + (q + 0.5) * ha + 0.5 * ha * x4[ga];
              if (integrand(c, line, a, p, val, stats) > 0.0) line_sum += val * (0.5 * ha * w4[ga]);
            }
        }
        acc += line_sum * line.weight;
        ++stats.lines;
      }
  }
  if (stats_out) *stats_out = stats;
  return acc;
}

}  // namespace skyband
