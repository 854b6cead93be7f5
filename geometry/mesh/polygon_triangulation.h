#pragma once
// Triangulation of one polygon face (a ring of vertex indices) of a mesh file into triangles
// whose corners are the polygon's own vertices (no new vertices are ever created, so the soup
// keeps the file's coordinates verbatim).
//
// Method: the polygon is projected onto the coordinate plane that drops the dominant axis of its
// Newell normal (Newell 1972 / Sutherland et al. 1974: n = Σ (p_i − p_0) × (p_{i+1} − p_0) / 2,
// the vector area). Dropping a coordinate is exact, so every decision below is an exact
// predicate on the file's own doubles; the Newell normal (a floating-point construction) only
// chooses the axis and the orientation sign, and any axis with a non-zero component would give
// a valid projection. The projected ring's edges are inserted as constraints of a CGAL
// constrained Delaunay triangulation; each face of the triangulation gets the winding number
// of the ring around it (flood fill from the infinite face, crossing a constrained edge changes
// the winding by the net number of ring edges running along it), and the faces with a non-zero
// winding number are kept, oriented like the ring (same sign of the normal as the Newell
// normal). This handles convex, non-convex and slightly non-planar polygons, polygons touching
// themselves (keyhole polygons whose bridge is traversed twice, repeated indices) and collinear
// vertices on edges.
//
// Fallback: polygons that cannot be triangulated this way — zero Newell normal, all points
// collinear in projection, or a projected ring that crosses itself (a crossing would need a new
// vertex) — are fan-triangulated from their first vertex so that nothing is silently dropped;
// such pieces have (near) zero area or overlap and the result says so.
#include <array>
#include <cstdint>
#include <ostream>
#include <span>
#include <vector>

#include "geometry/core/vec3.h"

namespace skyband {

enum class PolygonTriangulationMethod {
  kTriangle,             // the polygon was a triangle: returned unchanged (even if degenerate)
  kConstrainedDelaunay,  // projected CDT, faces with non-zero winding number kept
  kFanZeroArea,          // fan: zero Newell normal or collinear projection (zero-area polygon)
  kFanSelfIntersecting,  // fan: the projected ring crosses itself
};

inline const char* to_string(PolygonTriangulationMethod m) {
  switch (m) {
    case PolygonTriangulationMethod::kTriangle:
      return "triangle";
    case PolygonTriangulationMethod::kConstrainedDelaunay:
      return "constrained Delaunay";
    case PolygonTriangulationMethod::kFanZeroArea:
      return "fan (zero area)";
    case PolygonTriangulationMethod::kFanSelfIntersecting:
      return "fan (self-crossing outline)";
  }
  return "?";
}
inline std::ostream& operator<<(std::ostream& os, PolygonTriangulationMethod m) {
  return os << to_string(m);
}

struct PolygonTriangulation {
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into `positions`
  PolygonTriangulationMethod method = PolygonTriangulationMethod::kTriangle;
};

// `polygon` holds indices into `positions` (≥ 3 of them; repeated indices allowed). Throws
// std::invalid_argument on fewer than 3 indices or an index out of range (callers validate
// user input first and report it as InputError).
PolygonTriangulation triangulate_polygon_with_method(std::span<const Vec3> positions, std::span<const std::uint32_t> polygon);

inline std::vector<std::array<std::uint32_t, 3>> triangulate_polygon(std::span<const Vec3> positions,
                                                                     std::span<const std::uint32_t> polygon) {
  return triangulate_polygon_with_method(positions, polygon).triangles;
}

}  // namespace skyband
