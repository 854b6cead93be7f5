#pragma once
// Triangulation of one planar-ish polygon with holes (an outer ring and inner rings of vertex
// indices, as in CityJSON, CityGML or OGC simple features) into triangles whose corners are the
// rings' own vertices (no new vertex is created, so a reader keeps the file's coordinates).
//
// Method (the one of polygon_triangulation.h, extended to several rings): all rings are
// projected onto the coordinate plane that drops the dominant axis of the OUTER ring's Newell
// normal (dropping a coordinate is exact, so every decision is an exact predicate on the input
// doubles). Every ring's edges are inserted as constraints of one CGAL constrained Delaunay
// triangulation. Each face of the triangulation gets, for every ring r, the winding number w_r
// of r around it (flood fill from the infinite face; crossing a constrained edge changes w_r by
// the net number of r's edges along it). A face is kept iff
//     w_outer ≠ 0  and  w_hole = 0 for every inner ring,
// i.e. inside the outer ring and outside every hole whatever the holes' orientation (real files
// do not always wind inner rings opposite to the outer one) and even if holes overlap or touch
// the outer ring or each other. Kept faces are oriented like the outer ring.
//
// Fallbacks (reported in the result, never silent):
//  - no inner rings: exactly triangulate_polygon_with_method (polygon_triangulation.h);
//  - a zero-area outer ring (zero Newell normal, or every projected point on one line): the
//    outer ring is fan-triangulated, holes ignored (there is no area to cut them from);
//  - rings crossing each other or themselves (a crossing point would be a new vertex): the
//    outer ring alone is triangulated by triangulate_polygon_with_method and `holes_dropped`
//    is set — the surface is filled rather than lost (a lost surface leaks sky light; a filled
//    hole in a wall is usually covered by a Window/Door surface of the same model anyway).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/core/vec3.h"
#include "geometry/mesh/polygon_triangulation.h"

namespace skyband {

struct PolygonWithHolesTriangulation {
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into `positions`
  // kTriangle / kConstrainedDelaunay / kFan* as for one ring; with holes kConstrainedDelaunay
  // unless a fallback above applied.
  PolygonTriangulationMethod method = PolygonTriangulationMethod::kTriangle;
  bool holes_dropped = false;  // rings crossed: the outer ring was triangulated without its holes
};

// rings[0] is the outer ring, rings[1..] the inner rings; each ring holds ≥ 3 indices into
// `positions` (repeated indices allowed). Throws std::invalid_argument on an empty `rings`, a
// ring of fewer than 3 indices or an index out of range (callers validate user input first and
// report it as InputError).
PolygonWithHolesTriangulation triangulate_polygon_with_holes(std::span<const Vec3> positions,
                                                             std::span<const std::vector<std::uint32_t>> rings);

}  // namespace skyband
