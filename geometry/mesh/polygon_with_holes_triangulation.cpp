#include "geometry/mesh/polygon_with_holes_triangulation.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>
#include <deque>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

namespace skyband {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
// Vertex info: index into the caller's positions (the first ring index mapped to the point).
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
using ConstrainedFaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel>;
// Face info: the face's row in the winding table (one winding number per ring).
using FaceBase = CGAL::Triangulation_face_base_with_info_2<std::size_t, Kernel, ConstrainedFaceBase>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// A crossing of constraints (which would need a constructed point) throws; see the fallback.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;
using Point2 = Kernel::Point_2;
using VertexHandle = Cdt::Vertex_handle;

// Newell normal (vector area ×2) of a ring, relative to its first vertex (large projected
// coordinates would otherwise cancel catastrophically).
Vec3 newell_normal(std::span<const Vec3> positions, const std::vector<std::uint32_t>& ring) {
  const Vec3& origin = positions[ring[0]];
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0; i < ring.size(); ++i)
    n += (positions[ring[i]] - origin).cross(positions[ring[(i + 1) % ring.size()]] - origin);
  return n;
}

// Dropping axis `drop`, kept axes ordered so that the outer ring is counter-clockwise.
Point2 project(const Vec3& p, int drop, bool flip) {
  const int a = (drop + 1) % 3, b = (drop + 2) % 3;
  return flip ? Point2(p[b], p[a]) : Point2(p[a], p[b]);
}

PolygonWithHolesTriangulation outer_only(std::span<const Vec3> positions, const std::vector<std::uint32_t>& outer,
                                         bool holes_dropped) {
  PolygonTriangulation t = triangulate_polygon_with_method(positions, outer);
  return {std::move(t.triangles), t.method, holes_dropped};
}

}  // namespace

PolygonWithHolesTriangulation triangulate_polygon_with_holes(std::span<const Vec3> positions,
                                                             std::span<const std::vector<std::uint32_t>> rings) {
  if (rings.empty()) throw std::invalid_argument("triangulate_polygon_with_holes: no rings");
  for (const auto& ring : rings) {
    if (ring.size() < 3) throw std::invalid_argument("triangulate_polygon_with_holes: a ring needs at least 3 vertices");
    for (const std::uint32_t i : ring)
      if (i >= positions.size())
        throw std::invalid_argument("triangulate_polygon_with_holes: index " + std::to_string(i) + " out of range");
  }
  const std::vector<std::uint32_t>& outer = rings[0];
  if (rings.size() == 1) return outer_only(positions, outer, false);

  const Vec3 n = newell_normal(positions, outer);
  int drop = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) > std::abs(n[drop])) drop = k;
  if (!(std::abs(n[drop]) > 0.0)) return outer_only(positions, outer, false);  // zero area: fan
  const bool flip = n[drop] < 0.0;

  const std::size_t ring_count = rings.size();
  std::size_t corner_count = 0;
  for (const auto& ring : rings) corner_count += ring.size();

  Cdt cdt;
  std::vector<std::vector<VertexHandle>> handles(ring_count);
  try {
    for (std::size_t r = 0; r < ring_count; ++r) {
      handles[r].resize(rings[r].size());
      for (std::size_t i = 0; i < rings[r].size(); ++i) {
        const std::size_t before = cdt.number_of_vertices();
        handles[r][i] = cdt.insert(project(positions[rings[r][i]], drop, flip));
        // Several indices may land on one projected point: the first one names the vertex.
        if (cdt.number_of_vertices() > before) handles[r][i]->info() = rings[r][i];
      }
    }
    if (cdt.dimension() < 2) return outer_only(positions, outer, false);  // collinear: fan
    for (std::size_t r = 0; r < ring_count; ++r)
      for (std::size_t i = 0; i < rings[r].size(); ++i) {
        const VertexHandle a = handles[r][i], b = handles[r][(i + 1) % rings[r].size()];
        if (a != b) cdt.insert_constraint(a, b);
      }
  } catch (const std::exception&) {  // Intersection_of_constraints_exception: rings cross
    return outer_only(positions, outer, true);
  }

  // Net number of ring r's edges along each directed triangulation edge (a ring edge a→b may be
  // split by vertices lying on it: walk the chain of collinear vertices from a to b, exactly).
  using Key = std::tuple<const void*, const void*, std::size_t>;
  std::map<Key, int> directed;
  auto key = [](VertexHandle p, VertexHandle q, std::size_t r) {
    return Key(static_cast<const void*>(&*p), static_cast<const void*>(&*q), r);
  };
  for (std::size_t r = 0; r < ring_count; ++r)
    for (std::size_t i = 0; i < rings[r].size(); ++i) {
      const VertexHandle a = handles[r][i], b = handles[r][(i + 1) % rings[r].size()];
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
        if (next == VertexHandle() || ++guard > corner_count) return outer_only(positions, outer, true);  // be safe
        ++directed[key(w, next, r)];
        w = next;
      }
    }
  auto net_left = [&](VertexHandle p, VertexHandle q, std::size_t r) {  // r's edges p→q: left side +1
    int count = 0;
    if (auto it = directed.find(key(p, q, r)); it != directed.end()) count += it->second;
    if (auto it = directed.find(key(q, p, r)); it != directed.end()) count -= it->second;
    return count;
  };

  // Winding table: row f->info(), one column per ring; rows of unvisited faces are unknown.
  std::size_t face_count = 0;
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = face_count++;
  std::vector<int> winding(face_count * ring_count, 0);
  std::vector<char> known(face_count, 0);
  std::deque<Cdt::Face_handle> queue;
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f)
    if (cdt.is_infinite(f)) {
      known[f->info()] = 1;
      queue.push_back(f);
    }
  while (!queue.empty()) {
    const Cdt::Face_handle f = queue.front();
    queue.pop_front();
    for (int i = 0; i < 3; ++i) {
      const Cdt::Face_handle g = f->neighbor(i);
      if (known[g->info()]) continue;
      known[g->info()] = 1;
      const VertexHandle p = f->vertex(Cdt::ccw(i)), q = f->vertex(Cdt::cw(i));  // f lies left of p→q
      const bool constrained = f->is_constrained(i);
      for (std::size_t r = 0; r < ring_count; ++r)
        winding[g->info() * ring_count + r] = winding[f->info() * ring_count + r] - (constrained ? net_left(p, q, r) : 0);
      queue.push_back(g);
    }
  }

  PolygonWithHolesTriangulation result;
  result.method = PolygonTriangulationMethod::kConstrainedDelaunay;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    const int* w = &winding[f->info() * ring_count];
    if (!known[f->info()] || w[0] == 0) continue;
    bool in_hole = false;
    for (std::size_t r = 1; r < ring_count && !in_hole; ++r) in_hole = w[r] != 0;
    if (in_hole) continue;
    const std::uint32_t i0 = f->vertex(0)->info(), i1 = f->vertex(1)->info(), i2 = f->vertex(2)->info();
    // CDT faces are counter-clockwise in the projection, as the outer ring where it winds
    // positively; where it winds negatively (a self-overlapping outer ring) follow the ring.
    if (w[0] > 0)
      result.triangles.push_back({i0, i1, i2});
    else
      result.triangles.push_back({i0, i2, i1});
  }
  return result;
}

}  // namespace skyband
