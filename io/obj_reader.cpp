// Validating OBJ reader (see mesh_reader.h for what is supported). Wavefront OBJ reference:
// "Object Files (.obj)", Appendix B1 of the Wavefront Advanced Visualizer manual.
#include <map>
#include <unordered_map>

#include "geometry/core/input_error.h"
#include "io/mesh_reader.h"
#include "io/utf8_text.h"

namespace skyband::mesh_io {

PolygonSoup parse_obj(const std::string& name, const std::string& bytes) {
  PolygonSoup soup;
  soup.format = "OBJ";
  soup.polygon_start.push_back(0);
  std::vector<std::string_view> tokens;
  // Positive indices may refer forward (some exporters write faces first); they are checked
  // once the file is read. Remember the first face line that uses each too-large index.
  std::size_t max_index_line = 0;
  long long max_index = 0;
  std::string max_index_token;
  bool any_usemtl = false;
  std::uint32_t current_material = 0;
  // Objects: the latest `o` name, else the latest `g` names (a group line may list several;
  // they are joined by spaces), per face; faces before either belong to the unnamed object 0.
  bool any_object = false;
  std::uint32_t current_object = 0;
  std::unordered_map<std::string, std::uint32_t> object_ids;
  std::unordered_map<std::string, std::uint32_t> material_ids;
  std::map<std::string, std::size_t> ignored_keywords;
  reject_nul_bytes(name, bytes, "the OBJ text");

  for_each_line(bytes, [&](std::size_t line, std::string_view text) {
    if (const auto hash = text.find('#'); hash != std::string_view::npos) text = text.substr(0, hash);
    split_tokens(text, tokens);
    if (tokens.empty()) return;
    const std::string_view key = tokens[0];
    if (key == "v") {
      if (tokens.size() < 4)
        throw InputError(name + ":" + std::to_string(line) + ": vertex has " + std::to_string(tokens.size() - 1) +
                         " coordinates, 3 needed: '" + printable_text(text) + "'");
      static const char* axes[3] = {"x coordinate", "y coordinate", "z coordinate"};
      Vec3 p;
      for (int i = 0; i < 3; ++i) p[i] = parse_coordinate(tokens[static_cast<std::size_t>(i) + 1], name, line, axes[i]);
      add_vertex(soup, p);
    } else if (key == "f") {
      if (tokens.size() < 4)
        throw InputError(name + ":" + std::to_string(line) + ": face has " + std::to_string(tokens.size() - 1) +
                         " vertices, at least 3 needed: '" + printable_text(text) + "'");
      for (std::size_t i = 1; i < tokens.size(); ++i) {
        const std::string_view corner = tokens[i];
        const std::string_view position = corner.substr(0, corner.find('/'));
        const long long index = parse_integer(position, name, line, "face vertex index");
        long long zero_based = 0;
        if (index > 0) {
          zero_based = index - 1;
          if (index > max_index) {
            max_index = index;
            max_index_line = line;
            max_index_token = printable_text(corner);
          }
        } else if (index < 0) {
          zero_based = static_cast<long long>(soup.vertices.size()) + index;  // relative: -1 = last vertex
          if (zero_based < 0)
            throw InputError(name + ":" + std::to_string(line) + ": relative face index " + std::to_string(index) +
                             " reaches before the first vertex (" + std::to_string(soup.vertices.size()) + " vertices so far)");
        } else {
          throw InputError(name + ":" + std::to_string(line) + ": face index 0 is invalid (OBJ indices start at 1)");
        }
        if (zero_based > 0xFFFFFFFEll)
          throw InputError(name + ":" + std::to_string(line) + ": face index " + std::to_string(index) + " is too large");
        soup.indices.push_back(static_cast<std::uint32_t>(zero_based));
      }
      soup.polygon_start.push_back(static_cast<std::uint32_t>(soup.indices.size()));
      soup.polygon_material.push_back(current_material);
      soup.polygon_object.push_back(current_object);
    } else if (key == "o" || key == "g") {
      std::string object;
      for (std::size_t i = 1; i < tokens.size(); ++i) object += (i > 1 ? " " : "") + printable_text(tokens[i]);
      if (!any_object) {
        any_object = true;
        soup.object_names.push_back("");  // faces before the first o / g
        object_ids.emplace("", 0);
      }
      auto [it, inserted] = object_ids.emplace(object, static_cast<std::uint32_t>(soup.object_names.size()));
      if (inserted) soup.object_names.push_back(object);
      current_object = it->second;
    } else if (key == "usemtl") {
      const std::string material = tokens.size() > 1 ? std::string(tokens[1]) : std::string("default");
      if (!any_usemtl) {
        any_usemtl = true;
        soup.material_names.push_back("default");  // faces before the first usemtl
        material_ids.emplace("default", 0);
      }
      auto [it, inserted] = material_ids.emplace(material, static_cast<std::uint32_t>(soup.material_names.size()));
      if (inserted) soup.material_names.push_back(material);
      current_material = it->second;
    } else if (key == "vt" || key == "vn" || key == "vp" || key == "s" || key == "mtllib" || key == "l" || key == "p") {
      // texture/normal data, smoothing, materials library, lines and points: not geometry we occlude with
    } else {
      ++ignored_keywords[std::string(key)];
    }
  });

  if (max_index > static_cast<long long>(soup.vertices.size()))
    throw InputError(name + ":" + std::to_string(max_index_line) + ": face vertex index " + std::to_string(max_index) + " ('" +
                     max_index_token + "') is out of range: the file has " + std::to_string(soup.vertices.size()) + " vertices");
  if (!any_usemtl) soup.polygon_material.clear();
  if (!any_object) soup.polygon_object.clear();
  soup.faces_declared = soup.polygon_count();
  std::size_t listed = 0;  // a garbage file may hold thousands of distinct "keywords": list a few
  for (const auto& [keyword, count] : ignored_keywords) {
    if (++listed > 10) {
      soup.notes.push_back("ignored lines with " + std::to_string(ignored_keywords.size() - 10) + " more unknown OBJ keywords");
      break;
    }
    soup.notes.push_back("ignored " + std::to_string(count) + " line(s) with unknown OBJ keyword '" + printable_text(keyword) +
                         "'");
  }
  return soup;
}

}  // namespace skyband::mesh_io
