#pragma once
// Calculation points on a real mesh, as a user places them: half *street* points 5 cm above the
// local ground (normal up) and half *facade* points 5 cm in front of wall triangles (along the
// triangle's winding normal). Deterministic in the seed.
//
// Street: xy uniform over the mesh's bounding box; a vertical ray from above finds the highest
// surface there. Where that is nearly horizontal and within 1.5 m of the local ground level (the
// lowest vertex within 25 m), the point is 5 cm above it; where nothing lies below, the point is
// 5 cm above the local ground level in a model without a ground surface (buildings alone) and
// rejected in a model with one (terrain, roads or water under at least a tenth of 400 trial
// places: there nothing below means outside the model or in a hole of its ground); roofs, and
// points with anything above them, are rejected. Facade: a triangle whose normal is within 6° of
// horizontal, chosen by area, a point uniform on it.
#include <cstdint>
#include <vector>

#include "geometry/bands/band_visibility.h"
#include "geometry/mesh/scene.h"

namespace skyband::gen {

std::vector<QueryPoint> real_mesh_street_points(const Scene& scene, std::size_t count, std::uint64_t seed);
std::vector<QueryPoint> real_mesh_facade_points(const Scene& scene, std::size_t count, std::uint64_t seed);
// count/2 street points then the rest facade points.
std::vector<QueryPoint> real_mesh_points(const Scene& scene, std::size_t count, std::uint64_t seed);

}  // namespace skyband::gen
