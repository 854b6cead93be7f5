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
// specular_sky_reference() (specular_sky_reference.h) integrates the same quantity without
// truncation, with an independent rule (3-point Gauss–Legendre in δ per piece, 4-point Gauss–Legendre along α on every visible
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
#include "geometry/core/gauss_legendre.h"
#include "lighting/brdf/cook_torrance.h"
#include "lighting/integrals/specular_lobe_factor.h"
#include "lighting/integrals/specular_sky_options.h"
#include "lighting/spectrum/spectrum.h"

namespace skyband {

namespace specular_detail {

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
        if (l[n].g > 0.0) cell += out[n] * (half * kGauss3Weights[n]);
      }
      raise(level, l[n]);
    }
  } else {
    for (int n = 0; n < 3; ++n) {
      if (k[n] > 0.0) {
        ++stats.radiance_evals;
        l[n].g = p.eval(cos_a[n] * f.x + sin_a[n] * line.u, v_dot_h[n], k[n], scratch);
        if (l[n].g > 0.0) cell += scratch * (half * kGauss3Weights[n]);
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
          sin_d = std::sin(half * kGauss3Nodes[2]);
          cos_d = std::cos(half * kGauss3Nodes[2]);
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

}  // namespace skyband
