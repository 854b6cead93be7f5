#pragma once
// Calculation points on a regular ground grid, none inside or under a building: what
// `skyband points grid` writes (a naive grid over a city model puts a quarter of its points
// inside buildings, where the SVF is 0 and the data silently wrong).
//
// The grid: nodes at the centres of the cells of an S-aligned raster covering the box,
// x_i = (⌊x_min/S⌋ + i + ½)·S, y_j likewise (so that a map of the results is a raster with
// pixel edges at multiples of S). At each node the column above (x_i, y_j) is examined:
//   - every triangle whose xy projection contains the node (exact orient2d, boundary included;
//     vertical triangles have none) and its height there (the plane through its corners);
//   - the highest of them is the surface: if it is ground (its material is a ground class), the
//     point stands `height_m` above it; if it is anything else (a roof, an eave, a bridge) the
//     node is under or on a building and gets no point; a node exactly on a vertical triangle's
//     footprint (on a wall) gets none either;
//   - no triangle: outside the model's ground when it has ground triangles (no point), else the
//     ground is the plane z = the model's lowest z (buildings on a flat floor without terrain).
// Each point is then checked exactly against every non-ground triangle over its xy (exact
// orient2d and orient3d, as the exact horizon's under-a-triangle test): a point that lies under
// or on one (a roof at the ground's height, the rounding of the plane's height) is dropped and
// counted.
// Normal (0, 0, 1).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "geometry/mesh/scene.h"

namespace skyband {

struct GroundGridOptions {
  double spacing_m = 10;  // S, > 0
  double height_m = 0;    // above the local ground, ≥ 0
  // x_min, y_min, x_max, y_max of the area (metres); unset: the scene's box.
  std::optional<std::array<double, 4>> bounds;
  std::size_t max_nodes = 50'000'000;  // InputError beyond (a spacing too fine for the area)
};

struct GroundGridPoint {
  Vec3 position;
  std::int64_t ix = 0, iy = 0;        // cell indices of the S-aligned raster (x_i = (ix + ½)·S)
  std::int64_t ground_triangle = -1;  // the triangle it stands on, −1 on the floor plane
};

struct GroundGrid {
  std::vector<GroundGridPoint> points;
  std::int64_t ix0 = 0, iy0 = 0;  // the first cell's indices
  std::size_t columns = 0, rows = 0;
  std::size_t under_building = 0;  // nodes under or on a non-ground surface, or on a wall
  std::size_t off_ground = 0;      // nodes where a model with ground triangles has none
  std::size_t dropped_exact = 0;   // points the final exact test found under or on a triangle
  bool floor_plane = false;        // no ground triangles: points stand on z = the lowest z
};

// `ground`: per triangle of the scene's soup, whether it is ground (empty: none is).
// Throws InputError for a spacing or height out of range, an empty area or too many nodes.
GroundGrid make_ground_grid(const Scene& scene, const std::vector<bool>& ground, const GroundGridOptions& options);

}  // namespace skyband
