#include "lighting/specular_sky.h"

#include <algorithm>
#include <cmath>

namespace skyband::specular_detail {

namespace {
// A band split finer than this is a parameter error upstream (m tiny but above the mirror
// threshold); capping keeps the cost bounded instead of hanging.
constexpr int kMaxPiecesPerBand = 1 << 16;
}  // namespace

int line_count(const BandFrame& f, const BandRecord& b, double step_rad) {
  const double width = f.delta_at(b.s1) - f.delta_at(b.s0);
  if (!(width > 0.0) || !(step_rad > 0.0)) return 1;
  const double pieces = std::ceil(width / step_rad);
  if (pieces <= 1.0) return 1;
  return 2 * static_cast<int>(std::min(pieces, static_cast<double>(kMaxPiecesPerBand)));
}

Line band_line(const BandFrame& f, const BandRecord& b, std::size_t band, int j, int count) {
  Line line;
  line.band = band;
  if (count <= 1) {
    // The band itself: seed eq. 7 (its sample plane, weight w_b).
    line.delta_rad = b.delta_rad;
    line.weight = double(b.s1) - double(b.s0);
  } else {
    // Piece j/2 of count/2 equal-δ pieces, Gauss–Legendre node j%2: δ = mid ∓ h/(2√3),
    // weight (h/2)·cos(δ − β) (the δ-measure of N·ω dω, band_frame.h).
    const double d0 = f.delta_at(b.s0), d1 = f.delta_at(b.s1);
    const double h = (d1 - d0) / (count / 2);
    const double mid = d0 + (j / 2 + 0.5) * h;
    line.delta_rad = mid + (j % 2 == 0 ? -1.0 : 1.0) * h / (2.0 * std::sqrt(3.0));
    line.weight = 0.5 * h * std::cos(line.delta_rad - f.beta_rad);
  }
  line.u = std::cos(line.delta_rad) * f.h + std::sin(line.delta_rad) * f.z;
  return line;
}

std::size_t band_of_s(const PointVisibilityView& v, double s) {
  std::size_t lo = 0, hi = v.band_count();  // first band with s1 ≥ s
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (double(v.band(mid).s1) < s) lo = mid + 1;
    else hi = mid;
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

double nearest_alpha(const BandFrame& f, const Vec3& u, const Vec3& q) {
  const double a = std::atan2(q.dot(u), q.dot(f.x));
  if (a >= 0.0) return std::min(a, kPi);
  return a > -kPi / 2 ? 0.0 : kPi;  // q behind the half-plane: the nearer end of the semicircle
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
  return true;
}

}  // namespace skyband::specular_detail
