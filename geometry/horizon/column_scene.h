#pragma once
// Is the scene, seen from a point, a "column scene" — one where the exact horizon method
// (geometry/horizon/horizon_svf.h) is valid?
//
// The candidates are the soup's surfaces: triangles linked through edges in exactly two triangles
// (exactly equal vertex positions). A surface is a *column solid* when
//   1. no edge of it lies in three triangles, or in four or more unless vertical and traversed as
//      often up as down once oriented (columns meeting along a vertical line only: height-field
//      pixels touching diagonally, buildings touching at a corner); edges in one triangle are open;
//   2. it is orientable (the files' windings need not agree), with a non-zero signed volume whose
//      sign makes the orientation outward.
// Its *base floor* is its lowest height raised to the highest end of its open edges (their cap
// lies below it): the floor plane of a building on a flat floor, modelled or left open. Its
// down-facing triangles (exact xy-orientation predicate) above that — a floor following the
// terrain, the soffit of an overhang — raise the *floor height* of the parts of the silhouette
// candidates over them (in xy). Along a vertical line meeting none of them above a height, the
// surface, capped below, has only up-facing and vertical triangles there, so going up the line
// its winding number never rises: a building extruded from its footprint (flat or pitched roofs,
// any footprint, with courtyards) keeps every edge at its floor.
// Triangles repeating a vertex are left out (no area, nothing added to any boundary).
//
// From a point P outside every column solid, at or above the floor height of every candidate that
// is not hidden below the envelope, and every other triangle at or below P's horizontal plane or hidden below the column solids'
// horizon, a sky direction is occluded exactly when it lies below the highest scene point in its azimuth (docs/geometry.md,
// "Exact horizon"): the sky is bounded by a horizon function of azimuth alone.
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
  double floor_z;  // metres, its floor height (its solid's base floor, or a soffit's top under it)
  std::int8_t facing_sign[2];
  std::int8_t face_kind[2];
  std::int8_t kind_sign[2];
};
static_assert(sizeof(SilhouetteEdge) == 64);

// The part of a silhouette candidate over a down-facing triangle of its solid above the solid's
// base floor: parameters along it from a (0) to b (1), widened to hold the exact range, and the
// triangle's top.
struct RaisedPart {
  double t0, t1;
  double floor_z;  // metres
};

struct ColumnScene {
  std::size_t column_solids = 0;     // surfaces (triangles linked through two-triangle edges) that are column solids
  std::size_t other_components = 0;  // surfaces that are not column solids (non-manifold, not orientable, flat)
  double min_column_floor_z = std::numeric_limits<double>::infinity();   // metres, the lowest base floor
  double max_column_floor_z = -std::numeric_limits<double>::infinity();  // metres, the highest floor height
  double max_other_z = -std::numeric_limits<double>::infinity();         // metres, any vertex of a non-column triangle

  // Silhouette candidates: the edges of column solids whose two faces are not coplanar, and their
  // open edges (one face, stored twice with opposite facing signs: never skipped), not vertical
  // (their ends differ in x or y) and not wholly at or below min_column_floor_z (the method
  // declines points lower than that; higher ones see them at or below their horizon), in the
  // order of `edge_nodes`' leaves.
  std::vector<SilhouetteEdge> edges;
  std::vector<std::array<Vec3, 2>> edge_third_vertices;  // edges[i]'s faces' third vertices c[0], c[1]
  std::vector<BvhNode> edge_nodes;                       // node 0 the root; children of an inner node at first, first + 1
  // Per candidate: its solid's base floor, and its raised parts raised_parts[raised_first[i] ..
  // raised_first[i + 1]); SilhouetteEdge::floor_z is the highest of them all. From a point below
  // floor_z but at or above the base, the parts higher than the point wait (horizon_svf.cpp) and
  // the rest of the edge counts.
  std::vector<double> edge_base_floor_z;
  std::vector<std::uint32_t> raised_first;
  std::vector<RaisedPart> raised_parts;
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
