#pragma once
// The visible sky of one calculation point, whichever method computed it (geometry/visibility/sky_visibility.h
// chooses): everything the lighting module and the CLI need from the geometry — SVF and sky
// exposure, the irradiance integral under any sky, the exact sun test as a look-up, the horizon
// profile.
//
// The exact methods (the exact horizon of column scenes, geometry/horizon/horizon_svf.h; the exact union
// of occluders, geometry/exact/exact_sky.h) hand over the occluded sky over azimuth: pieces of diamond
// angle t (geometry/horizon/horizon_envelope.h), each shorter than a quarter turn, with the sorted list of
// great circles bounding the occluded intervals in it (B₀ = the nadir, B₁ the top of the grounded
// interval, …; the sky is visible between B₁ and B₂, B₃ and B₄, … and above the last one unless it
// is the zenith). A circle is stored by (a, b): tan e = a·w_x + b·w_y along the unit horizontal
// direction w. The band method hands over its cache view (exact α-intervals on band lines).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/bands/band_visibility.h"  // SkyFactors, QueryPoint
#include "geometry/bands/visibility_cache.h"
#include "geometry/exact/sky_fan.h"

namespace skyband {

class OccludedSky;
class HorizonEnvelope;

enum class SkyMethod : std::uint8_t {
  exact_horizon,  // closed extruded buildings seen from outside (geometry/horizon/horizon_svf.h)
  exact_union,    // any triangle soup (geometry/exact/exact_sky.h)
  bands,          // the band method (geometry/bands/band_visibility.h)
};
const char* sky_method_name(SkyMethod m);

struct VisibleSky {
  static constexpr std::uint32_t kGround = 0, kZenith = 1;  // circle ids (tan e = −∞, +∞)
  struct Piece {
    double t0, w0x, w0y;         // start: diamond angle and unit horizontal direction
    double t1, w1x, w1y;         // end
    std::uint32_t first, count;  // boundaries: ids[first .. first + count)
  };

  SkyMethod method = SkyMethod::exact_union;
  Vec3 point{0, 0, 0};   // the evaluated point (metres: the query point 1 µm in front of its face)
  Vec3 normal{0, 0, 1};  // unit
  SkyFactors factors;

  // Exact methods: the occluded sky over azimuth (empty for the band method).
  std::vector<Piece> pieces;
  std::vector<std::uint32_t> ids;
  std::vector<std::array<double, 2>> circles;  // circles[c] for ids c ≥ 2 (entries 0, 1 unused)
  // Band method: its cache view (valid while the caller's cache lives).
  const PointVisibilityView* bands = nullptr;

  bool exact() const { return method != SkyMethod::bands; }
  double value(std::uint32_t c, double wx, double wy) const;

  // Copies an occluded sky (exact union) or an envelope (exact horizon, sky above it).
  void assign(const OccludedSky& sky);
  void assign(const HorizonEnvelope& envelope);

  // The visible region as signed fans of spherical triangles (zenith, a, b) (geometry/exact/sky_fan.h):
  // per piece and visible gap, + the fan down to its lower arc, − the fan down to its upper arc
  // (none for the zenith). Exact methods only.
  void fan(std::vector<SkyFanTriangle>& out) const;

  // SVF and exposure of the region in closed form (Lambert's formula and Van Oosterom and
  // Strackee's, exact_sky.h) for the normal n.
  SkyFactors integrate(const Vec3& n) const;

  // Is the unit direction d visible? +1 yes, 0 no, −1 too close to a boundary of the region (within
  // its rounding) to say: the caller decides with an exact test. Below the horizontal or behind the
  // face: 0. Exact methods only.
  int lookup(const Vec3& d) const;

  // The highest occluded elevation (radians, ≥ 0; π/2 when the sky is covered up to the zenith) in
  // the azimuth of the unit horizontal direction w: above it the sky is visible up to the zenith.
  // Sky seen below an occluder (under a balcony or a bridge) is not counted: the profile is the
  // occluder's top there. Exact methods only.
  double horizon_elevation(double wx, double wy) const;

 private:
  const Piece& piece_at(double t) const;
};

// SVF and exposure of an occluded sky given as pieces, for the unit normal n: for_each_piece(f)
// calls f(w0x, w0y, w1x, w1y, ids) for the pieces in order of azimuth all round, value(c, wx, wy)
// is circle c's tan e (ids 0 and 1 the nadir and the zenith). One implementation for OccludedSky
// and VisibleSky.
//
// Over each piece each visible gap between a lower arc X and an upper arc Y (or the zenith) is
// the difference of two fans of spherical triangles, (Z, X(w₀), X(w₁)) − (Z, Y(w₀), Y(w₁)).
// Lambert's formula gives the projected solid angle, ½ Σ Θ_e n·ĝ_e over the boundary arcs — for the
// fan triangle of a circle, its arc a→b and the meridians Z→a and b→Z; the solid angle is Van
// Oosterom and Strackee's triangle formula. The meridian arcs at the pieces' ends cancel where the
// visible elevations continue, so they are summed only where the boundary lists change: ½·M(w)·ΔV,
// M(w) = n·(Z × w) and ΔV the change of the visible elevation Σ (e_upper − e_lower) there.
// Everything in the sky region is in front of the face (the occluded sky holds the back of the
// face), so the signed cosine integral is the SVF's.
template <class ForEachPiece, class Value>
SkyFactors integrate_occluded_sky(const Vec3& n, ForEachPiece&& for_each_piece, Value&& value) {
  constexpr std::uint32_t kZenith = 1;  // (id 0, the nadir, bounds no gap)
  constexpr double kHalfPi = 1.57079632679489661923;
  const Vec3 Z(0, 0, 1);
  const bool meridians = n.x() != 0 || n.y() != 0;
  double phi = 0, omega = 0, mer = 0;
  const auto fan = [&](std::uint32_t c, double w0x, double w0y, double w1x, double w1y, double sign) {
    if (c == kZenith) return;
    const Vec3 a = Vec3(w0x, w0y, value(c, w0x, w0y)).normalized();
    const Vec3 b = Vec3(w1x, w1y, value(c, w1x, w1y)).normalized();
    const Vec3 ab = a.cross(b);
    const double nab = ab.norm();
    if (nab > 0) phi += sign * std::atan2(nab, a.dot(b)) * n.dot(ab) / nab;
    omega += sign * 2 * std::atan2(Z.dot(ab), 1 + a.z() + a.dot(b) + b.z());
  };
  const auto visible_elevation = [&](std::span<const std::uint32_t> ids, double wx, double wy) {
    const auto e = [&](std::uint32_t c) { return c == kZenith ? kHalfPi : std::atan(value(c, wx, wy)); };
    double v = 0;
    for (std::size_t k = 1; k < ids.size(); k += 2) {
      if (ids[k] == kZenith) break;
      v += (k + 1 < ids.size() ? e(ids[k + 1]) : kHalfPi) - e(ids[k]);
    }
    return v;
  };
  // (copies: the spans handed over may not outlive the call)
  std::vector<std::uint32_t> prev, first;
  double prev_x = 0, prev_y = 0;
  bool have_prev = false;
  const auto same = [](std::span<const std::uint32_t> a, std::span<const std::uint32_t> b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
  };
  for_each_piece([&](double w0x, double w0y, double w1x, double w1y, std::span<const std::uint32_t> ids) {
    for (std::size_t k = 1; k < ids.size(); k += 2) {
      if (ids[k] == kZenith) break;
      fan(ids[k], w0x, w0y, w1x, w1y, 1.0);
      if (k + 1 < ids.size()) fan(ids[k + 1], w0x, w0y, w1x, w1y, -1.0);
    }
    if (meridians) {
      if (!have_prev)
        first.assign(ids.begin(), ids.end());
      else if (!same(prev, ids))
        mer += (-n.x() * w0y + n.y() * w0x) * (visible_elevation(ids, w0x, w0y) - visible_elevation(prev, prev_x, prev_y));
      prev.assign(ids.begin(), ids.end());
      prev_x = w1x, prev_y = w1y, have_prev = true;
    }
  });
  if (meridians && have_prev && !same(prev, first))  // the boundary at t = 0 (direction +x)
    mer += n.y() * (visible_elevation(first, 1.0, 0.0) - visible_elevation(prev, prev_x, prev_y));
  SkyFactors f;
  f.svf = std::clamp(0.5 * (phi + mer) / kPi, 0.0, 1.0);
  f.sky_exposure = std::clamp(omega / (2 * kPi), 0.0, 1.0);
  return f;
}

}  // namespace skyband
