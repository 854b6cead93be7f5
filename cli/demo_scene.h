#pragma once
// The built-in demo scene of `skyband svf --demo`: a small street block of box buildings on a
// ground plane, with named calculation points (street floor, facades, roofs, a courtyard).
#include <string>
#include <vector>

#include "geometry/bands/band_visibility.h"
#include "geometry/mesh/triangle_soup.h"

namespace skyband::cli {

struct DemoPoint {
  std::string name;
  QueryPoint point;
};

struct DemoScene {
  TriangleSoup soup;
  std::vector<DemoPoint> points;
};

DemoScene make_demo_scene();

}  // namespace skyband::cli
