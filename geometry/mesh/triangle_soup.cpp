#include "geometry/mesh/triangle_soup.h"

#include <unordered_map>

namespace skyband {

void TriangleSoup::append_objects(const TriangleSoup& other, std::size_t old_triangles) {
  if (triangle_object.empty() && other.triangle_object.empty()) return;
  // Triangles without an object (either side) get one unnamed object per soup.
  auto unnamed = [this](std::size_t from, std::size_t to) {
    object_names.emplace_back();
    const auto id = static_cast<std::uint32_t>(object_names.size() - 1);
    triangle_object.resize(from, 0);
    triangle_object.resize(to, id);
  };
  if (triangle_object.empty() && old_triangles > 0) unnamed(0, old_triangles);
  triangle_object.resize(old_triangles);
  if (other.triangle_object.empty()) {
    unnamed(old_triangles, triangles.size());
    return;
  }
  const auto base = static_cast<std::uint32_t>(object_names.size());
  object_names.insert(object_names.end(), other.object_names.begin(), other.object_names.end());
  for (const std::uint32_t o : other.triangle_object) triangle_object.push_back(base + o);
}

void TriangleSoup::append(const TriangleSoup& other) {
  const auto base = static_cast<std::uint32_t>(vertices.size());
  const std::size_t old_triangles = triangles.size();
  vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
  for (const auto& t : other.triangles) triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  append_objects(other, old_triangles);

  const bool any_materials = !triangle_material.empty() || !other.triangle_material.empty();
  if (!any_materials) return;
  if (material_names.empty()) material_names.push_back("default");
  triangle_material.resize(old_triangles, 0);
  std::unordered_map<std::string, std::uint32_t> index;
  for (std::uint32_t i = 0; i < material_names.size(); ++i) index.emplace(material_names[i], i);
  auto id_of = [&](const std::string& name) {
    auto [it, inserted] = index.emplace(name, static_cast<std::uint32_t>(material_names.size()));
    if (inserted) material_names.push_back(name);
    return it->second;
  };
  for (std::size_t i = 0; i < other.triangles.size(); ++i) {
    const std::uint32_t m = other.triangle_material.empty() ? 0 : other.triangle_material[i];
    const std::string name = m < other.material_names.size() ? other.material_names[m] : std::string("default");
    triangle_material.push_back(id_of(name));
  }
}

void append_box(TriangleSoup& soup, const Vec3& lo, const Vec3& hi) {
  const auto b = static_cast<std::uint32_t>(soup.vertices.size());
  // Corner i has x from bit 0, y from bit 1, z from bit 2.
  for (int i = 0; i < 8; ++i)
    soup.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  static constexpr std::uint32_t kFaces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                                  {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& t : kFaces) soup.triangles.push_back({b + t[0], b + t[1], b + t[2]});
  if (!soup.triangle_material.empty()) soup.triangle_material.resize(soup.triangles.size(), 0);
  if (!soup.triangle_object.empty()) {
    soup.object_names.emplace_back();
    soup.triangle_object.resize(soup.triangles.size(), static_cast<std::uint32_t>(soup.object_names.size() - 1));
  }
}

}  // namespace skyband
