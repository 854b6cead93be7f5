#pragma once
// Welding by exact position: vertices whose coordinates are bit-equal doubles (+0 and −0 equal)
// share one id. Used wherever topology is read from a triangle soup (mesh_defects.h,
// column_scene.h), so both see the same mesh.
#include <cstdint>
#include <vector>

#include "geometry/core/vec3.h"

namespace skyband {

// Welded id per vertex, ids numbered in order of first occurrence (0 … distinct − 1).
std::vector<std::uint32_t> weld_positions(const std::vector<Vec3>& vertices);

}  // namespace skyband
