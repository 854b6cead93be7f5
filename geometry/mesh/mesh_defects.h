#pragma once
// Degeneracy report of a triangle soup. Degenerate input is accepted by the engine (occlusion
// depends neither on orientation nor on manifoldness, see triangle_soup.h); this report says
// what is there so that users see what their mesh contains.
//
// Every count except the "as stored" ones is computed after welding exactly equal positions
// (bit-equal doubles, +0 and −0 equal), i.e. on the mesh a reader that merges identical
// coordinates would see. Edges are undirected pairs of distinct welded vertices taken from the
// triangles' three sides; a side whose two welded ends coincide is not an edge.
#include <cstddef>
#include <string>

#include "geometry/mesh/triangle_soup.h"

namespace skyband {

struct MeshDefects {
  // As stored (before welding):
  std::size_t duplicate_vertex_positions = 0;       // distinct positions stored more than once
  std::size_t vertices_in_duplicate_positions = 0;  // vertices sharing their position with another
  std::size_t unreferenced_vertices = 0;            // vertices used by no triangle
  std::size_t degenerate_index_triangles = 0;       // a vertex index repeated within a triangle
  // After welding:
  std::size_t welded_vertices = 0;                // distinct positions
  std::size_t zero_area_triangles = 0;            // exactly collinear corners (exact predicate)
  std::size_t duplicate_triangles = 0;            // same welded vertex set as an earlier triangle
  std::size_t boundary_edges = 0;                 // edges with exactly 1 triangle
  std::size_t non_manifold_edges = 0;             // edges with more than 2 triangles
  std::size_t inconsistently_oriented_edges = 0;  // edges of 2 triangles, both in one direction
  // Triangles around the vertex form more than one fan (linked through shared edges); only
  // triangles with three distinct welded vertices take part.
  std::size_t non_manifold_vertices = 0;

  bool any() const;
  // e.g. "3 duplicate positions, 4 zero-area triangles, 3 boundary edges"; "no defects" if none.
  std::string summary() const;
};

MeshDefects analyse_defects(const TriangleSoup& soup);

}  // namespace skyband
