#pragma once
// Is the scene, seen from a point, a "column scene" — one where the exact horizon method
// (geometry/horizon/horizon_svf.h) is valid?
//
// A connected component of the triangle soup (triangles linked through exactly equal vertex
// positions) is a *column solid* when
//   1. it is a closed, consistently oriented surface: every edge belongs to exactly two of its
//      triangles, traversed in opposite directions (or to one, when the edge lies in the floor
//      plane: a floor left open), and no triangle repeats a vertex. A vertical edge may belong to
//      4, 6, ... triangles (columns meeting along a vertical line only: height-field pixels
//      touching diagonally, buildings touching at a corner) when it is traversed as often up as
//      down. The triangles reached from one another over two-triangle edges form an
//      orientation region, made outward by the sign of its own signed volume; a multi-edge must
//      be balanced within each region (every region a closed surface by itself);
//   2. with its orientation made outward, every triangle facing down (exact xy-orientation
//      predicate) lies in the plane z = z_floor, the component's lowest z.
// Going up a vertical line, the winding number of such a surface can only rise at z_floor and
// then never rises again, so the solid meets every vertical line in one segment that starts at
// its floor: a building extruded from its footprint (flat or pitched roofs, any footprint, with
// courtyards) is one; an overhang, a bridge or a floating box is not.
//
// From a point P outside every column solid with z_P ≥ the floor of every column solid it sees, and
// every other triangle at or below P's horizontal plane or hidden below the column solids' horizon, a sky direction is occluded
// exactly when it lies below the highest scene point in its azimuth (docs/geometry.md, "Exact horizon"): the sky is bounded by a
// horizon function of azimuth alone.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "geometry/mesh/scene.h"
#include "geometry/mesh/triangle_soup.h"

namespace skyband {

// An edge shared by two faces of a column solid. Seen from a point p outside the solid, face k is
// front-facing (p on its outer side) when facing_sign[k] · sign(det[a − p, b − p, c[k] − p]) > 0,
// c[k] its third vertex (ColumnScene::edge_third_vertices). For horizontal and vertical faces that
// sign has a cheaper exact form (face_kind, kind_sign), which needs no c:
//   horizontal (a, b, c[k] at one height): sign(det) = kind_sign[k] · sign(a.z − p.z);
//   vertical (xy-projection a segment):    sign(det) = kind_sign[k] · orient2d(a, b, p).
// One cache line each: what the per-point walk reads for every edge it reaches.
struct alignas(64) SilhouetteEdge {
  enum Kind : std::int8_t { kGeneral = 0, kHorizontal = 1, kVertical = 2 };
  Vec3 a, b;       // metres; a is the end with the lower welded vertex id (canonical for both faces)
  double floor_z;  // metres, the floor of its column solid
  std::int8_t facing_sign[2];
  std::int8_t face_kind[2];
  std::int8_t kind_sign[2];
};
static_assert(sizeof(SilhouetteEdge) == 64);

struct ColumnScene {
  std::size_t column_solids = 0;
  std::size_t other_components = 0;                                      // open, non-manifold, overhanging, ... components
  double min_column_floor_z = std::numeric_limits<double>::infinity();   // metres
  double max_column_floor_z = -std::numeric_limits<double>::infinity();  // metres
  double max_other_z = -std::numeric_limits<double>::infinity();         // metres, any vertex of a non-column triangle

  // Silhouette candidates: the edges of column solids whose two faces are not coplanar, not
  // vertical (their ends differ in x or y) and not wholly at or below the lowest column floor
  // (a point that high sees them at or below its horizon; a point lower than every floor sees
  // the solids' upper edges, and the method declines it), in the order of `edge_nodes`' leaves.
  std::vector<SilhouetteEdge> edges;
  std::vector<std::array<Vec3, 2>> edge_third_vertices;  // edges[i]'s faces' third vertices c[0], c[1]
  std::vector<BvhNode> edge_nodes;                       // node 0 the root; children of an inner node at first, first + 1
  // Candidates continued by another collinear candidate at an end (faces split along the edge: a
  // wall split into a grid of cells has 11 candidates along its top where one would do).
  std::size_t split_edges = 0;

  // The triangles of the other components (open, non-manifold, overhanging, …) and their BVH:
  // the method requires each to be at or below the point's horizontal plane or wholly hidden
  // below the column solids' horizon (checked per point).
  std::vector<std::uint32_t> other_triangles;  // in the order of `other_nodes`' leaves
  std::vector<BvhNode> other_nodes;            // leaves index other_triangles

  // Above this height (metres) no other component rises: there the method never declines for
  // them (it may still decline inside or under a column solid, or below a floating one).
  bool valid_from_height(double z) const { return z >= max_other_z; }
};

ColumnScene classify_column_scene(const TriangleSoup& soup);

}  // namespace skyband
