#include "geometry/visibility/visible_sky.h"

#include <algorithm>
#include <cmath>

#include "geometry/exact/occluded_sky.h"
#include "geometry/horizon/horizon_envelope.h"

namespace skyband {

namespace {
constexpr double kHalfPi = 1.57079632679489661923;
// A direction within this relative distance of a boundary of the region (in tan e), or of a
// piece's end (in diamond angle), is left to an exact test: the region's values carry rounding
// errors of ~1e-15 relative.
constexpr double kMargin = 1e-9;
}  // namespace

const char* sky_method_name(SkyMethod m) {
  switch (m) {
    case SkyMethod::exact_horizon:
      return "exact horizon";
    case SkyMethod::exact_union:
      return "exact union";
    default:
      return "bands";
  }
}

double VisibleSky::value(std::uint32_t c, double wx, double wy) const {
  if (c <= kZenith) return c == kGround ? -HUGE_VAL : HUGE_VAL;
  return circles[c][0] * wx + circles[c][1] * wy;
}

void VisibleSky::assign(const OccludedSky& sky) {
  pieces.clear();
  ids.clear();
  circles.assign(2, {0.0, 0.0});
  thread_local std::vector<std::uint32_t> remap;
  remap.assign(sky.circle_count(), 0xffffffffu);
  remap[kGround] = kGround, remap[kZenith] = kZenith;
  sky.for_each_piece([&](double t0, double w0x, double w0y, double t1, double w1x, double w1y, std::span<const std::uint32_t> b) {
    const auto first = std::uint32_t(ids.size());
    for (const std::uint32_t c : b) {
      if (remap[c] == 0xffffffffu) {
        remap[c] = std::uint32_t(circles.size());
        circles.push_back(sky.coefficients(c));
      }
      ids.push_back(remap[c]);
    }
    pieces.push_back(Piece{t0, w0x, w0y, t1, w1x, w1y, first, std::uint32_t(b.size())});
  });
}

void VisibleSky::assign(const HorizonEnvelope& env) {
  pieces.clear();
  ids.clear();
  circles.assign(2, {0.0, 0.0});
  std::uint32_t last_circle = 0xffffffffu, last_id = 0;
  env.for_each_run([&](double start, double end, std::uint32_t c) {
    std::uint32_t id = kZenith;  // kBlocked: no sky (behind a vertical face)
    if (c != HorizonEnvelope::kBlocked) {
      if (c != last_circle) {
        last_circle = c;
        last_id = std::uint32_t(circles.size());
        circles.push_back({env.value(c, 1.0, 0.0), env.value(c, 0.0, 1.0)});  // a·1 + b·0 = a exactly
      }
      id = last_id;
    }
    // Pieces cut at the edges of the occluded sky's 32 segments (multiples of 1/8 in t, exact), as
    // the exact union's are: each spans less than π, as arcs must, and an open sky is the same
    // pieces whichever exact method computed it (so its quadratures agree bit for bit).
    for (double u0 = start; u0 < end;) {
      const double u1 = std::min(end, (std::floor(u0 * 8) + 1) / 8);
      Piece p{u0, 0, 0, u1, 0, 0, std::uint32_t(ids.size()), 2};
      diamond_direction(u0, p.w0x, p.w0y);
      diamond_direction(u1, p.w1x, p.w1y);
      ids.push_back(kGround);
      ids.push_back(id);
      pieces.push_back(p);
      u0 = u1;
    }
  });
}

void VisibleSky::fan(std::vector<SkyFanTriangle>& out) const {
  out.clear();
  const auto dir = [&](std::uint32_t c, double wx, double wy) { return Vec3(wx, wy, value(c, wx, wy)).normalized(); };
  for (const Piece& p : pieces) {
    const std::uint32_t* b = ids.data() + p.first;
    for (std::uint32_t k = 1; k < p.count; k += 2) {
      if (b[k] == kZenith) break;
      out.push_back({dir(b[k], p.w0x, p.w0y), dir(b[k], p.w1x, p.w1y), 1.0});
      if (k + 1 < p.count && b[k + 1] != kZenith) out.push_back({dir(b[k + 1], p.w0x, p.w0y), dir(b[k + 1], p.w1x, p.w1y), -1.0});
    }
  }
}

SkyFactors VisibleSky::integrate(const Vec3& n) const {
  return integrate_occluded_sky(
      n,
      [&](auto&& f) {
        for (const Piece& p : pieces)
          f(p.w0x, p.w0y, p.w1x, p.w1y, std::span<const std::uint32_t>(ids.data() + p.first, p.count));
      },
      [&](std::uint32_t c, double wx, double wy) { return value(c, wx, wy); });
}

const VisibleSky::Piece& VisibleSky::piece_at(double t) const {
  std::size_t lo = 0, n = pieces.size();
  while (n > 1) {
    const std::size_t half = n / 2;
    lo = pieces[lo + half].t0 <= t ? lo + half : lo;
    n -= half;
  }
  return pieces[lo];
}

int VisibleSky::lookup(const Vec3& d) const {
  if (!(d.z() > 0) || !(normal.dot(d) > 0) || pieces.empty()) return 0;
  const double h = std::sqrt(d.x() * d.x() + d.y() * d.y());
  if (!(h > 0)) {  // the zenith: covered when an interval reaches it (all round)
    const Piece& p = pieces.front();
    return ids[p.first + p.count - 1] == kZenith ? 0 : 1;
  }
  const double wx = d.x() / h, wy = d.y() / h, te = d.z() / h;
  const auto decide = [&](const Piece& p) {
    int below = 0;
    for (std::uint32_t k = 0; k < p.count; ++k) {
      const double v = value(ids[p.first + k], wx, wy);
      if (std::abs(v - te) <= kMargin * (1 + std::abs(te))) return -1;
      below += v < te;
    }
    return below % 2 == 0 ? 1 : 0;  // an even count below: in a gap
  };
  const double t = diamond_angle(d.x(), d.y());
  const std::size_t i = std::size_t(&piece_at(t) - pieces.data());
  const int here = decide(pieces[i]);
  // Near a piece's end the neighbour must agree.
  const double margin = kMargin * 4;
  if (t - pieces[i].t0 <= margin) {
    const int there = decide(pieces[(i + pieces.size() - 1) % pieces.size()]);
    if (there != here) return -1;
  }
  if (pieces[i].t1 - t <= margin) {
    const int there = decide(pieces[(i + 1) % pieces.size()]);
    if (there != here) return -1;
  }
  return here;
}

double VisibleSky::horizon_elevation(double wx, double wy) const {
  if (pieces.empty()) return 0;
  const Piece& p = piece_at(diamond_angle(wx, wy));
  const std::uint32_t top = ids[p.first + p.count - 1];
  if (top == kZenith) return kHalfPi;
  return std::max(0.0, std::atan(value(top, wx, wy)));
}

}  // namespace skyband
