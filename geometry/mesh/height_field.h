#pragma once
// A raster digital surface model (DSM) as a triangle mesh: each pixel a flat-topped column of
// its height — the scene UMEP and SAGA assume when they estimate a sky view factor raster by
// shadow casting, here meshed so that the exact methods see it.
//
// Pixel (c, r) covers the rectangle between the corners X_c = x0 + c·dx, X_{c+1} and
// Y_r = y0 + r·dy, Y_{r+1} (dx, dy signed: a north-up raster has dy < 0), each corner coordinate
// computed once from that formula, so that neighbouring pixels share corners bit for bit. The
// mesh is
//   - the top of every pixel with a height: two triangles at z = h, wound upwards;
//   - a vertical wall wherever a pixel is higher than its neighbour (or than the floor, at the
//     raster's edge and next to a pixel without height), from the lower to the higher height,
//     wound towards the lower side; its two vertical sides are split at every height the pixels
//     around that corner have between the two (and the floor), so that walls meeting at a corner
//     share edges exactly (no T-junction), and triangulated as a strip between the two sides;
//   - no floor: the surface is closed but for its boundary in the plane z = floor_z.
// Every edge is then shared by two triangles traversed in opposite directions, or lies in the
// floor plane, or is a vertical edge where pixels touch diagonally (4 triangles, balanced): the
// mesh is one column solid (geometry/horizon/column_scene.h) and points on the pixels' tops get the
// exact horizon method.
#include <cstddef>
#include <vector>

#include "geometry/mesh/triangle_soup.h"

namespace skyband {

struct HeightField {
  std::size_t columns = 0, rows = 0;
  double x0 = 0, y0 = 0;   // metres: the outer corner of pixel (0, 0)
  double dx = 1, dy = -1;  // metres per pixel along columns and rows (signed, non-zero)
  // Row-major heights (metres), rows × columns; NaN = no column (nodata).
  std::vector<double> heights;

  double height(std::size_t c, std::size_t r) const { return heights[r * columns + c]; }
  double corner_x(std::size_t c) const { return x0 + double(c) * dx; }
  double corner_y(std::size_t r) const { return y0 + double(r) * dy; }
  // The pixel's centre (metres).
  double centre_x(std::size_t c) const { return x0 + (double(c) + 0.5) * dx; }
  double centre_y(std::size_t r) const { return y0 + (double(r) + 0.5) * dy; }
};

// The lowest height of the field minus max(1 m, 1 % of its height range): a floor below every
// pixel's top. InputError when no pixel has a height.
double height_field_floor(const HeightField& field);

// The mesh described above. Material names: "top" (material 0) and "wall" (material 1).
// InputError when the field is empty, its steps are zero or not finite, a height is infinite,
// or floor_z is not below every height.
TriangleSoup height_field_mesh(const HeightField& field, double floor_z);

}  // namespace skyband
