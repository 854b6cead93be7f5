#pragma once
// A mesh with a value on each face, as binary little-endian PLY — results on the model itself,
// for 3D viewers (MeshLab, CloudCompare, Blender's PLY import show the face colours).
//
// Elements: `vertex` with `double x, y, z` (metres, verbatim: projected coordinates keep their
// precision); `face` with `list uchar uint vertex_indices`, `float value` (the face's value, or
// the nodata value where it has none) and `uchar red, green, blue` (its colour). Header comments
// carry the caller's lines (quantity, units, range, nodata, provenance). Written atomically.
#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "geometry/mesh/triangle_soup.h"

namespace skyband {

struct FaceValuesPly {
  const TriangleSoup* soup = nullptr;
  std::span<const float> values;                     // one per triangle
  std::span<const std::array<std::uint8_t, 3>> rgb;  // one per triangle
  std::vector<std::string> comments;                 // one header line each (no line breaks)
};

// InputError when the counts disagree, a comment holds a line break, or the file cannot be written.
void write_face_values_ply(const std::filesystem::path& file, const FaceValuesPly& ply);

}  // namespace skyband
