#pragma once
// A scene's geometry as an indexed triangle soup: no topology is assumed (non-manifold edges,
// open boundaries, inconsistent orientation, duplicates and zero-area triangles are all allowed;
// occlusion never depends on orientation or manifoldness).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/core/vec3.h"

namespace skyband {

struct TriangleSoup {
  std::vector<Vec3> vertices;  // metres, world frame, z up
  std::vector<std::array<std::uint32_t, 3>> triangles;
  // Optional per-triangle material index into material_names (empty = all material 0).
  std::vector<std::uint32_t> triangle_material;
  std::vector<std::string> material_names;
  // Optional per-triangle object index into object_names (empty = no objects): the city object
  // (CityJSON CityObject id, CityGML gml:id) a triangle belongs to. Kept by append; objects of
  // different soups stay distinct even when their names coincide.
  std::vector<std::uint32_t> triangle_object;
  std::vector<std::string> object_names;

  std::size_t triangle_count() const { return triangles.size(); }
  // Appends another soup (indices and material ids are offset; materials merged by name).
  void append(const TriangleSoup& other);

 private:
  void append_objects(const TriangleSoup& other, std::size_t old_triangles);
};

// Appends the closed axis-aligned box [lo, hi] as 12 outward-oriented triangles.
void append_box(TriangleSoup& soup, const Vec3& lo, const Vec3& hi);

}  // namespace skyband
