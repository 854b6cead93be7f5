#include "lighting/integrals/specular_sky.h"

#include <algorithm>
#include <cmath>

namespace skyband::specular_detail {

namespace {
// A segment split finer than this is a parameter error upstream (m tiny but above the mirror
// threshold); capping keeps the cost bounded instead of hanging.
constexpr int kMaxPiecesPerSegment = 1 << 16;
}  // namespace

bool same_visibility(const PointVisibilityView& v, std::size_t a, std::size_t b, double lo, double hi) {
  const std::span<const VisibleInterval> x = v.visible(a), y = v.visible(b);
  std::size_t i = 0, j = 0;
  for (;;) {
    // Skip intervals wholly outside [lo, hi].
    while (i < x.size() && !(clamp_alpha(x[i].alpha1_rad) > lo && clamp_alpha(x[i].alpha0_rad) < hi)) ++i;
    while (j < y.size() && !(clamp_alpha(y[j].alpha1_rad) > lo && clamp_alpha(y[j].alpha0_rad) < hi)) ++j;
    if (i == x.size() || j == y.size()) return i == x.size() && j == y.size();
    if (std::max(clamp_alpha(x[i].alpha0_rad), lo) != std::max(clamp_alpha(y[j].alpha0_rad), lo) ||
        std::min(clamp_alpha(x[i].alpha1_rad), hi) != std::min(clamp_alpha(y[j].alpha1_rad), hi))
      return false;
    ++i;
    ++j;
  }
}

Segment segment_at(const PointContext& c, std::size_t b, int dir, double step_rad, double single_width_rad) {
  const PointVisibilityView& v = *c.view;
  Segment s;
  s.b0 = s.b1 = b;
  if (dir <= 0)
    while (s.b0 > 0 && same_visibility(v, s.b0 - 1, b, c.alpha_lo, c.alpha_hi)) --s.b0;
  if (dir >= 0)
    while (s.b1 + 1 < v.band_count() && same_visibility(v, s.b1 + 1, b, c.alpha_lo, c.alpha_hi)) ++s.b1;
  const BandFrame& f = v.frame();
  s.d0_rad = f.delta_at(v.band(s.b0).s0);
  s.d1_rad = f.delta_at(v.band(s.b1).s1);
  const double width = s.d1_rad - s.d0_rad;
  if (!(width > single_width_rad) || !(step_rad > 0.0)) {
    s.count = 1;
  } else {
    const double pieces = std::min(std::max(1.0, std::ceil(width / step_rad)), static_cast<double>(kMaxPiecesPerSegment));
    // Two Gauss–Legendre lines suffice on pieces up to two thirds of the step (their error
    // (h/σ)⁴/1440 is then ≤ 10⁻⁴ of the lobe), three beyond.
    s.nodes = width / pieces <= (2.0 / 3.0) * step_rad ? 2 : 3;
    s.count = s.nodes * static_cast<int>(pieces);
  }
  return s;
}

Line segment_line(const PointVisibilityView& v, const Segment& s, int j) {
  const BandFrame& f = v.frame();
  Line line;
  line.band = s.b0;  // every band of the segment has the same visible intervals
  if (s.count <= 1) {
    if (s.b0 == s.b1) {
      // One band: its own sample plane, weight w_b (seed eq. 7).
      line.delta_rad = v.band(s.b0).delta_rad;
    } else {
      // A merged run: the plane at its s-midpoint (the midpoint rule in the weight s).
      line.delta_rad = f.delta_at(0.5 * (double(v.band(s.b0).s0) + double(v.band(s.b1).s1)));
    }
    line.weight = double(v.band(s.b1).s1) - double(v.band(s.b0).s0);
  } else {
    // Piece j/3 of count/3 equal-δ pieces, Gauss–Legendre node j%3, weight (h/2)·w·cos(δ − β)
    // (the δ-measure of N·ω dω, band_frame.h).
    const double* x = s.nodes == 2 ? kGauss2Nodes : kGauss3Nodes;
    const double* w = s.nodes == 2 ? kGauss2Weights : kGauss3Weights;
    const double h = (s.d1_rad - s.d0_rad) / (s.count / s.nodes);
    const double mid = s.d0_rad + (j / s.nodes + 0.5) * h;
    line.delta_rad = mid + 0.5 * h * x[j % s.nodes];
    line.weight = 0.5 * h * w[j % s.nodes] * std::cos(line.delta_rad - f.beta_rad);
  }
  line.u = std::cos(line.delta_rad) * f.h + std::sin(line.delta_rad) * f.z;
  return line;
}

int nearest_line(const Segment& s, double delta_rad) {
  if (s.count <= 1 || !(s.d1_rad > s.d0_rad)) return 0;
  const int pieces = s.count / s.nodes;
  const double* xs = s.nodes == 2 ? kGauss2Nodes : kGauss3Nodes;
  const double h = (s.d1_rad - s.d0_rad) / pieces;
  const double x = (delta_rad - s.d0_rad) / h;
  const int piece = std::clamp(static_cast<int>(x), 0, pieces - 1);
  const double t = 2.0 * (x - piece) - 1.0;  // position in the piece, [−1, 1]
  int best = 0;
  for (int n = 1; n < s.nodes; ++n)
    if (std::abs(t - xs[n]) < std::abs(t - xs[best])) best = n;
  return s.nodes * piece + best;
}

std::size_t band_of_s(const PointVisibilityView& v, double s) {
  std::size_t lo = 0, hi = v.band_count();  // first band with s1 ≥ s
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (double(v.band(mid).s1) < s)
      lo = mid + 1;
    else
      hi = mid;
  }
  return std::min(lo, v.band_count() - 1);
}

double s_of_direction(const BandFrame& f, const Vec3& q) {
  double alpha, delta;
  f.angles_of(q, alpha, delta);
  if (delta < 0.0) delta = delta > -kPi / 2 ? 0.0 : kPi;  // below the horizon: nearest horizon plane
  delta = std::clamp(delta, f.delta_min_rad, f.delta_max_rad);
  return std::clamp(std::sin(delta - f.beta_rad), f.s_min, f.s_max);
}

double nearest_alpha(const BandFrame& f, const Vec3& u, const Vec3& q, double& cos_a, double& sin_a) {
  const double qu = q.dot(u), qx = q.dot(f.x);
  const double a = std::atan2(qu, qx);
  const double r = std::hypot(qu, qx);
  if (a >= 0.0 && r > 0.0) {  // atan2 ≤ π
    cos_a = qx / r;
    sin_a = qu / r;
    return a;
  }
  // q behind the half-plane: the nearer end of the semicircle (q along the plane's normal,
  // r = 0: atan2 gives 0).
  const double end = a >= 0.0 || a > -kPi / 2 ? 0.0 : kPi;
  cos_a = end == 0.0 ? 1.0 : -1.0;
  sin_a = 0.0;
  return end;
}

AlphaCells alpha_cells(double step_rad) {
  AlphaCells c;
  c.step = step_rad;
  c.half = 0.5 * step_rad;
  c.cos_half = std::cos(c.half);
  c.sin_half = std::sin(c.half);
  c.cos_d = std::cos(c.half * kGauss3Nodes[2]);
  c.sin_d = std::sin(c.half * kGauss3Nodes[2]);
  c.cos_step = std::cos(step_rad);
  c.sin_step = std::sin(step_rad);
  return c;
}

bool alpha_visible(std::span<const VisibleInterval> visible, double alpha_rad) {
  for (const VisibleInterval& iv : visible)
    if (alpha_rad >= clamp_alpha(iv.alpha0_rad) && alpha_rad <= clamp_alpha(iv.alpha1_rad)) return true;
  return false;
}

bool make_context(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe, PointContext& c) {
  const double len = view_dir.norm();
  if (!(len > 0.0) || !std::isfinite(len)) return false;
  c.view = &view;
  c.lobe = lobe;
  c.n = view.frame().normal;
  c.v = view_dir / len;
  c.n_dot_v = c.n.dot(c.v);
  if (!(c.n_dot_v > 0.0)) return false;
  c.q = 2.0 * c.n_dot_v * c.n - c.v;
  c.n_dot_x = c.n.dot(view.frame().x);
  c.v_dot_x = c.v.dot(view.frame().x);
  c.lobe_k = lobe_constants(lobe, c.n_dot_v);
  return true;
}

LobeConstants lobe_constants(const SpecularLobe& lobe, double n_dot_v) {
  LobeConstants k;
  const double m2 = lobe.roughness_m * lobe.roughness_m;
  k.inv_m2 = 1.0 / m2;
  k.scale = lobe.weight * (lobe.paper_scale ? kPaperScale : 1.0) / (4.0 * kPi * m2 * n_dot_v);
  k.n_dot_v = n_dot_v;
  return k;
}

MarchSteps march_steps(PointContext& c, const SpecularSkyOptions& opt) {
  const BandFrame& f = c.view->frame();
  const double m = c.lobe.roughness_m;
  // The lobe's shape around Q, as a Gaussian in the tangent plane at Q: standard deviation
  // σ∥ = √2·m in the plane of incidence (the reflected direction turns by 2·dθ when H tilts by
  // dθ in that plane, and the Beckmann slope spread is m/√2) and σ⊥ = (V·H)·σ∥ ≈ (N·V)·σ∥ across
  // it (it turns by 2(V·H)·dθ there): at grazing views the lobe is a thin streak. The steps
  // follow the widths the rules see: along a line (direction e_α at Q) the conditional width
  // 1/√(e_αᵀΣ⁻¹e_α); across lines (e_δ) the marginal width √(e_δᵀΣe_δ), turned into δ by the
  // line spacing sin α_Q. m_a and m_d are these widths in units of √2 (= m at normal incidence).
  double alpha_q, delta_q;
  f.angles_of(c.q, alpha_q, delta_q);
  const double sig_par = m;  // (/√2 units)
  const double sig_perp = sig_par * std::clamp(c.n_dot_v, opt.min_compression, 1.0);
  Vec3 p = c.n.cross(c.v);
  if (!(p.norm() > 1e-9)) p = std::abs(c.q.z()) < 0.9 ? c.q.cross(Vec3(0, 0, 1)) : c.q.cross(Vec3(1, 0, 0));
  p.normalize();
  const Vec3 t = p.cross(c.q).normalized();  // in the plane of incidence, ⟂ Q
  const Vec3 u_q = std::cos(delta_q) * f.h + std::sin(delta_q) * f.z;
  const Vec3 e_a = -std::sin(alpha_q) * f.x + std::cos(alpha_q) * u_q;
  const Vec3 e_d = -std::sin(delta_q) * f.h + std::cos(delta_q) * f.z;
  const double at = e_a.dot(t), ap = e_a.dot(p), dt = e_d.dot(t), dp = e_d.dot(p);
  double m_a = 1.0 / std::sqrt(at * at / (sig_par * sig_par) + ap * ap / (sig_perp * sig_perp));
  double m_d = std::sqrt(sig_par * sig_par * dt * dt + sig_perp * sig_perp * dp * dp) / std::max(std::sin(alpha_q), 1e-3);
  // The Gaussian model is a first-order picture (the lobe bends on the sphere, sin²α and G
  // reshape it): never step coarser than the isotropic width m·max(N·V, ½) (measured in
  // bench_specular, where the model alone doubled the worst errors).
  const double iso = m * std::max(c.n_dot_v, 0.5);
  m_a = std::min(m_a, iso);
  m_d = std::min(m_d, iso);
  // The lobe window: every direction within R of Q has |α − α_Q| ≤ R (α is the angle from the
  // axis x, and |∠(ω, x) − ∠(Q, x)| ≤ ∠(ω, Q)), so integrating only α ∈ [α_Q − R, α_Q + R]
  // drops nothing of the cap ∠(ω, Q) ≤ R, outside which the Beckmann factor exp(−tan²θ_h/m²)
  // with θ_h ≥ ∠(ω, Q)/2 in the plane of incidence is below e^{−R²/4m²} = 5·10⁻⁶ of its peak
  // at R = 7m (across it the lobe is narrower still).
  const double r = opt.lobe_window_per_m * m;
  c.alpha_lo = std::max(0.0, alpha_q - r);
  c.alpha_hi = std::min(kPi, alpha_q + r);
  MarchSteps s;
  s.alpha_rad = std::min(opt.alpha_step_per_m * m_a, opt.max_alpha_step_rad);
  s.delta_rad = std::min(opt.delta_step_per_m * m_d, opt.max_delta_step_rad);
  s.single_line_rad = opt.single_line_per_m * m_d;
  return s;
}

}  // namespace skyband::specular_detail

namespace skyband {

LobeWindowSky lobe_window_sky(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                              const SpecularSkyOptions& opt) {
  using namespace specular_detail;
  PointContext c;
  if (view.band_count() == 0 || lobe.weight <= 0.0 || !make_context(view, view_dir, lobe, c))
    return LobeWindowSky::kClosed;  // nothing reflected toward V (the integral is exactly 0)
  const BandFrame& f = view.frame();
  const double r = opt.lobe_window_per_m * lobe.roughness_m;
  if (!(r > 0.0 && r < kPi / 2)) return LobeWindowSky::kMixed;
  double alpha_q, delta_q;
  f.angles_of(c.q, alpha_q, delta_q);
  const double sin_ratio = std::sin(r) / std::sin(alpha_q);
  if (!(sin_ratio < 1.0) || !(sin_ratio > 0.0)) return LobeWindowSky::kMixed;  // the cap holds the pencil axis
  const double half = std::asin(sin_ratio);
  // δ_Q in [−π/2, 3π/2): the sky range lies in [0, π], so the cap's δ interval compares with it
  // without wrapping (a Q just below the horizon on the far side is near δ = π, not −π).
  if (delta_q < -kPi / 2) delta_q += 2 * kPi;
  const double d0 = delta_q - half, d1 = delta_q + half;
  if (d1 <= f.delta_min_rad || d0 >= f.delta_max_rad) return LobeWindowSky::kClosed;  // no sky in the cap
  if (d0 < f.delta_min_rad || d1 > f.delta_max_rad) return LobeWindowSky::kMixed;     // horizon or face plane
  const double a0 = alpha_q - r, a1 = alpha_q + r;                                    // inside (0, π): sin α_Q > sin R
  const std::size_t b0 = band_of_s(view, std::sin(d0 - f.beta_rad)), b1 = band_of_s(view, std::sin(d1 - f.beta_rad));
  bool open = true, closed = true;
  for (std::size_t b = b0; b <= b1; ++b) {
    bool covered = false, touched = false;
    for (const VisibleInterval& iv : view.visible(b)) {
      const double lo = clamp_alpha(iv.alpha0_rad), hi = clamp_alpha(iv.alpha1_rad);
      if (lo <= a0 && hi >= a1) covered = true;
      if (hi > a0 && lo < a1) touched = true;
    }
    open = open && covered;
    closed = closed && !touched;
    if (!open && !closed) return LobeWindowSky::kMixed;
  }
  return open ? LobeWindowSky::kOpen : LobeWindowSky::kClosed;
}

}  // namespace skyband
