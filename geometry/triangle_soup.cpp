#include "geometry/triangle_soup.h"

#include <unordered_map>

namespace skyband {

void TriangleSoup::append(const TriangleSoup& other) {
  const auto base = static_cast<std::uint32_t>(vertices.size());
  const std::size_t old_triangles = triangles.size();
  vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
  for (const auto& t : other.triangles) triangles.push_back({t[0] + base, t[1] + base, t[2] + base});

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

}  // namespace skyband
