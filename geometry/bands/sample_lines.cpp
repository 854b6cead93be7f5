#include "geometry/bands/sample_lines.h"

#include <algorithm>
#include <cmath>

#include "geometry/bands/sky_integral.h"

namespace skyband {

namespace {

// A visible stretch of the line between two unit directions, with the keys −a·x ≤ −b·x (−cos α:
// increasing along the line).
struct Stretch {
  Vec3 a, b;
  double ka, kb;
};

}  // namespace

// Everything is done with unit direction vectors on the line's plane, span{x, u}: a direction d on
// the line's upper half (d·u ≥ 0) is at α = atan2(d·u, d·x), so α_A < α_B ⟺
// (A·x)(B·u) − (A·u)(B·x) > 0, and angles are taken only for the end points written out.
void visible_on_sample_line(const VisibleSky& sky, const BandFrame& frame, double delta_rad, std::vector<VisibleInterval>& out) {
  if (sky.pieces.empty()) return;
  const std::size_t first = out.size();
  const double cd = std::cos(delta_rad), sd = std::sin(delta_rad);
  const Vec3 x = frame.x;
  const Vec3 u = cd * frame.h + sd * frame.z;  // ω(α) = cos α·x + sin α·u
  const Vec3 plane_normal = x.cross(u);
  // The line's point over the horizontal direction w = p·x + q·h: its horizontal part
  // cos α·x + sin α·cos δ·h must be a positive multiple of w, so d = sgn·(p·cos δ·x + q·u) with
  // sgn = sign(cos δ); the line covers the half turn sgn·q ≥ 0 (a line through the zenith,
  // cos δ = 0, covers the azimuths ±x only: every other azimuth maps to the zenith, α = π/2).
  const double sgn = cd >= 0 ? 1.0 : -1.0;
  const auto on_line = [&](double p, double q) -> Vec3 {
    if (q == 0) return p > 0 ? x : Vec3(-x);
    const Vec3 d = sgn * (p * cd * x + q * u);
    return d / d.norm();
  };
  const auto before = [&](const Vec3& a, const Vec3& b) { return a.dot(x) * b.dot(u) - a.dot(u) * b.dot(x) > 0; };
  const auto alpha = [&](const Vec3& d) { return std::atan2(std::max(0.0, d.dot(u)), d.dot(x)); };
  thread_local std::vector<Vec3> cuts;
  thread_local std::vector<Stretch> visible;
  visible.clear();
  for (const VisibleSky::Piece& piece : sky.pieces) {
    const double p0 = piece.w0x * x.x() + piece.w0y * x.y(), q0 = piece.w0x * frame.h.x() + piece.w0y * frame.h.y();
    const double p1 = piece.w1x * x.x() + piece.w1y * x.y(), q1 = piece.w1x * frame.h.x() + piece.w1y * frame.h.y();
    const bool in0 = sgn * q0 >= 0, in1 = sgn * q1 >= 0;
    if (!in0 && !in1) continue;  // (a piece spans less than a quarter turn)
    // A piece leaving the line's half turn crosses it at ±x, on the side of its middle.
    const Vec3 leave = p0 + p1 > 0 ? x : Vec3(-x);
    Vec3 a = in0 ? on_line(p0, q0) : leave, b = in1 ? on_line(p1, q1) : leave;
    if (before(b, a)) std::swap(a, b);
    if (!before(a, b)) continue;  // no length on the line
    // Crossings with the piece's boundary circles (tan e = a·w_x + b·w_y: the plane through the
    // point with normal (a, b, −1)), on the line's upper half.
    cuts.clear();
    cuts.push_back(a);
    const std::span<const std::uint32_t> ids(sky.ids.data() + piece.first, piece.count);
    for (const std::uint32_t c : ids) {
      if (c <= VisibleSky::kZenith) continue;
      Vec3 d = plane_normal.cross(Vec3(sky.circles[c][0], sky.circles[c][1], -1.0));
      if (d.dot(u) < 0) d = -d;
      const double n = d.norm();
      if (!(n > 0)) continue;
      d /= n;
      if (before(a, d) && before(d, b)) cuts.push_back(d);
    }
    cuts.push_back(b);
    // (cos α = d·x falls along the line: a consistent key for the sort)
    std::sort(cuts.begin() + 1, cuts.end() - 1, [&](const Vec3& p, const Vec3& q) { return p.dot(x) > q.dot(x); });
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      // Visible where an even number of the piece's boundaries lie below the stretch's middle
      // (B₀, the nadir, always does): a·m_x + b·m_y < m_z is tan e above the circle at m's azimuth.
      const Vec3 m = cuts[k] + cuts[k + 1];
      std::size_t below = 0;
      for (const std::uint32_t c : ids) below += sky.value(c, m.x(), m.y()) < m.z();
      if (below % 2 != 0) continue;
      const double ka = -cuts[k].dot(x), kb = -cuts[k + 1].dot(x);
      if (kb > ka) visible.push_back({cuts[k], cuts[k + 1], ka, kb});
    }
  }
  // Stretches of neighbouring pieces, or on both sides of a crossing that bounds no visible sky,
  // share their end point bit for bit (the same direction computed once): merged, and the angles
  // taken at the ends that remain.
  std::sort(visible.begin(), visible.end(), [](const Stretch& p, const Stretch& q) { return p.ka < q.ka; });
  for (std::size_t i = 0; i < visible.size();) {
    std::size_t last = i, j = i + 1;
    while (j < visible.size() && visible[j].ka <= visible[last].kb) {
      if (visible[j].kb > visible[last].kb) last = j;
      ++j;
    }
    const float f0 = static_cast<float>(std::clamp(alpha(visible[i].a), 0.0, kPi));
    const float f1 = static_cast<float>(std::clamp(alpha(visible[last].b), 0.0, kPi));
    // (ends a rounding apart, e.g. a crossing found in two pieces, meet once stored as float)
    if (out.size() > first && f0 <= out.back().alpha1_rad)
      out.back().alpha1_rad = std::max(out.back().alpha1_rad, f1);
    else if (f1 > f0)
      out.push_back({f0, f1});
    i = j;
  }
}

int sample_lines_of(const VisibleSky& sky, const SampleLineOptions& options, VisibilityCache::PointResult& out) {
  const BandFrame frame = BandFrame::make(sky.normal);
  int n = std::max(1, options.bands);
  for (int doubling = 0;; ++doubling, n *= 2) {
    out.normal = sky.normal;
    out.bands.clear();
    out.intervals.clear();
    double svf = 0, omega = 0;
    for (const Band& b : equal_weight_bands(frame, n)) {
      BandRecord r;
      r.s0 = static_cast<float>(b.s0);
      r.s1 = static_cast<float>(b.s1);
      r.delta_rad = static_cast<float>(frame.delta_at(b.s_centre()));
      r.exposure_weight = static_cast<float>(frame.delta_at(b.s1) - frame.delta_at(b.s0));
      r.first_interval = static_cast<std::uint32_t>(out.intervals.size());
      visible_on_sample_line(sky, frame, r.delta_rad, out.intervals);
      // The cache's own integrals (geometry/bands/sky_integral.cpp), on the values as stored.
      double line_svf = 0, line_omega = 0;
      for (std::size_t k = r.first_interval; k < out.intervals.size(); ++k) {
        const double a0 = clamp_alpha(out.intervals[k].alpha0_rad), a1 = clamp_alpha(out.intervals[k].alpha1_rad);
        line_svf += uniform_sky_primitive(a1) - uniform_sky_primitive(a0);
        line_omega += std::cos(a0) - std::cos(a1);
      }
      svf += (double(r.s1) - double(r.s0)) * line_svf;
      omega += double(r.exposure_weight) * line_omega;
      out.bands.push_back(r);
    }
    if (options.tolerance <= 0 || doubling >= options.max_doublings) return n;
    const double half = 0.5 * options.tolerance;
    if (std::abs(svf / kPi - sky.factors.svf) <= half && std::abs(omega / (2 * kPi) - sky.factors.sky_exposure) <= half) return n;
  }
}

}  // namespace skyband
