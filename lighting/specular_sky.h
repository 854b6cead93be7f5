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
//     max_alpha_step_rad), so the lobe (angular width ≈ √2·m) is always resolved; occluded parts
//     are skipped, the end points of visible intervals are evaluated exactly. Each visible piece
//     uses Simpson's rule (the trapezoid nodes plus the piece's midpoint) instead of the seed's
//     trapezoid: where an occluder leaves only a lobe tail visible, the trapezoid's h²f''/12
//     error is several % of what remains at dα = m/2, and halving dα costs the same as Simpson's
//     extra midpoint while gaining only a factor 4 (measured in specular_sky_test). The march stops at
//     the first node where G ≤ ε·G_max (G_max the largest G seen so far at this point) and G is
//     no longer rising (the seed stops at G < ε alone; at grazing views and near the pencil axis
//     G(α*) sits on a rising flank and that loses several % of wide lobes).
//  3. Lines are visited outward from Q's line in both δ directions while the line's largest G is
//     ≥ ε·G_max or still rising from line to line (seed: while G(α*) ≥ ε).
//  4. Sub-band integration in δ: where a band is wider (in δ) than c_δ·m (or max_delta_step_rad),
//     it is split into K pieces of equal δ width with two Gauss–Legendre lines each (weights
//     (h/2)·cos(δ − β)). One line per piece (the midpoint rule the bands themselves use) was
//     measured 3% low where the horizon cuts a narrow lobe's tail (specular_sky_test).
//  5. m below mirror_below_m: a perfect mirror, I = w_s F(N·V) L(Q) if Q is visible (the band
//     containing Q's δ, visible at α_Q), else 0.
//
// G here is the channel mean of the integrand w_s f_s L sin²α itself, whereas seed eq. 10 writes
// L·R_s·sin α; using the integrand makes ε a bound on what each dropped sample contributes.
//
// specular_sky_reference() integrates the same quantity without truncation, with an independent
// rule (3-point Gauss–Legendre in δ per piece, 4-point Gauss–Legendre along α on every visible
// interval, both on pieces ≤ c·m and ≤ a cap): the oracle of tests and benchmarks.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

#include "geometry/band_frame.h"
#include "geometry/sky_integral.h"
#include "geometry/visibility_cache.h"
#include "lighting/cook_torrance.h"
#include "lighting/spectrum.h"

namespace skyband {

struct SpecularSkyOptions {
  double epsilon = 1e-3;             // truncation threshold, relative to G_max (seed's ε)
  double alpha_step_per_m = 0.5;     // dα = alpha_step_per_m · m ...
  double max_alpha_step_rad = 0.05;  // ... but never coarser than this (sky variation)
  double delta_step_per_m = 0.25;    // sub-band piece width in δ ≤ delta_step_per_m · m ...
  double max_delta_step_rad = 0.1;   // ... and ≤ this
  double mirror_below_m = 0.005;     // m below this: perfect mirror (single look-up)
};

struct SpecularSkyStats {
  std::size_t radiance_evals = 0;  // sky radiance evaluations
  std::size_t lines = 0;           // sample lines integrated
};

namespace specular_detail {

// One sample line: plane δ, its weight (the s-measure it represents) and the cached band whose
// visibility it uses; u = cos δ·h + sin δ·z spans the plane with x.
struct Line {
  double delta_rad = 0;
  double weight = 0;
  std::size_t band = 0;
  Vec3 u;
};

// Per-point constants.
struct PointContext {
  const PointVisibilityView* view = nullptr;
  Vec3 n, v, q;  // normal, unit view direction, mirror direction
  double n_dot_v = 0;
  SpecularLobe lobe;
};

// Number of sample lines of band b: 1 (the band's own plane, seed eq. 7) when the band is at
// most `step_rad` wide in δ, else 2 per piece of ≤ step_rad (2-point Gauss–Legendre in δ).
int line_count(const BandFrame& f, const BandRecord& b, double step_rad);
// Line j of the `count` lines of band `band`, in increasing δ.
Line band_line(const BandFrame& f, const BandRecord& b, std::size_t band, int j, int count);
// Index of the band whose weight range holds s (clamped to the first/last band).
std::size_t band_of_s(const PointVisibilityView& v, double s);
// Weight coordinate s = sin(δ − β) of direction q, clamped to the face's sky range.
double s_of_direction(const BandFrame& f, const Vec3& q);
// The point of the line (x, u) nearest q: α* = atan2(q·u, q·x), clamped to [0, π].
double nearest_alpha(const BandFrame& f, const Vec3& u, const Vec3& q);
// Whether α lies in one of the sorted visible intervals.
bool alpha_visible(std::span<const VisibleInterval> visible, double alpha_rad);
// Per-point setup; false when V is at or behind the surface (nothing reflected toward V).
bool make_context(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe, PointContext& c);

// Integrand w_s f_s L sin²α at α on `line` into `out`; returns its channel mean (G).
template <class Radiance>
double integrand(const PointContext& c, const Line& line, double alpha, Radiance& sky, Spectrum& out,
                 SpecularSkyStats& stats) {
  const BandFrame& f = c.view->frame();
  const double sa = std::sin(alpha);
  const Vec3 w = std::cos(alpha) * f.x + sa * line.u;
  MicrofacetCosines mc;
  double k = 0;
  if (microfacet_cosines(c.n, w, c.v, mc)) k = c.lobe.factor(mc) * sa * sa;
  if (!(k > 0.0)) {
    out = Spectrum{};
    return 0.0;
  }
  sky(w, out);
  ++stats.radiance_evals;
  if (c.lobe.fresnel) {
    Spectrum fr;
    c.lobe.fresnel->eval(mc.v_dot_h, fr);
    out *= fr;
  }
  out *= k;
  double mean = 0;
  for (int i = 0; i < kSpectrumSamples; ++i) mean += out[i];
  return mean / kSpectrumSamples;
}

// March from α* toward one end (dir = +1: to π, −1: to 0) over the visible parts of
// `line`; adds ∫ to `acc` (unweighted) and updates g_max. f_start/g_start: integrand at α*.
template <class Radiance>
void march(const PointContext& c, const Line& line, double alpha_star, const Spectrum& f_start, double g_start,
           int dir, double step, double eps, double& g_max, double& line_max, Spectrum& acc, Radiance& sky,
           SpecularSkyStats& stats) {
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
  Spectrum f_a = f_start, f_b, f_lo, f_hi, f_mid;
  double a = alpha_star, g_a = g_start, g_b = g_start;
  const double end = dir > 0 ? kPi : 0.0;
  while (dir > 0 ? a < end : a > end) {
    const double b = dir > 0 ? std::min(a + step, end) : std::max(a - step, end);
    g_b = integrand(c, line, b, sky, f_b, stats);
    // Cell [lo_cell, hi_cell] in increasing α.
    const double lo_cell = std::min(a, b), hi_cell = std::max(a, b);
    const Spectrum& f_lo_cell = dir > 0 ? f_a : f_b;
    const Spectrum& f_hi_cell = dir > 0 ? f_b : f_a;
    while (idx >= 0 && idx < count) {
      const double i0 = clamp_alpha(vis[idx].alpha0_rad), i1 = clamp_alpha(vis[idx].alpha1_rad);
      if (dir > 0 ? i0 >= hi_cell : i1 <= lo_cell) break;  // next interval starts beyond this cell
      const double lo = std::max(lo_cell, i0), hi = std::min(hi_cell, i1);
      if (hi > lo) {
        const Spectrum* pl = &f_lo_cell;
        const Spectrum* ph = &f_hi_cell;
        if (lo > lo_cell) { integrand(c, line, lo, sky, f_lo, stats); pl = &f_lo; }
        if (hi < hi_cell) { integrand(c, line, hi, sky, f_hi, stats); ph = &f_hi; }
        integrand(c, line, 0.5 * (lo + hi), sky, f_mid, stats);
        const double sixth = (hi - lo) / 6.0;  // Simpson: (len/6)(f_lo + 4 f_mid + f_hi)
        for (int i = 0; i < kSpectrumSamples; ++i) acc[i] += sixth * ((*pl)[i] + 4.0 * f_mid[i] + (*ph)[i]);
      }
      // Move on only if the interval ends inside this cell (in the march direction).
      if (dir > 0 ? i1 <= hi_cell : i0 >= lo_cell) idx += dir;
      else break;
    }
    g_max = std::max(g_max, g_b);
    line_max = std::max(line_max, g_b);
    // Stop once G is negligible AND no longer rising (G at α* can sit on the rising flank: near
    // the pencil axis sin²α → 0, or off-specular peaks at grazing views).
    const bool stop = g_b <= eps * g_max && g_b <= g_a;
    a = b;
    f_a = f_b;
    g_a = g_b;
    if (stop) break;
  }
}

// Integrates one line from its α* both ways into acc (times the line's weight); returns the
// largest G met on the line.
template <class Radiance>
double integrate_line(const PointContext& c, const Line& line, double step, double eps, double& g_max, Spectrum& acc,
                      Radiance& sky, SpecularSkyStats& stats) {
  const double a_star = nearest_alpha(c.view->frame(), line.u, c.q);
  Spectrum f_star;
  const double g_star = integrand(c, line, a_star, sky, f_star, stats);
  g_max = std::max(g_max, g_star);
  double line_max = g_star;
  Spectrum line_sum;
  march(c, line, a_star, f_star, g_star, +1, step, eps, g_max, line_max, line_sum, sky, stats);
  march(c, line, a_star, f_star, g_star, -1, step, eps, g_max, line_max, line_sum, sky, stats);
  acc += line_sum * line.weight;
  ++stats.lines;
  return line_max;
}

template <class Radiance>
Spectrum mirror_lookup(const PointContext& c, Radiance& sky, SpecularSkyStats& stats) {
  const BandFrame& f = c.view->frame();
  if (c.q.dot(f.z) < 0.0) return Spectrum{};  // mirror direction below the horizon: not sky
  double alpha, delta;
  f.angles_of(c.q, alpha, delta);
  const std::size_t b = band_of_s(*c.view, s_of_direction(f, c.q));
  if (!alpha_visible(c.view->visible(b), alpha)) return Spectrum{};
  Spectrum l;
  sky(c.q, l);
  ++stats.radiance_evals;
  if (c.lobe.fresnel) {
    Spectrum fr;
    c.lobe.fresnel->eval(c.n_dot_v, fr);
    l *= fr;
  }
  return l * c.lobe.weight;
}

// The opening both integrators share: nothing to integrate (no bands, no lobe, the view behind
// the face), or a perfect mirror (one look-up of L in the mirror direction). True when `acc` is
// the answer.
template <class Radiance>
bool trivial_case(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe, Radiance& sky,
                  const SpecularSkyOptions& opt, PointContext& c, SpecularSkyStats& stats, Spectrum& acc) {
  if (view.band_count() == 0 || lobe.weight <= 0.0 || !make_context(view, view_dir, lobe, c)) return true;
  if (lobe.roughness_m < opt.mirror_below_m) {
    acc = mirror_lookup(c, sky, stats);
    return true;
  }
  return false;
}

}  // namespace specular_detail

// The ε-truncated partial-sky integral (seed §3). `sky(const Vec3& world_dir, Spectrum& out)`
// gives L in W·m⁻²·sr⁻¹·nm⁻¹; `view_dir` points from the surface toward the eye (any length).
template <class Radiance>
Spectrum specular_sky_radiance(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                               Radiance&& sky, const SpecularSkyOptions& opt = {}, SpecularSkyStats* stats_out = nullptr) {
  using namespace specular_detail;
  SpecularSkyStats stats;
  Spectrum acc;
  PointContext c;
  if (trivial_case(view, view_dir, lobe, sky, opt, c, stats, acc)) {
    if (stats_out) *stats_out = stats;
    return acc;
  }
  const BandFrame& f = view.frame();
  const double m = lobe.roughness_m;
  const double a_step = std::min(opt.alpha_step_per_m * m, opt.max_alpha_step_rad);
  const double d_step = std::min(opt.delta_step_per_m * m, opt.max_delta_step_rad);
  const double eps = opt.epsilon;

  // Start: the piece of Q's band that holds δ_Q.
  const double s_q = s_of_direction(f, c.q);
  const std::size_t b_q = band_of_s(view, s_q);
  const int k_count_q = line_count(f, view.band(b_q), d_step);
  const double d_lo = f.delta_at(view.band(b_q).s0), d_hi = f.delta_at(view.band(b_q).s1);
  const double d_q = f.delta_at(s_q);
  int k_q = 0;
  if (k_count_q > 1 && d_hi > d_lo) {
    const double x = (d_q - d_lo) / (d_hi - d_lo) * (k_count_q / 2);  // piece coordinate
    const int piece = std::clamp(static_cast<int>(x), 0, k_count_q / 2 - 1);
    k_q = 2 * piece + (x - piece > 0.5 ? 1 : 0);
  }

  double g_max = 0;
  const double first_max =
      integrate_line(c, band_line(f, view.band(b_q), b_q, k_q, k_count_q), a_step, eps, g_max, acc, sky, stats);
  // Outward in δ: lower pieces/bands, then higher ones, each until a line's largest G is below
  // ε·G_max and no longer rising from line to line.
  for (int dir : {-1, +1}) {
    std::ptrdiff_t b = static_cast<std::ptrdiff_t>(b_q);
    int k = k_q, kc = k_count_q;
    double prev_max = first_max;
    for (;;) {
      k += dir;
      if (k < 0 || k >= kc) {
        b += dir;
        if (b < 0 || b >= static_cast<std::ptrdiff_t>(view.band_count())) break;
        kc = line_count(f, view.band(static_cast<std::size_t>(b)), d_step);
        k = dir > 0 ? 0 : kc - 1;
      }
      const std::size_t bu = static_cast<std::size_t>(b);
      const double line_max = integrate_line(c, band_line(f, view.band(bu), bu, k, kc), a_step, eps, g_max, acc, sky, stats);
      if (line_max <= eps * g_max && line_max <= prev_max) break;
      prev_max = line_max;
    }
  }
  if (stats_out) *stats_out = stats;
  return acc;
}

// Reference: the same integral over every band and visible interval without truncation.
// Pieces in δ and α are ≤ min(step_per_m·m, max_step_rad); 3-point GL in δ (weight cos(δ − β)),
// 4-point GL along α. Perfect mirrors (m < opt.mirror_below_m) use the same look-up as above.
template <class Radiance>
Spectrum specular_sky_reference(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                                Radiance&& sky, double step_per_m = 0.5, double max_step_rad = 0.02,
                                const SpecularSkyOptions& opt = {}, SpecularSkyStats* stats_out = nullptr) {
  using namespace specular_detail;
  static constexpr double x3[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  static constexpr double w3[3] = {0.5555555555555556, 0.8888888888888888, 0.5555555555555556};
  static constexpr double x4[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  static constexpr double w4[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  SpecularSkyStats stats;
  Spectrum acc;
  PointContext c;
  if (trivial_case(view, view_dir, lobe, sky, opt, c, stats, acc)) {
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
    for (int p = 0; p < kd; ++p)
      for (int gd = 0; gd < 3; ++gd) {
        Line line;
        line.band = b;
        line.delta_rad = d0 + (p + 0.5) * hd + 0.5 * hd * x3[gd];
        line.u = std::cos(line.delta_rad) * f.h + std::sin(line.delta_rad) * f.z;
        line.weight = 0.5 * hd * w3[gd] * std::cos(line.delta_rad - f.beta_rad);
        Spectrum line_sum;
        for (const VisibleInterval& iv : view.visible(b)) {
          const double a0 = clamp_alpha(iv.alpha0_rad), a1 = clamp_alpha(iv.alpha1_rad);
          if (!(a1 > a0)) continue;
          const int ka = std::max(1, static_cast<int>(std::ceil((a1 - a0) / step)));
          const double ha = (a1 - a0) / ka;
          for (int q = 0; q < ka; ++q)
            for (int ga = 0; ga < 4; ++ga) {
              const double a = a0 + (q + 0.5) * ha + 0.5 * ha * x4[ga];
              if (integrand(c, line, a, sky, val, stats) > 0.0) line_sum += val * (0.5 * ha * w4[ga]);
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
