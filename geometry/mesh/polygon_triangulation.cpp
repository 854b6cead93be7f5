#include "geometry/mesh/polygon_triangulation.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace skyband {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
// Vertex info: index into the caller's positions (the first polygon index mapped to the point).
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
using ConstrainedFaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel>;
// Face info: winding number of the projected ring around the face (INT_MIN = not yet known).
using FaceBase = CGAL::Triangulation_face_base_with_info_2<int, Kernel, ConstrainedFaceBase>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Touching and overlapping constraints are fine; a crossing (which would need a constructed
// intersection point) throws, and the caller falls back to a fan.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;
using Point2 = Kernel::Point_2;
using VertexHandle = Cdt::Vertex_handle;

constexpr int kUnknownWinding = std::numeric_limits<int>::min();

// Newell normal (vector area ×2) of the ring, accumulated relative to the first vertex so that
// large projected coordinates (x ≈ 4·10⁵ m, y ≈ 6·10⁶ m) do not cancel catastrophically.
Vec3 newell_normal(std::span<const Vec3> positions, std::span<const std::uint32_t> polygon) {
  const Vec3& origin = positions[polygon[0]];
  Vec3 n = Vec3::Zero();
  const std::size_t count = polygon.size();
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 a = positions[polygon[i]] - origin;
    const Vec3 b = positions[polygon[(i + 1) % count]] - origin;
    n += a.cross(b);
  }
  return n;
}

std::vector<std::array<std::uint32_t, 3>> fan(std::span<const std::uint32_t> polygon) {
  std::vector<std::array<std::uint32_t, 3>> out;
  out.reserve(polygon.size() - 2);
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) out.push_back({polygon[0], polygon[i], polygon[i + 1]});
  return out;
}

// Projection dropping axis `drop`, with the two kept axes ordered so that the projected ring
// has positive orientation when the normal's `drop` component is positive (right-handed:
// dropping z keeps (x, y), dropping x keeps (y, z), dropping y keeps (z, x)).
Point2 project(const Vec3& p, int drop, bool flip) {
  const int a = (drop + 1) % 3;
  const int b = (drop + 2) % 3;
  return flip ? Point2(p[b], p[a]) : Point2(p[a], p[b]);
}

}  // namespace

PolygonTriangulation triangulate_polygon_with_method(std::span<const Vec3> positions, std::span<const std::uint32_t> polygon) {
  if (polygon.size() < 3) throw std::invalid_argument("triangulate_polygon: a polygon needs at least 3 vertices");
  for (const std::uint32_t i : polygon)
    if (i >= positions.size()) throw std::invalid_argument("triangulate_polygon: index " + std::to_string(i) + " out of range");

  PolygonTriangulation result;
  if (polygon.size() == 3) {
    result.triangles.push_back({polygon[0], polygon[1], polygon[2]});
    result.method = PolygonTriangulationMethod::kTriangle;
    return result;
  }

  const Vec3 n = newell_normal(positions, polygon);
  int drop = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) > std::abs(n[drop])) drop = k;
  if (!(std::abs(n[drop]) > 0.0)) {  // zero (or NaN) Newell normal: a zero-area polygon
    result.triangles = fan(polygon);
    result.method = PolygonTriangulationMethod::kFanZeroArea;
    return result;
  }
  const bool flip = n[drop] < 0.0;

  Cdt cdt;
  std::vector<VertexHandle> handles(polygon.size());
  try {
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      handles[i] = cdt.insert(project(positions[polygon[i]], drop, flip));
      // Several polygon indices may land on one projected point (repeated indices, coincident
      // positions): the first one names the triangulation vertex.
      if (std::find(handles.begin(), handles.begin() + static_cast<std::ptrdiff_t>(i), handles[i]) ==
          handles.begin() + static_cast<std::ptrdiff_t>(i))
        handles[i]->info() = polygon[i];
    }
    if (cdt.dimension() < 2) {  // every projected point on one line: zero-area polygon
      result.triangles = fan(polygon);
      result.method = PolygonTriangulationMethod::kFanZeroArea;
      return result;
    }
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const VertexHandle a = handles[i];
      const VertexHandle b = handles[(i + 1) % polygon.size()];
      if (a != b) cdt.insert_constraint(a, b);
    }
  } catch (const std::exception&) {  // Intersection_of_constraints_exception: the ring crosses itself
    result.triangles = fan(polygon);
    result.method = PolygonTriangulationMethod::kFanSelfIntersecting;
    return result;
  }

  // Net number of ring edges running along each directed triangulation edge. A ring edge a→b
  // may be split by ring vertices lying on it; walk the chain of collinear triangulation
  // vertices from a to b (exact predicates).
  std::map<std::pair<const void*, const void*>, int> directed;
  auto key = [](VertexHandle p, VertexHandle q) {
    return std::make_pair(static_cast<const void*>(&*p), static_cast<const void*>(&*q));
  };
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const VertexHandle a = handles[i];
    const VertexHandle b = handles[(i + 1) % polygon.size()];
    if (a == b) continue;
    VertexHandle w = a;
    std::size_t guard = 0;
    while (w != b) {
      VertexHandle next;
      auto vc = cdt.incident_vertices(w), done = vc;
      do {
        if (cdt.is_infinite(vc)) continue;
        const VertexHandle x = vc;
        if (x == b || (CGAL::orientation(a->point(), b->point(), x->point()) == CGAL::COLLINEAR &&
                       CGAL::collinear_are_strictly_ordered_along_line(w->point(), x->point(), b->point()))) {
          next = x;
          break;
        }
      } while (++vc != done);
      if (next == VertexHandle() || ++guard > polygon.size()) {
        // Cannot happen for a constrained edge; be safe rather than loop.
        result.triangles = fan(polygon);
        result.method = PolygonTriangulationMethod::kFanSelfIntersecting;
        return result;
      }
      ++directed[key(w, next)];
      w = next;
    }
  }
  auto net_left = [&](VertexHandle p, VertexHandle q) {
    // ring edges p→q have their left side +1 relative to the right side
    int count = 0;
    if (auto it = directed.find(key(p, q)); it != directed.end()) count += it->second;
    if (auto it = directed.find(key(q, p)); it != directed.end()) count -= it->second;
    return count;
  };

  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = kUnknownWinding;
  std::deque<Cdt::Face_handle> queue;
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f)
    if (cdt.is_infinite(f)) {
      f->info() = 0;
      queue.push_back(f);
    }
  while (!queue.empty()) {
    const Cdt::Face_handle f = queue.front();
    queue.pop_front();
    for (int i = 0; i < 3; ++i) {
      const Cdt::Face_handle g = f->neighbor(i);
      if (g->info() != kUnknownWinding) continue;
      // Edge i of f runs p→q counter-clockwise around f, so f lies on its left.
      const VertexHandle p = f->vertex(Cdt::ccw(i));
      const VertexHandle q = f->vertex(Cdt::cw(i));
      g->info() = f->info() - net_left(p, q);
      queue.push_back(g);
    }
  }

  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    const int winding = f->info();
    if (winding == 0 || winding == kUnknownWinding) continue;
    const std::uint32_t i0 = f->vertex(0)->info(), i1 = f->vertex(1)->info(), i2 = f->vertex(2)->info();
    // CDT faces are counter-clockwise in the projection, i.e. oriented like the ring where the
    // ring winds positively; where it winds negatively the piece is flipped to follow the ring.
    if (winding > 0)
      result.triangles.push_back({i0, i1, i2});
    else
      result.triangles.push_back({i0, i2, i1});
  }
  result.method = PolygonTriangulationMethod::kConstrainedDelaunay;
  return result;
}

}  // namespace skyband
