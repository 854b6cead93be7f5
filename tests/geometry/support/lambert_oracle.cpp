#include "geometry/support/lambert_oracle.h"

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace skyband::oracle {

namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactPolygon = CGAL::Polygon_2<Epeck>;
using ExactPolygonWithHoles = CGAL::Polygon_with_holes_2<Epeck>;
using ExactPolygonSet = CGAL::Polygon_set_2<Epeck>;

// One upper face of the unit cube centred on P: the face plane is q·w = 1 (q = point − P), with
// in-plane axes (u, v) and u × v = w, so a polygon counter-clockwise in (u, v) is seen from P
// with a consistent orientation on every face.
struct CubeFace {
  Vec3 u, v, w;
};

const CubeFace kCubeFaces[5] = {
    {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},   // top
    {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},   // +x
    {{0, 0, 1}, {0, 1, 0}, {-1, 0, 0}},  // −x  (u × v = (0,0,1)×(0,1,0) = (−1,0,0))
    {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},   // +y  ((0,0,1)×(1,0,0) = (0,1,0))
    {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}},  // −y  ((1,0,0)×(0,0,1) = (0,−1,0))
};

// Does the plane of `polygon` (first three vertices, or any non-degenerate triple) contain P?
// Exact orientation predicate: such a polygon subtends zero solid angle and is dropped.
bool plane_contains_point(std::span<const Vec3> polygon, const Vec3& p) {
  if (polygon.size() < 3) return true;
  const Epick::Point_3 pp(p.x(), p.y(), p.z());
  const Epick::Point_3 a(polygon[0].x(), polygon[0].y(), polygon[0].z());
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    const Epick::Point_3 b(polygon[i].x(), polygon[i].y(), polygon[i].z());
    const Epick::Point_3 c(polygon[i + 1].x(), polygon[i + 1].y(), polygon[i + 1].z());
    if (CGAL::collinear(a, b, c)) continue;
    return CGAL::orientation(a, b, c, pp) == CGAL::COPLANAR;
  }
  return true;  // all vertices collinear: zero area
}

// Projects the occluder onto one cube face: clipped to the face's pyramid (4 planes through P),
// the sky half-space and the element's front half-space, then centrally projected. The clipped
// polygon is convex if the occluder is (triangles, box faces), and so is its central projection;
// taking the convex hull with exact predicates turns float round-off near-degeneracies into a
// simple polygon. Non-convex occluder polygons must be triangulated by the caller.
bool project_onto_face(std::span<const Vec3> polygon, const Vec3& p, const Vec3& n, const CubeFace& f, ExactPolygon& out) {
  Polygon3 clipped = clip_to_sky_front(polygon, p, n);
  const Vec3 planes[4] = {f.w - f.u, f.w + f.u, f.w - f.v, f.w + f.v};
  for (const Vec3& m : planes) {
    if (clipped.size() < 3) return false;
    clipped = clip_to_half_space(clipped, p, m);
  }
  if (clipped.size() < 3) return false;
  std::vector<Epick::Point_2> projected;
  projected.reserve(clipped.size());
  for (const Vec3& q_world : clipped) {
    const Vec3 q = q_world - p;
    const double depth = q.dot(f.w);
    if (!(depth > 0)) continue;  // only P itself has depth 0 inside the pyramid
    // Inside the pyramid |u|, |v| ≤ 1 up to round-off; clamp so the union stays on the face.
    projected.emplace_back(std::clamp(q.dot(f.u) / depth, -1.0, 1.0), std::clamp(q.dot(f.v) / depth, -1.0, 1.0));
  }
  std::vector<Epick::Point_2> hull;
  CGAL::convex_hull_2(projected.begin(), projected.end(), std::back_inserter(hull));
  if (hull.size() < 3) return false;
  out.clear();
  for (const auto& h : hull) out.push_back(Epeck::Point_2(h.x(), h.y()));
  return true;  // convex_hull_2 reports counter-clockwise order without collinear points
}

// Signed Lambert sum of a union boundary on cube face f, lifted back to 3D (q = u·a + v·b + w).
double lifted_contour(const ExactPolygon& poly, const Vec3& p, const Vec3& n, const CubeFace& f, std::vector<Vec3>& scratch) {
  scratch.clear();
  for (auto it = poly.vertices_begin(); it != poly.vertices_end(); ++it) {
    const double a = CGAL::to_double(it->x()), b = CGAL::to_double(it->y());
    scratch.push_back(p + a * f.u + b * f.v + f.w);
  }
  return lambert_contour_signed(p, n, scratch);
}

bool polygon_may_matter(std::span<const Vec3> polygon, const Vec3& p, const Vec3& n) {
  // Conservative float rejections (anything kept is clipped exactly afterwards): entirely below
  // the horizon of P, or entirely behind the element.
  bool above = false, front = false;
  for (const Vec3& v : polygon) {
    above = above || v.z() > p.z();
    front = front || n.dot(v - p) > 0;
  }
  return above && front;
}

}  // namespace

double lambert_contour_signed(const Vec3& p, const Vec3& n, std::span<const Vec3> polygon) {
  const std::size_t m = polygon.size();
  double sum = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const Vec3 a = polygon[i] - p;
    const Vec3 b = polygon[(i + 1) % m] - p;
    const Vec3 c = a.cross(b);
    const double c_norm = c.norm();
    if (!(c_norm > 0)) continue;                        // edge collinear with P: zero contribution
    const double gamma = std::atan2(c_norm, a.dot(b));  // angle between r_i and r_{i+1}, radians
    sum += gamma * n.dot(c) / c_norm;
  }
  return sum / (2.0 * kPi);
}

double lambert_form_factor(const Vec3& p, const Vec3& n, std::span<const Vec3> polygon) {
  return std::abs(lambert_contour_signed(p, n, polygon));
}

Polygon3 clip_to_half_space(std::span<const Vec3> polygon, const Vec3& origin, const Vec3& plane_normal) {
  Polygon3 out;
  const std::size_t m = polygon.size();
  if (m == 0) return out;
  out.reserve(m + 1);
  for (std::size_t i = 0; i < m; ++i) {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % m];
    const double da = plane_normal.dot(a - origin);
    const double db = plane_normal.dot(b - origin);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) {
      // Crossing point; t ∈ (0, 1] since the signs differ. Evaluated from the inside vertex
      // outwards so that the two orders of a shared edge give the same point.
      const double t = da / (da - db);
      out.push_back(a + t * (b - a));
    }
  }
  if (out.size() < 3) out.clear();
  return out;
}

Polygon3 clip_to_sky_front(std::span<const Vec3> polygon, const Vec3& p, const Vec3& n) {
  Polygon3 sky = clip_to_half_space(polygon, p, Vec3(0, 0, 1));
  if (sky.size() < 3) return {};
  return clip_to_half_space(sky, p, n);
}

double open_sky_view_factor(const Vec3& n) {
  return 0.5 * (1.0 + n.normalized().z());
}

Vec3 OrientedBox::corner(int k) const {
  const double lx = ((k & 1) ? 0.5 : -0.5) * size.x();
  const double ly = ((k & 2) ? 0.5 : -0.5) * size.y();
  const double lz = ((k & 4) ? 0.5 : -0.5) * size.z();
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  return centre + Vec3(c * lx - s * ly, s * lx + c * ly, lz);
}

std::vector<Polygon3> OrientedBox::faces() const {
  std::vector<Polygon3> out;
  for (int axis = 0; axis < 3; ++axis) {
    const int bi = 1 << ((axis + 1) % 3), bj = 1 << ((axis + 2) % 3);
    for (int side = 0; side < 2; ++side) {
      const int base = side ? (1 << axis) : 0;
      Polygon3 q = {corner(base), corner(base | bi), corner(base | bi | bj), corner(base | bj)};
      // (bi, bj) follow the cyclic axis order, so (q1 − q0) × (q3 − q0) points along +axis:
      // counter-clockwise seen from outside for the + side, clockwise for the − side.
      if (side == 0) std::reverse(q.begin(), q.end());
      out.push_back(std::move(q));
    }
  }
  return out;
}

double svf_single_convex_box(const Vec3& p, const Vec3& n_in, const OrientedBox& box) {
  const Vec3 n = n_in.normalized();
  double blocked = 0;
  for (const Polygon3& face : box.faces()) {
    const Vec3 outward = (face[1] - face[0]).cross(face[3] - face[0]);
    if (!(outward.dot(p - face[0]) > 0)) continue;  // back face or P in its plane
    const Polygon3 visible = clip_to_sky_front(face, p, n);
    if (visible.size() >= 3) blocked += lambert_form_factor(p, n, visible);
  }
  return open_sky_view_factor(n) - blocked;
}

// Signed solid angle of a union boundary on cube face f lifted back to 3D: a fan of Van Oosterom &
// Strackee triangles from its first vertex (the lifted polygon is planar, on the face's plane).
double lifted_solid_angle(const ExactPolygon& poly, const Vec3& p, const CubeFace& f, std::vector<Vec3>& scratch) {
  scratch.clear();
  for (auto it = poly.vertices_begin(); it != poly.vertices_end(); ++it)
    scratch.push_back(CGAL::to_double(it->x()) * f.u + CGAL::to_double(it->y()) * f.v + f.w);
  double sum = 0;
  for (std::size_t i = 1; i + 1 < scratch.size(); ++i) {
    const Vec3 &a = scratch[0], &b = scratch[i], &c = scratch[i + 1];
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    sum += 2 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la);
  }
  (void)p;
  return sum;
}

UnionSkyFactors sky_union_oracle(const Vec3& p, const Vec3& n_in, std::span<const Polygon3> occluders) {
  const Vec3 n = n_in.normalized();
  double blocked = 0, blocked_sr = 0;
  std::vector<const Polygon3*> candidates;
  for (const Polygon3& poly : occluders)
    if (polygon_may_matter(poly, p, n) && !plane_contains_point(poly, p)) candidates.push_back(&poly);
  std::vector<ExactPolygon> projected;
  std::vector<ExactPolygonWithHoles> pieces;
  std::vector<Vec3> scratch;
  for (const CubeFace& f : kCubeFaces) {
    projected.clear();
    ExactPolygon poly;
    for (const Polygon3* occ : candidates)
      if (project_onto_face(*occ, p, n, f, poly)) projected.push_back(poly);
    if (projected.empty()) continue;
    ExactPolygonSet united;
    united.join(projected.begin(), projected.end());
    pieces.clear();
    united.polygons_with_holes(std::back_inserter(pieces));
    double face_sum = 0, face_sr = 0;
    for (const ExactPolygonWithHoles& pwh : pieces) {
      // Outer boundaries are counter-clockwise and holes clockwise (CGAL convention), so the
      // signed sums of holes come out with the opposite sign and subtract.
      face_sum += lifted_contour(pwh.outer_boundary(), p, n, f, scratch);
      face_sr += lifted_solid_angle(pwh.outer_boundary(), p, f, scratch);
      for (auto h = pwh.holes_begin(); h != pwh.holes_end(); ++h) {
        face_sum += lifted_contour(*h, p, n, f, scratch);
        face_sr += lifted_solid_angle(*h, p, f, scratch);
      }
    }
    blocked += std::abs(face_sum);
    blocked_sr += std::abs(face_sr);
  }
  UnionSkyFactors out;
  out.svf = open_sky_view_factor(n) - blocked;
  out.sky_exposure = 0.5 + std::asin(std::clamp(n.z(), -1.0, 1.0)) / kPi - blocked_sr / (2 * kPi);
  return out;
}

double svf_union_oracle(const Vec3& p, const Vec3& n, std::span<const Polygon3> occluders) {
  return sky_union_oracle(p, n, occluders).svf;
}

UnionSkyFactors sky_union_oracle(const Vec3& p, const Vec3& n, const TriangleSoup& soup) {
  std::vector<Polygon3> polys;
  polys.reserve(soup.triangles.size());
  for (const auto& t : soup.triangles) polys.push_back({soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]]});
  return sky_union_oracle(p, n, polys);
}

double svf_union_oracle(const Vec3& p, const Vec3& n, const TriangleSoup& soup) {
  std::vector<Polygon3> polys;
  polys.reserve(soup.triangles.size());
  for (const auto& t : soup.triangles) polys.push_back({soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]]});
  return svf_union_oracle(p, n, polys);
}

SvfBounds svf_union_oracle_culled(const Vec3& p, const Vec3& n_in, const TriangleSoup& soup, double initial_radius_m,
                                  double target_half_width, bool front_faces_only, double max_radius_m) {
  const Vec3 n = n_in.normalized();
  double z_top = -std::numeric_limits<double>::infinity();
  for (const Vec3& v : soup.vertices) z_top = std::max(z_top, v.z());
  // Horizontal distance from P to each triangle's xy bounding box (a lower bound on the
  // horizontal distance of every point of the triangle); triangles that cannot matter at all
  // (below the horizon or behind the element) are skipped once here.
  struct Candidate {
    double distance_m;
    Polygon3 tri;
  };
  std::vector<Candidate> cands;
  for (const auto& t : soup.triangles) {
    Polygon3 tri = {soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]]};
    if (!polygon_may_matter(tri, p, n)) continue;
    if (front_faces_only && !((tri[1] - tri[0]).cross(tri[2] - tri[0]).dot(p - tri[0]) > 0)) continue;
    double lo_x = tri[0].x(), hi_x = lo_x, lo_y = tri[0].y(), hi_y = lo_y;
    for (const Vec3& v : tri) {
      lo_x = std::min(lo_x, v.x());
      hi_x = std::max(hi_x, v.x());
      lo_y = std::min(lo_y, v.y());
      hi_y = std::max(hi_y, v.y());
    }
    const double dx = std::max({lo_x - p.x(), p.x() - hi_x, 0.0});
    const double dy = std::max({lo_y - p.y(), p.y() - hi_y, 0.0});
    cands.push_back({std::hypot(dx, dy), std::move(tri)});
  }
  std::sort(cands.begin(), cands.end(), [](const Candidate& a, const Candidate& b) { return a.distance_m < b.distance_m; });

  SvfBounds result;
  double radius = initial_radius_m;
  for (;;) {
    std::vector<Polygon3> near;
    std::size_t k = 0;
    while (k < cands.size() && cands[k].distance_m < radius) near.push_back(cands[k++].tri);
    result.near_triangles = near.size();
    result.hi = svf_union_oracle(p, n, near);
    if (k == cands.size() || !(z_top > p.z())) {
      result.lo = result.hi;  // nothing dropped that could occlude: exact
      return result;
    }
    // Ring of M vertical quads inscribed in the circle of radius R (see header).
    constexpr int kRingQuads = 128;
    for (int i = 0; i < kRingQuads; ++i) {
      const double a0 = 2 * kPi * i / kRingQuads, a1 = 2 * kPi * (i + 1) / kRingQuads;
      const Vec3 c0 = p + radius * Vec3(std::cos(a0), std::sin(a0), 0);
      const Vec3 c1 = p + radius * Vec3(std::cos(a1), std::sin(a1), 0);
      const Vec3 up(0, 0, z_top - p.z());
      near.push_back({c0, c1, c1 + up, c0 + up});
    }
    result.lo = svf_union_oracle(p, n, near);
    if (result.half_width() <= target_half_width || 2 * radius > max_radius_m) return result;
    radius *= 2;
  }
}

double canyon_floor_svf(double x, double w, double h) {
  return 0.5 * (x / std::hypot(x, h) + (w - x) / std::hypot(w - x, h));
}

double canyon_wall_svf(double z, double w, double h) {
  return 0.5 * (1.0 - (h - z) / std::hypot(w, h - z));
}

double wall_ground_svf(double d, double h) {
  return 0.5 * (1.0 + d / std::hypot(d, h));
}

double parallel_rectangle_form_factor(double a, double b, double c) {
  const double A = a / c, B = b / c;
  const double sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2 * kPi);
}

double perpendicular_rectangle_form_factor(double w, double h, double c) {
  const double X = h / w, Y = c / w;
  const double r = std::hypot(X, Y);
  return (std::atan(1 / Y) - Y / r * std::atan(1 / r)) / (2 * kPi);
}

}  // namespace skyband::oracle
