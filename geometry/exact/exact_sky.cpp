#include "geometry/exact/exact_sky.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "geometry/core/exact_sign.h"
#include "geometry/visibility/visible_sky.h"

namespace skyband {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::uint32_t kNoCircle = 0xffffffffu;  // an edge in a vertical plane through the point

double node_distance2(const Aabb& box, const Vec3& p) {
  const double dx = std::max({box.lo.x() - p.x(), p.x() - box.hi.x(), 0.0});
  const double dy = std::max({box.lo.y() - p.y(), p.y() - box.hi.y(), 0.0});
  return dx * dx + dy * dy;
}

// The great circle through the point of an edge from da to db (relative to the point): tan e =
// a·w_x + b·w_y on the plane with normal da × db — the same bits whichever way round the edge is
// taken (u × v = −(v × u) exactly), so an edge shared by two occluders gives one arc. False for an
// edge in a vertical plane through the point (no azimuth range).
bool edge_circle_coefficients(const Vec3& da, const Vec3& db, double& a, double& b) {
  const Vec3 m = da.cross(db);
  if (m.z() == 0) return false;  // (no division: floating-point traps stay quiet)
  a = -m.x() / m.z(), b = -m.y() / m.z();
  return std::isfinite(a) && std::isfinite(b);
}

// A diamond angle unwrapped against t_ref, into [−2, 2].
double unwrapped(double t, double t_ref) {
  double u = t - t_ref;
  if (u > 2) u -= 4;
  if (u < -2) u += 4;
  return u;
}

}  // namespace

ExactSky::ExactSky(const Scene& scene, double surface_offset_m) : set_(scene.occluders()), offset_m_(surface_offset_m) {}

void ExactSky::insert_back_of_face() {
  const Vec3& n = n_;
  if (n.x() == 0 && n.y() == 0) {
    if (n.z() < 0) sky_.insert_full_turn(OccludedSky::kGround, OccludedSky::kZenith);
    return;
  }
  // The face's own plane: tan e = −(n_x w_x + n_y w_y)/n_z along w. Behind the face lies the sky
  // below it on the far side of the normal (n_z > 0), the whole far half (a vertical face), or
  // all the sky above it (n_z < 0).
  const double tl = diamond_angle(-n.y(), n.x()), tm = diamond_angle(-n.x(), -n.y()), tr = diamond_angle(n.y(), -n.x());
  if (n.z() > 0) {
    sky_.insert_half_turn(OccludedSky::kGround, sky_.add_circle(-n.x() / n.z(), -n.y() / n.z()), tl, tm, tr);
  } else if (n.z() == 0) {
    sky_.insert_half_turn(OccludedSky::kGround, OccludedSky::kZenith, tl, tm, tr);
  } else {
    sky_.insert_full_turn(sky_.add_circle(-n.x() / n.z(), -n.y() / n.z()), OccludedSky::kZenith);
  }
}

// Conservative: false when everything in the box is at or below the point's horizontal or behind
// its face; else the box's azimuth range and the bounds of tan e over it.
bool ExactSky::node_bounds(const Aabb& box, Bounds& out) const {
  const Vec3& p = p_;
  if (box.hi.z() <= p.z()) return false;
  const double x0 = box.lo.x() - p.x(), x1 = box.hi.x() - p.x();
  const double y0 = box.lo.y() - p.y(), y1 = box.hi.y() - p.y();
  const double z0 = box.lo.z() - p.z(), z1 = box.hi.z() - p.z();
  // Behind the face: the largest n·(c − p) over the box's corners.
  const double front =
      std::max(n_.x() * x0, n_.x() * x1) + std::max(n_.y() * y0, n_.y() * y1) + std::max(n_.z() * z0, n_.z() * z1);
  if (front < -1e-12 * (std::abs(x0) + std::abs(x1) + std::abs(y0) + std::abs(y1) + std::abs(z0) + std::abs(z1))) return false;
  const double dx = std::max({x0, -x1, 0.0}), dy = std::max({y0, -y1, 0.0});
  out.open = dx == 0 && dy == 0;
  if (out.open) return true;
  out.top = z1 / std::sqrt(dx * dx + dy * dy) * (1 + 1e-12);
  out.bottom = -kInf;
  if (z0 > 0) {
    const double fx = std::max(std::abs(x0), std::abs(x1)), fy = std::max(std::abs(y0), std::abs(y1));
    out.bottom = z0 / std::sqrt(fx * fx + fy * fy) * (1 - 1e-12);
  }
  box_azimuth_range(x0, x1, y0, y1, out.lo, out.hi);
  return true;
}

// Conservative: true when everything in the box is at or below the point's horizontal, behind
// its face, or already occluded over the box's azimuth range.
bool ExactSky::node_hidden(const Aabb& box) const {
  Bounds b;
  if (!node_bounds(box, b)) return true;
  return !b.open && sky_.hidden(b.lo, b.hi, b.top, b.bottom);
}

void ExactSky::project(const Occluder& o) {
  const Vec3& p = p_;
  const std::uint32_t k = o.count;
  std::array<Vec3, 4> d;
  bool above = false;
  double front = -kInf;
  for (std::uint32_t i = 0; i < k; ++i) {
    d[i] = o.v[i] - p;
    above = above || d[i].z() > 0;
    front = std::max(front, n_.dot(d[i]));
  }
  if (!above) return;  // at or below the horizontal plane (exact: fl(a − b) has the sign of a − b)
  if (front < 0) {     // behind the face (conservative up to rounding of a hair in front)
    double scale = 0;
    for (std::uint32_t i = 0; i < k; ++i) scale = std::max(scale, d[i].lpNorm<Eigen::Infinity>());
    if (front < -1e-12 * scale) return;
  }
  // Cull against what is already occluded: the highest elevation is at most max z / distance to
  // the xy box, over the azimuth range of the box.
  double x0 = kInf, x1 = -kInf, y0 = kInf, y1 = -kInf, zmin = kInf, zmax = -kInf;
  for (std::uint32_t i = 0; i < k; ++i) {
    x0 = std::min(x0, d[i].x()), x1 = std::max(x1, d[i].x());
    y0 = std::min(y0, d[i].y()), y1 = std::max(y1, d[i].y());
    zmin = std::min(zmin, d[i].z()), zmax = std::max(zmax, d[i].z());
  }
  const double dx = std::max({x0, -x1, 0.0}), dy = std::max({y0, -y1, 0.0});
  if (dx > 0 || dy > 0) {
    const double top = zmax / std::sqrt(dx * dx + dy * dy) * (1 + 1e-12);
    double bottom = -kInf;
    if (zmin > 0) {
      const double fx = std::max(std::abs(x0), std::abs(x1)), fy = std::max(std::abs(y0), std::abs(y1));
      bottom = zmin / std::sqrt(fx * fx + fy * fy) * (1 - 1e-12);
    }
    double lo, hi;
    box_azimuth_range(x0, x1, y0, y1, lo, hi);
    if (sky_.hidden(lo, hi, top, bottom)) return;
  }
  if (o.upper_count >= 2 && o.lower_top_z <= p.z()) {
    // A vertical polygon standing at or below the point's height (a wall): it covers the sky from
    // the ground up to its upper chain's arcs (occluder_set.h), and nothing else is needed.
    if (exact_orient2d_sign(o.v[o.across[0]], o.v[o.across[1]], p) == 0) return;  // edge-on
    ++projected_;
    std::uint32_t a = o.upper[0];
    double ta = diamond_angle(d[a].x(), d[a].y());
    double ra = 1.0 / std::sqrt(d[a].x() * d[a].x() + d[a].y() * d[a].y());
    for (std::uint32_t i = 1; i < o.upper_count; ++i) {
      const std::uint32_t b = o.upper[i];
      const double tb = diamond_angle(d[b].x(), d[b].y());
      const double rb = 1.0 / std::sqrt(d[b].x() * d[b].x() + d[b].y() * d[b].y());
      double ca, cb;
      if (edge_circle_coefficients(d[a], d[b], ca, cb))
        sky_.insert(OccludedSky::kGround, sky_.add_circle(ca, cb), ta, d[a].x() * ra, d[a].y() * ra, tb, d[b].x() * rb,
                    d[b].y() * rb);
      a = b, ta = tb, ra = rb;
    }
    return;
  }
  const int s3 = exact_orientation(o.v[0], o.v[1], o.v[2], p);
  if (s3 == 0) return;  // seen edge-on: hides a set of measure zero
  ++projected_;
  // The circle through p of each edge (i, i + 1), made once: tan e = a·w_x + b·w_y on the plane
  // with normal m = d_i × d_{i+1} (the same bits whichever triangle of a shared edge makes it).
  std::array<std::uint32_t, 4> circle;
  std::array<bool, 4> made{};
  const auto edge_circle = [&](std::uint32_t e) -> std::uint32_t {
    if (!made[e]) {
      made[e] = true;
      double a, b;
      circle[e] = edge_circle_coefficients(d[e], d[(e + 1) % k], a, b) ? sky_.add_circle(a, b) : kNoCircle;
    }
    return circle[e];  // kNoCircle: the edge lies in a vertical plane through p (no azimuth range)
  };
  std::array<double, 4> t, wx, wy;
  const auto direction = [&](std::uint32_t i) {
    const double r = 1.0 / std::sqrt(d[i].x() * d[i].x() + d[i].y() * d[i].y());
    wx[i] = d[i].x() * r, wy[i] = d[i].y() * r;
    t[i] = diamond_angle(d[i].x(), d[i].y());
  };

  const int s = o.xy_sign;
  if (s != 0) {
    std::array<int, 4> side;
    bool contains = true;
    for (std::uint32_t i = 0; i < k && contains; ++i) {
      side[i] = exact_orient2d_sign(o.v[i], o.v[(i + 1) % k], p);
      contains = side[i] * s >= 0;
    }
    if (contains) {
      // Over (or under) the point: each edge not through p's vertical bounds the sky it covers
      // from its arc up to the zenith (down to the nadir) over its azimuth range.
      const bool over = s3 * s > 0;
      for (std::uint32_t i = 0; i < k; ++i)
        if (d[i].x() != 0 || d[i].y() != 0) direction(i);
      for (std::uint32_t i = 0; i < k; ++i) {
        if (side[i] == 0) continue;
        const std::uint32_t j = (i + 1) % k;
        const std::uint32_t c = edge_circle(i);
        if (c == kNoCircle) continue;
        if (over)
          sky_.insert(c, OccludedSky::kZenith, t[i], wx[i], wy[i], t[j], wx[j], wy[j]);
        else
          sky_.insert(OccludedSky::kGround, c, t[i], wx[i], wy[i], t[j], wx[j], wy[j]);
      }
      return;
    }
  }
  // The point's xy lies outside the occluder's: its azimuth range is less than a half turn, with
  // a first vertex F and a last La (counter-clockwise), and two chains of edges between them.
  for (std::uint32_t i = 0; i < k; ++i) direction(i);
  std::array<double, 4> u;  // azimuths unwrapped around vertex 0's
  std::uint32_t f = 0, la = 0;
  for (std::uint32_t i = 0; i < k; ++i) {
    u[i] = unwrapped(t[i], t[0]);
    if (u[i] < u[f]) f = i;
    if (u[i] > u[la]) la = i;
  }
  if (f == la || exact_orient2d_sign(p, o.v[f], o.v[la]) <= 0) return;  // no azimuth range
  // The chains F → La forwards and backwards around the polygon; the one through a vertex above
  // the great circle of F and La (exact orient3d) is the upper one.
  std::array<std::uint32_t, 5> fwd, bwd;
  std::uint32_t nf = 0, nb = 0;
  for (std::uint32_t i = f;; i = (i + 1) % k) {
    fwd[nf++] = i;
    if (i == la) break;
  }
  for (std::uint32_t i = f;; i = (i + k - 1) % k) {
    bwd[nb++] = i;
    if (i == la) break;
  }
  const bool fwd_has_inner = nf > 2;
  const std::uint32_t m = fwd_has_inner ? fwd[1] : bwd[1];
  const int above_m = exact_orientation(o.v[f], o.v[la], o.v[m], p);
  if (above_m == 0) return;  // (coplanar with p: excluded above)
  const bool fwd_upper = (above_m > 0) == fwd_has_inner;
  const std::uint32_t* up = fwd_upper ? fwd.data() : bwd.data();
  const std::uint32_t* lo = fwd_upper ? bwd.data() : fwd.data();
  const std::uint32_t nu = fwd_upper ? nf : nb, nl = fwd_upper ? nb : nf;
  const auto edge_of = [&](std::uint32_t a, std::uint32_t b) { return b == (a + 1) % k ? a : b; };
  // A lower chain wholly at or below the horizontal (its arcs, shorter than π between points below
  // it, stay below): the occluder covers from the ground up, and its lower arcs are not needed.
  bool grounded = true;
  for (std::uint32_t i = 0; i < nl; ++i) grounded = grounded && d[lo[i]].z() <= 0;
  std::uint32_t iu = 0, il = 0, at = f;
  double x = u[f];
  while (iu + 1 < nu && il + 1 < nl) {
    const double eu = u[up[iu + 1]], el = u[lo[il + 1]];
    const double next = std::min(eu, el);
    const std::uint32_t next_vertex = eu <= el ? up[iu + 1] : lo[il + 1];
    if (next > x) {
      const std::uint32_t cl = grounded ? OccludedSky::kGround : edge_circle(edge_of(lo[il], lo[il + 1]));
      const std::uint32_t cu = edge_circle(edge_of(up[iu], up[iu + 1]));
      if (cl != kNoCircle && cu != kNoCircle)
        sky_.insert(cl, cu, t[at], wx[at], wy[at], t[next_vertex], wx[next_vertex], wy[next_vertex]);
      x = next;
      at = next_vertex;
    }
    if (eu <= next) ++iu;
    if (el <= next) ++il;
  }
}

// Is the point strictly above (side > 0) or below (side < 0) the plane of every member? The
// patch's plane bounds decide most cases; else each member's exact orient3d.
bool ExactSky::beyond_every_plane(const HeightPatch& patch, int side) const {
  const Vec3& p = p_;
  if (strictly_beyond_every_plane(patch, p.x(), p.y(), p.z(), side)) return true;
  if (side > 0 ? p.z() <= patch.box.lo.z() : p.z() >= patch.box.hi.z()) return false;  // not beyond the lowest (highest) vertex
  const std::uint32_t* member = set_.height_patches.members.data() + patch.first_member;
  for (std::uint32_t j = 0; j < patch.member_count; ++j) {
    const Occluder& o = set_.occluders[member[j]];
    // orient3d · xy orientation > 0: the member is over the point (the point below its plane).
    if (exact_orientation(o.v[0], o.v[1], o.v[2], p) * o.xy_sign != -side) return false;
  }
  return true;
}

// The exact side of p of every member's plane into patch_side_ (+1 above, −1 below); false when
// p lies in one of them.
bool ExactSky::member_sides(const HeightPatch& patch) {
  patch_side_.resize(patch.member_count);
  const std::uint32_t* member = set_.height_patches.members.data() + patch.first_member;
  for (std::uint32_t j = 0; j < patch.member_count; ++j) {
    const Occluder& o = set_.occluders[member[j]];
    const int s = exact_orientation(o.v[0], o.v[1], o.v[2], p_) * o.xy_sign;
    if (s == 0) return false;
    patch_side_[j] = s > 0 ? -1 : 1;  // orient3d · xy orientation > 0: p below the plane
  }
  return true;
}

// A silhouette edge's end points (azimuth, unwrapped against t_ref, direction) and circle; false
// when the edge has no circle (it lies in a vertical plane through p).
bool ExactSky::silhouette_arc(const PatchEdge& edge, double t_ref, ArcVertex& a, ArcVertex& b, std::uint32_t& circle) {
  const Vec3 da = edge.a - p_, db = edge.b - p_;
  double ca, cb;
  if (!edge_circle_coefficients(da, db, ca, cb)) return false;
  circle = sky_.add_circle(ca, cb);
  const auto vertex = [&](const Vec3& dv, ArcVertex& w) {
    const double r = 1.0 / std::hypot(dv.x(), dv.y());
    w.wx = dv.x() * r, w.wy = dv.y() * r;
    w.t = diamond_angle(dv.x(), dv.y());
    w.u = unwrapped(w.t, t_ref);
  };
  vertex(da, a);
  vertex(db, b);
  return true;
}

// Unites, over the overlap of two arc chains' azimuth ranges (vertices in increasing unwrapped
// azimuth u, one circle per segment), everything between them: in each sub-range from the lower
// to the higher, split where they cross (the chord between the ends' directions cut where the
// circles' difference, linear in the direction, is zero). False when some sub-range could not be
// claimed (a segment without a circle, or a crossing that rounding puts outside its sub-range).
// `order` > 0 (< 0) when A (B) is known to be the lower one throughout: nothing is compared.
bool ExactSky::insert_between(const std::vector<ArcVertex>& A, const std::vector<std::uint32_t>& ca,
                              const std::vector<ArcVertex>& B, const std::vector<std::uint32_t>& cb, int order) {
  if (A.size() < 2 || B.size() < 2) return true;
  const double start = std::max(A.front().u, B.front().u), end = std::min(A.back().u, B.back().u);
  if (!(start < end)) return true;
  std::size_t i = 0, j = 0;
  while (i + 2 < A.size() && A[i + 1].u <= start) ++i;
  while (j + 2 < B.size() && B[j + 1].u <= start) ++j;
  ArcVertex at = A.front().u >= B.front().u ? A.front() : B.front();
  bool claimed = true;
  while (i + 1 < A.size() && j + 1 < B.size() && at.u < end) {
    const ArcVertex& na = A[i + 1];
    const ArcVertex& nb = B[j + 1];
    const ArcVertex next = na.u <= nb.u ? na : nb;
    if (next.u > at.u) {
      const std::uint32_t c1 = ca[i], c2 = cb[j];
      if (c1 == kNoCircle || c2 == kNoCircle) {
        claimed = false;
      } else {
        const double d0 = order != 0 ? -order : sky_.value(c1, at.wx, at.wy) - sky_.value(c2, at.wx, at.wy);
        const double d1 = order != 0 ? -order : sky_.value(c1, next.wx, next.wy) - sky_.value(c2, next.wx, next.wy);
        if (d0 <= 0 && d1 <= 0) {
          sky_.insert(c1, c2, at.t, at.wx, at.wy, next.t, next.wx, next.wy);
        } else if (d0 >= 0 && d1 >= 0) {
          sky_.insert(c2, c1, at.t, at.wx, at.wy, next.t, next.wx, next.wy);
        } else {
          // d0 and d1 of opposite signs: the zero of d along the chord, d1·w0 − d0·w1 up to sign.
          const double s = d1 > 0 ? 1.0 : -1.0;
          double cx = s * (d1 * at.wx - d0 * next.wx), cy = s * (d1 * at.wy - d0 * next.wy);
          const double r = 1.0 / std::hypot(cx, cy);
          cx *= r, cy *= r;
          const double tc = diamond_angle(cx, cy);
          const double uc = at.u + unwrapped(tc, at.t);
          if (!(uc > at.u && uc < next.u) || !std::isfinite(r)) {
            claimed = false;
          } else {
            const std::uint32_t lo0 = d0 < 0 ? c1 : c2, hi0 = d0 < 0 ? c2 : c1;
            sky_.insert(lo0, hi0, at.t, at.wx, at.wy, tc, cx, cy);
            sky_.insert(hi0, lo0, tc, cx, cy, next.t, next.wx, next.wy);
          }
        }
      }
      at = next;
    }
    if (na.u <= next.u) ++i;
    if (nb.u <= next.u) ++j;
  }
  return claimed;
}

bool ExactSky::project_patch(const HeightPatch& patch) {
  const Vec3& p = p_;
  const Aabb& box = patch.box;
  if (node_hidden(box)) return true;  // every occluder of it hidden, as node_hidden would find each
  const std::uint32_t k = patch.vertex_count;
  const Vec3* v = set_.height_patches.vertices.data() + patch.first_vertex;
  patch_d_.resize(k);
  patch_circle_.assign(k, kNoCircle);
  for (std::uint32_t i = 0; i < k; ++i) patch_d_[i] = v[i] - p;
  const std::vector<Vec3>& d = patch_d_;
  // Where p's xy lies: strictly outside (an edge with p on its right), strictly inside, or on the
  // boundary (then nothing is claimed: the occluders are projected one by one).
  bool outside = false, on_boundary = false;
  for (std::uint32_t i = 0; i < k && !outside; ++i) {
    const int s = exact_orient2d_sign(v[i], v[(i + 1) % k], p);
    outside = s < 0;
    on_boundary = on_boundary || s == 0;
  }
  if (!outside && on_boundary) return false;
  const auto edge_circle = [&](std::uint32_t e) -> std::uint32_t {
    if (patch_circle_[e] == kNoCircle) {
      double a, b;  // as project(): the same bits from either side
      if (edge_circle_coefficients(d[e], d[(e + 1) % k], a, b)) patch_circle_[e] = sky_.add_circle(a, b);
    }
    return patch_circle_[e];
  };
  ++patches_projected_;
  if (!outside) {
    // Over or under p: the member whose xy holds p's tells which (exact orient3d).
    int over = 0;
    const std::uint32_t* member = set_.height_patches.members.data() + patch.first_member;
    for (std::uint32_t j = 0; j < patch.member_count && over == 0; ++j) {
      const Occluder& o = set_.occluders[member[j]];
      bool contains = true;
      for (std::uint32_t i = 0; i < o.count && contains; ++i)
        contains = exact_orient2d_sign(o.v[i], o.v[(i + 1) % o.count], p) * o.xy_sign >= 0;
      if (!contains) continue;
      const int s3 = exact_orientation(o.v[0], o.v[1], o.v[2], p);
      if (s3 == 0) return false;  // p on the surface
      over = s3 * o.xy_sign > 0 ? 1 : -1;
    }
    if (over == 0) return false;
    for (std::uint32_t i = 0; i < k; ++i) {
      const std::uint32_t j = (i + 1) % k;
      const std::uint32_t c = edge_circle(i);
      if (c == kNoCircle) continue;
      const double ri = 1.0 / std::hypot(d[i].x(), d[i].y()), rj = 1.0 / std::hypot(d[j].x(), d[j].y());
      const double ti = diamond_angle(d[i].x(), d[i].y()), tj = diamond_angle(d[j].x(), d[j].y());
      if (over > 0)
        sky_.insert(c, OccludedSky::kZenith, ti, d[i].x() * ri, d[i].y() * ri, tj, d[j].x() * rj, d[j].y() * rj);
      else
        sky_.insert(OccludedSky::kGround, c, ti, d[i].x() * ri, d[i].y() * ri, tj, d[j].x() * rj, d[j].y() * rj);
    }
    if (beyond_every_plane(patch, -over)) return true;
    // Members on both sides of p: the elevation turns only at silhouette edges, so from over
    // (under) the patch the nadir (zenith) up to each silhouette edge's arc is occluded too, and
    // with the boundary that is the whole projection.
    if (!member_sides(patch)) return false;
    for (std::uint32_t e = 0; e < patch.edge_count; ++e) {
      const PatchEdge& edge = set_.height_patches.edges[patch.first_edge + e];
      if (patch_side_[edge.member[0]] == patch_side_[edge.member[1]]) continue;
      if (exact_orient2d_sign(edge.a, edge.b, p) == 0) {
        if (strictly_between_xy(edge.a, p, edge.b)) return false;  // through p's vertical
        continue;                                                  // seen edge-on: no azimuth range
      }
      ArcVertex a, b;
      std::uint32_t c;
      if (!silhouette_arc(edge, 0, a, b, c)) return false;
      if (over > 0)
        sky_.insert(c, OccludedSky::kZenith, a.t, a.wx, a.wy, b.t, b.wx, b.wy);
      else
        sky_.insert(OccludedSky::kGround, c, a.t, a.wx, a.wy, b.t, b.wx, b.wy);
    }
    return true;
  }
  // Outside: the azimuth range (less than a half turn) from its first vertex f to its last la,
  // and the two boundary chains between them; in each azimuth everything between the chains' arcs
  // is occluded, and with the silhouette edges' intervals that is the whole projection.
  const bool above_all = beyond_every_plane(patch, +1);
  const bool below_all = !above_all && beyond_every_plane(patch, -1);
  patch_t_.resize(k);
  patch_u_.resize(k);
  std::uint32_t f = 0, la = 0;
  for (std::uint32_t i = 0; i < k; ++i) {
    patch_t_[i] = diamond_angle(d[i].x(), d[i].y());
    patch_u_[i] = unwrapped(patch_t_[i], patch_t_[0]);
    if (patch_u_[i] < patch_u_[f]) f = i;
    if (patch_u_[i] > patch_u_[la]) la = i;
  }
  if (f == la) return false;
  // The forward chain f, f + 1, …, la (counter-clockwise round the patch) is the near one when p
  // lies right of its edges.
  int forward_side = 0;
  for (std::uint32_t i = f; i != la && forward_side == 0; i = (i + 1) % k)
    forward_side = exact_orient2d_sign(v[i], v[(i + 1) % k], p);
  if (forward_side == 0) return false;
  const bool forward_near = forward_side < 0;
  const auto chain = [&](bool forward, std::vector<ArcVertex>& out, std::vector<std::uint32_t>& circles) {
    out.clear(), circles.clear();
    for (std::uint32_t i = f;; i = forward ? (i + 1) % k : (i + k - 1) % k) {
      const double r = 1.0 / std::hypot(d[i].x(), d[i].y());
      out.push_back({patch_u_[i], patch_t_[i], d[i].x() * r, d[i].y() * r});
      if (i == la) break;
      circles.push_back(edge_circle(forward ? i : (i + k - 1) % k));
    }
  };
  chain(forward_near, near_, near_circles_);
  chain(!forward_near, far_, far_circles_);
  // Beyond every member's plane the nearer chain is the lower (above) or the upper (below) one.
  if (above_all || below_all) return insert_between(near_, near_circles_, far_, far_circles_, above_all ? 1 : -1);
  if (!member_sides(patch)) {  // p in a member's plane: the chains' interval, and the members after it
    insert_between(near_, near_circles_, far_, far_circles_, 0);
    return false;
  }
  // Members on both sides of p: along each sight line the elevation turns only at silhouette
  // edges, so the projection is everything between the near chain's arc and the far chain's or a
  // silhouette edge's.
  bool claimed = insert_between(near_, near_circles_, far_, far_circles_, 0);
  for (std::uint32_t e = 0; e < patch.edge_count; ++e) {
    const PatchEdge& edge = set_.height_patches.edges[patch.first_edge + e];
    if (patch_side_[edge.member[0]] == patch_side_[edge.member[1]]) continue;
    if (exact_orient2d_sign(edge.a, edge.b, p) == 0) continue;  // seen edge-on: no azimuth range
    ArcVertex sa, sb;
    std::uint32_t c;
    if (!silhouette_arc(edge, patch_t_[0], sa, sb, c)) {
      claimed = false;
      continue;
    }
    if (sa.u > sb.u) std::swap(sa, sb);
    edge_arc_[0] = sa, edge_arc_[1] = sb;
    edge_circle_[0] = c;
    claimed = insert_between(near_, near_circles_, edge_arc_, edge_circle_, 0) && claimed;
  }
  return claimed;
}

void ExactSky::walk() {
  const std::vector<BvhNode>& nodes = set_.nodes;
  if (nodes.empty()) return;
  // A bucket queue over the squared elevation bound in quarter-octaves, highest first; last in,
  // first out within one (as the exact horizon's walk, geometry/horizon/horizon_svf.cpp).
  const auto bucket_of = [&](const Aabb& b) {
    const double d2 = node_distance2(b, p_), dz = b.hi.z() - p_.z();
    if (!(d2 > 0)) return 127;  // over the point's xy: first
    if (!(dz > 0)) return 0;
    const auto quarter_octaves = int(std::bit_cast<std::uint64_t>(dz * dz / d2) >> 50);
    return std::clamp(quarter_octaves - 4 * 1023 + 84, 1, 126);
  };
  for (auto& b : buckets_) b.clear();
  std::uint64_t filled[2] = {0, 0};
  const auto push = [&](std::uint32_t c) {
    const BvhNode& node = nodes[c];
    if (node.count == 0) {
      __builtin_prefetch(&nodes[node.first]);
      __builtin_prefetch(reinterpret_cast<const char*>(nodes.data() + node.first + 2) - 1);
    } else {
      __builtin_prefetch(&set_.occluders[node.first]);
    }
    const int b = bucket_of(node.box);
    buckets_[b].push_back(c);
    filled[b >> 6] |= std::uint64_t(1) << (b & 63);
  };
  // Nodes hidden only if the gaps below the highest interval closed are deferred; when the queue
  // runs dry, each is tested against the union as it is then, and those still not hidden go back,
  // to be opened.
  // So a node is skipped only when the exact test hides it: the result does not depend on the
  // deferral, which only changes the order (a terrain's far triangles wait until the near ones
  // have closed the gaps under it).
  if (opened_.size() != nodes.size()) opened_.assign(nodes.size(), 0);
  if (patch_seen_.size() != set_.height_patches.patches.size()) {
    patch_seen_.assign(set_.height_patches.patches.size(), 0);
    patch_whole_.assign(set_.height_patches.patches.size(), 0);
  }
  if (seen_.size() != set_.occluders.size()) seen_.assign(set_.occluders.size(), 0);
  if (++generation_ == 0) {
    std::fill(opened_.begin(), opened_.end(), 0), generation_ = 1;
    std::fill(seen_.begin(), seen_.end(), 0);
    std::fill(patch_seen_.begin(), patch_seen_.end(), 0), std::fill(patch_whole_.begin(), patch_whole_.end(), 0);
  }
  deferred_.clear();
  small_.clear();
  // One occluder (once): the walls under it first where it floats above the point (so that a
  // roof finds the wall under its eave in the union and joins it, instead of floating above it
  // until the wall comes), then a height patch's boundary (once), then the occluder unless that
  // was all.
  const auto project_once = [&](std::uint32_t k) {
    if (seen_[k] == generation_) return;
    seen_[k] = generation_;
    const std::size_t before = sky_.splices();
    project(set_.occluders[k]);
    changing_ += sky_.splices() != before;
  };
  const auto supports_first = [&](std::uint32_t k) {
    const Occluder& o = set_.occluders[k];
    for (std::uint32_t i = 0; i < o.count; ++i)
      if (o.v[i].z() <= p_.z()) return;  // reaches down to the point's height
    for (std::uint32_t j = set_.support_first[k]; j < set_.support_first[k + 1]; ++j) project_once(set_.support[j]);
  };
  const auto visit = [&](std::uint32_t k) {
    if (seen_[k] == generation_) return;
    const Occluder& o = set_.occluders[k];
    if (o.patch != kNoPatch) {
      if (patch_seen_[o.patch] != generation_) {
        patch_seen_[o.patch] = generation_;
        const HeightPatch& patch = set_.height_patches.patches[o.patch];
        const std::uint32_t* member = set_.height_patches.members.data() + patch.first_member;
        for (std::uint32_t j = 0; j < patch.member_count; ++j) supports_first(member[j]);
        if (project_patch(patch)) patch_whole_[o.patch] = generation_;
      }
      if (patch_whole_[o.patch] == generation_) {
        ++skipped_;
        return;
      }
    } else if (o.xy_sign != 0) {
      supports_first(k);
    }
    project_once(k);
  };
  push(0);
  for (;;) {
    while (filled[0] | filled[1]) {
      const int b = filled[1] ? 127 - __builtin_clzll(filled[1]) : 63 - __builtin_clzll(filled[0]);
      const std::uint32_t index = buckets_[b].back();
      buckets_[b].pop_back();
      if (buckets_[b].empty()) filled[b >> 6] &= ~(std::uint64_t(1) << (b & 63));
      const BvhNode& node = nodes[index];
      ++nodes_visited_;
      Bounds nb;
      if (!node_bounds(node.box, nb)) continue;
      if (!nb.open) {
        if (sky_.hidden(nb.lo, nb.hi, nb.top, nb.bottom)) continue;
        if (opened_[index] != generation_ && sky_.hidden_if_gaps_close(nb.lo, nb.hi, nb.top)) {
          deferred_.push_back(index);
          continue;
        }
      }
      if (node.count > 0) {
        for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
          if (small_fraction_ > 0 && looks_small(set_.occluders[k])) {
            small_.push_back(k);
            continue;
          }
          visit(k);
        }
        continue;
      }
      push(node.first);
      push(node.first + 1);
    }
    if (deferred_.empty()) break;
    retest_.swap(deferred_);
    deferred_.clear();
    for (const std::uint32_t index : retest_) {
      if (node_hidden(nodes[index].box)) continue;
      opened_[index] = generation_;
      push(index);
    }
    if (!(filled[0] | filled[1])) break;
  }
  // Occluders that look small from the point go last, in the order they were met: by then the
  // large ones have built most of the union and most small ones are culled as hidden.
  for (const std::uint32_t k : small_) visit(k);
}

bool ExactSky::looks_small(const Occluder& o) const {
  // Twice the area over the squared distance of its first vertex: about twice the solid angle.
  return o.area2_m2 < small_fraction_ * (o.v[0] - p_).squaredNorm();
}

void ExactSky::compute(const QueryPoint& q, SkyFactors& out) {
  n_ = q.normal;
  p_ = q.position + offset_m_ * n_;
  projected_ = nodes_visited_ = changing_ = patches_projected_ = skipped_ = 0;
  sky_.reset();
  insert_back_of_face();
  sky_.clear_changed();
  walk();
  if (!sky_.changed()) {
    // The open sky in front of the face in closed form: SVF (1 + sin β)/2, exposure 1/2 + β/π.
    const bool horizontal = n_.x() == 0 && n_.y() == 0;
    const double beta = std::asin(std::clamp(n_.z(), -1.0, 1.0));
    out.svf = horizontal ? (n_.z() > 0 ? 1.0 : 0.0) : 0.5 * (1 + n_.z());
    out.sky_exposure = horizontal ? (n_.z() > 0 ? 1.0 : 0.0) : 0.5 + beta / kPi;
    return;
  }
  out = integrate(sky_, n_);
}

SkyFactors ExactSky::integrate(const OccludedSky& sky, const Vec3& n) {
  return integrate_occluded_sky(
      n,
      [&](auto&& f) {
        sky.for_each_piece([&](double, double w0x, double w0y, double, double w1x, double w1y,
                               std::span<const std::uint32_t> ids) { f(w0x, w0y, w1x, w1y, ids); });
      },
      [&](std::uint32_t c, double wx, double wy) { return sky.value(c, wx, wy); });
}

}  // namespace skyband
