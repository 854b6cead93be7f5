#pragma once
// The building of the paper's Figures 5 and 6 (seed; method.md §7), modelled procedurally: a
// 24 m × 14 m block of five 3.3 m storeys with recessed windows (0.2 m reveals, a 7 cm frame and
// glass as separate materials), a flat roof, a 10 km ground square, and a 22 m neighbouring
// block to the south-east that hides part of the eastern sky and, under a morning sun, shades
// part of the south facade. Metres, x east, y north, z up; the building is centred on the origin.
//
// Material slots (TriangleSoup::material_names): "wall" (facades and window reveals), "frame",
// "glass", "roof", "ground", "neighbour". Every facade is a conforming grid of quads (no
// T-junctions), so primary rays and sample planes never meet a crack.
#include "geometry/mesh/camera.h"
#include "geometry/mesh/triangle_soup.h"

namespace skyband::cli {

struct PaperBuilding {
  TriangleSoup soup;
  CameraSpec camera;  // from the south-west, eye height 1.6 m; width/height to be set by the caller
};

PaperBuilding make_paper_building();

}  // namespace skyband::cli
