#include "io/cityjson_reader.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <unordered_map>

#include "geometry/core/input_error.h"
#include "geometry/mesh/polygon_with_holes_triangulation.h"
#include "io/crs_codes.h"
#include "io/utf8_text.h"

namespace skyband {
namespace {

using json = nlohmann::json;
constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// A JSON value quoted in a message: compact, at most ~60 characters, control characters escaped.
std::string value_text(const json& v) {
  std::string text = v.dump(-1, ' ', false, json::error_handler_t::replace);
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return printable_text(text);
}

// RFC 6901 JSON Pointer token escaping ("~" → "~0", "/" → "~1").
std::string pointer_token(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

// Where we are: file name, line (CityJSONSeq; 0 = not a line-based file), and a JSON pointer.
struct Where {
  std::string file;
  std::size_t line = 0;
  std::string prefix() const { return line ? file + ":" + std::to_string(line) + ": " : file + ": "; }
};

[[noreturn]] void fail(const Where& where, const std::string& pointer, const std::string& message) {
  throw InputError(where.prefix() + printable_text(pointer) + (pointer.empty() ? "" : ": ") + message);
}

// Notes aggregated by reason: "<count> × <reason> (first: <where>)".
class Notes {
 public:
  void add(const std::string& reason, const std::string& example) {
    auto [it, inserted] = counts_.try_emplace(reason, Entry{0, example, order_.size()});
    if (inserted) order_.push_back(reason);
    ++it->second.count;
  }
  void emit(std::vector<std::string>& out) const {
    for (const std::string& reason : order_) {
      const Entry& e = counts_.at(reason);
      out.push_back(std::to_string(e.count) + " x " + reason +
                    (e.example.empty() ? "" : " (first: " + printable_text(e.example) + ")"));
    }
  }

 private:
  struct Entry {
    std::size_t count;
    std::string example;
    std::size_t order;
  };
  std::map<std::string, Entry> counts_;
  std::vector<std::string> order_;
};

// ---- LoD -----------------------------------------------------------------------------------

struct Lod {
  std::string text;              // as written ("2.2", or the number's shortest form in 1.0)
  std::vector<long long> parts;  // numeric components: "2.2" → {2, 2}, "1" → {1}
};

// Numeric comparison component by component, missing components are 0 ("1" == "1.0").
int compare(const Lod& a, const Lod& b) {
  const std::size_t n = std::max(a.parts.size(), b.parts.size());
  for (std::size_t i = 0; i < n; ++i) {
    const long long x = i < a.parts.size() ? a.parts[i] : 0, y = i < b.parts.size() ? b.parts[i] : 0;
    if (x != y) return x < y ? -1 : 1;
  }
  return 0;
}

std::optional<Lod> parse_lod_text(const std::string& text) {
  Lod lod{text, {}};
  std::size_t i = 0;
  while (true) {
    long long v = 0;
    const auto [end, ec] = std::from_chars(text.data() + i, text.data() + text.size(), v);
    if (ec != std::errc() || v < 0) return std::nullopt;
    lod.parts.push_back(v);
    i = static_cast<std::size_t>(end - text.data());
    if (i == text.size()) return lod;
    if (text[i] != '.' || i + 1 == text.size()) return std::nullopt;
    ++i;
  }
}

Lod parse_lod(const json& v, const Where& where, const std::string& pointer) {
  std::string text;
  if (v.is_string())
    text = v.get<std::string>();
  else if (v.is_number_integer())
    text = v.dump();
  else if (v.is_number_float() && std::isfinite(v.get<double>()))
    text = v.dump();  // shortest round-trip form: 1.2 → "1.2", 2.0 → "2.0"
  if (auto lod = parse_lod_text(text)) return *lod;
  fail(where, pointer + "/lod", "LoD " + value_text(v) + " is not a LoD such as \"2.2\" or 1");
}

// ---- CRS -----------------------------------------------------------------------------------

// ---- Vertices ------------------------------------------------------------------------------

struct Transform {
  bool present = false;
  std::array<double, 3> scale{1, 1, 1}, translate{0, 0, 0};
};

Transform read_transform(const json& root, const Where& where, const std::string& version, Notes& notes) {
  Transform t;
  const auto it = root.find("transform");
  if (it == root.end()) {
    if (version != "1.0")
      notes.add("no \"transform\" although CityJSON " + version + " requires one: vertices read as real coordinates",
                "/transform");
    return t;
  }
  if (!it->is_object()) fail(where, "/transform", "transform " + value_text(*it) + " is not an object");
  for (const char* member : {"scale", "translate"}) {
    const auto m = it->find(member);
    const std::string pointer = std::string("/transform/") + member;
    if (m == it->end()) fail(where, pointer, "missing");
    if (!m->is_array() || m->size() != 3) fail(where, pointer, value_text(*m) + " is not an array of 3 numbers");
    for (std::size_t k = 0; k < 3; ++k) {
      const json& v = (*m)[k];
      if (!v.is_number() || !std::isfinite(v.get<double>()))
        fail(where, pointer + "/" + std::to_string(k), value_text(v) + " is not a finite number");
      (member[0] == 's' ? t.scale : t.translate)[k] = v.get<double>();
    }
  }
  for (std::size_t k = 0; k < 3; ++k)
    if (t.scale[k] == 0) fail(where, "/transform/scale/" + std::to_string(k), "scale 0 collapses every vertex");
  t.present = true;
  return t;
}

// x = i · scale + translate as CityJSON defines it: one correctly rounded product and one
// correctly rounded sum (no contraction into a fused multiply-add, which would round once).
#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("fp-contract=off")))
#endif
double
apply_transform(long long i, double scale, double translate) {
#if defined(__clang__)
#pragma clang fp contract(off)
#endif
  const double product = static_cast<double>(i) * scale;
  return product + translate;
}

// All of a chunk's vertices (a CityJSON file, or one CityJSONFeature), validated.
std::vector<Vec3> read_vertices(const json& root, const Transform& t, const Where& where) {
  const auto it = root.find("vertices");
  if (it == root.end()) fail(where, "/vertices", "missing");
  if (!it->is_array()) fail(where, "/vertices", value_text(*it) + " is not an array");
  std::vector<Vec3> out;
  out.reserve(it->size());
  constexpr long long kExactInDouble = 1LL << 53;  // |i| ≤ 2⁵³ converts to double exactly
  for (std::size_t v = 0; v < it->size(); ++v) {
    const json& p = (*it)[v];
    const std::string pointer = "/vertices/" + std::to_string(v);
    if (!p.is_array() || p.size() != 3) fail(where, pointer, "vertex " + value_text(p) + " is not an array of 3 numbers");
    Vec3 x;
    for (std::size_t k = 0; k < 3; ++k) {
      const json& c = p[k];
      if (t.present) {
        if (!c.is_number_integer())
          fail(where, pointer + "/" + std::to_string(k),
               "coordinate " + value_text(c) + " is not an integer (the transform requires integer vertices)");
        if (c.is_number_unsigned() && c.get<std::uint64_t>() > static_cast<std::uint64_t>(kExactInDouble))
          fail(where, pointer + "/" + std::to_string(k), "integer coordinate " + value_text(c) + " exceeds 2^53");
        const long long i = c.get<long long>();
        if (i > kExactInDouble || i < -kExactInDouble)
          fail(where, pointer + "/" + std::to_string(k), "integer coordinate " + value_text(c) + " exceeds 2^53");
        x[static_cast<int>(k)] = apply_transform(i, t.scale[k], t.translate[k]);
      } else {
        if (!c.is_number()) fail(where, pointer + "/" + std::to_string(k), "coordinate " + value_text(c) + " is not a number");
        x[static_cast<int>(k)] = c.get<double>();
      }
      if (!std::isfinite(x[static_cast<int>(k)]))
        fail(where, pointer + "/" + std::to_string(k), "coordinate " + value_text(c) + " is not finite after the transform");
    }
    out.push_back(x);
  }
  return out;
}

// ---- Geometry templates --------------------------------------------------------------------

struct Templates {
  const json* geometries = nullptr;  // "templates" array
  std::vector<Vec3> vertices;        // "vertices-templates", real coordinates
  std::string where_pointer = "/geometry-templates";
};

Templates read_templates(const json& root, const Where& where) {
  Templates t;
  const auto it = root.find("geometry-templates");
  if (it == root.end()) return t;
  const json& gt = *it;
  if (!gt.is_object()) fail(where, "/geometry-templates", value_text(gt) + " is not an object");
  const auto g = gt.find("templates");
  const auto v = gt.find("vertices-templates");
  if (g == gt.end() || !g->is_array()) fail(where, "/geometry-templates/templates", "missing or not an array");
  if (v == gt.end() || !v->is_array()) fail(where, "/geometry-templates/vertices-templates", "missing or not an array");
  t.geometries = &*g;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const json& p = (*v)[i];
    const std::string pointer = "/geometry-templates/vertices-templates/" + std::to_string(i);
    if (!p.is_array() || p.size() != 3) fail(where, pointer, value_text(p) + " is not an array of 3 numbers");
    Vec3 x;
    for (std::size_t k = 0; k < 3; ++k) {
      if (!p[k].is_number() || !std::isfinite(p[k].get<double>()))
        fail(where, pointer + "/" + std::to_string(k), value_text(p[k]) + " is not a finite number");
      x[static_cast<int>(k)] = p[k].get<double>();
    }
    t.vertices.push_back(x);
  }
  return t;
}

// ---- The reader ----------------------------------------------------------------------------

struct Counts {
  std::size_t objects = 0, objects_with_geometry = 0, skipped_objects = 0, surfaces = 0, surfaces_with_holes = 0;
  std::map<std::string, std::size_t> lods_used;
};

class ModelBuilder {
 public:
  ModelBuilder(const std::string& file, const CityModelReadOptions& options, TriangleSoup& soup, Counts& counts, Notes& notes)
      : options_(options), soup_(soup), counts_(counts), notes_(notes) {
    if (options.lod) {
      auto lod = parse_lod_text(*options.lod);
      if (!lod) throw InputError(file + ": requested LoD '" + printable_text(*options.lod) + "' is not a LoD such as \"2.2\"");
      requested_ = *lod;
    }
  }

  // Reads one chunk: the CityObjects of a CityJSON file or of one CityJSONFeature, with the
  // chunk's own vertices.
  void read_chunk(const json& root, const std::vector<Vec3>& vertices, const Templates& templates, const Where& where) {
    where_ = &where;
    vertices_ = &vertices;
    templates_ = &templates;
    remap_.assign(vertices.size(), kUnused);

    const auto it = root.find("CityObjects");
    if (it == root.end()) fail(where, "/CityObjects", "missing");
    if (!it->is_object()) fail(where, "/CityObjects", value_text(*it) + " is not an object");
    const json& objects = *it;

    // Pass 1: each object's chosen LoD (none: nothing to read).
    std::unordered_map<std::string, std::optional<Lod>> chosen;
    for (const auto& [id, object] : objects.items()) {
      const std::string pointer = "/CityObjects/" + pointer_token(id);
      if (!object.is_object()) fail(where, pointer, value_text(object) + " is not an object");
      chosen[id] = choose_lod(object, pointer);
    }
    // Pass 2: read, skipping parents superseded by children read at a higher LoD.
    for (const auto& [id, object] : objects.items()) {
      ++counts_.objects;
      const std::string pointer = "/CityObjects/" + pointer_token(id);
      const auto type_it = object.find("type");
      if (type_it == object.end() || !type_it->is_string()) fail(where, pointer + "/type", "missing or not a string");
      const auto geometry = object.find("geometry");
      if (geometry == object.end() || (geometry->is_array() && geometry->empty())) continue;  // no geometry: fine
      if (!geometry->is_array()) fail(where, pointer + "/geometry", value_text(*geometry) + " is not an array");
      const std::optional<Lod>& lod = chosen.at(id);
      if (!lod) {
        ++counts_.skipped_objects;
        notes_.add("objects skipped: no geometry of the requested LoD " + requested_->text, pointer);
        continue;
      }
      if (!options_.lod && !options_.keep_lower_lod_parents) {
        if (const auto children = object.find("children"); children != object.end() && children->is_array()) {
          std::optional<Lod> best_child;
          for (const json& c : *children) {
            if (!c.is_string()) continue;
            const auto ch = chosen.find(c.get<std::string>());
            if (ch != chosen.end() && ch->second && (!best_child || compare(*ch->second, *best_child) > 0))
              best_child = ch->second;
          }
          if (best_child && compare(*lod, *best_child) < 0) {
            ++counts_.skipped_objects;
            notes_.add("parent objects skipped: their highest LoD is below their children's (LoD " + lod->text + " parent, LoD " +
                           best_child->text + " children)",
                       pointer);
            continue;
          }
        }
      }
      material_fallback_ = type_it->get<std::string>();
      object_name_ = &id;
      object_index_ = kUnused;
      const std::size_t surfaces_before = counts_.surfaces;
      for (std::size_t g = 0; g < geometry->size(); ++g) {
        const json& geom = (*geometry)[g];
        const std::string gpointer = pointer + "/geometry/" + std::to_string(g);
        const auto [glod, is_instance] = geometry_lod(geom, gpointer);
        if (compare(glod, *lod) != 0) continue;
        if (is_instance)
          read_instance(geom, gpointer);
        else
          read_geometry(geom, gpointer, nullptr);
      }
      if (counts_.surfaces > surfaces_before) {
        ++counts_.objects_with_geometry;
        ++counts_.lods_used[lod->text];
      } else {
        ++counts_.skipped_objects;
        notes_.add("objects skipped: nothing with area at their LoD", pointer);
      }
    }
  }

 private:
  // The LoD of a geometry (a GeometryInstance takes its template's), and whether it is an instance.
  std::pair<Lod, bool> geometry_lod(const json& geom, const std::string& pointer) {
    if (!geom.is_object()) fail(*where_, pointer, value_text(geom) + " is not an object");
    const auto type = geom.find("type");
    if (type == geom.end() || !type->is_string()) fail(*where_, pointer + "/type", "missing or not a string");
    if (*type == "GeometryInstance") {
      const json& tmpl = template_of(geom, pointer);
      const auto lod = tmpl.find("lod");
      const std::string tpointer = "/geometry-templates/templates/" + std::to_string(geom["template"].get<std::size_t>());
      if (lod == tmpl.end()) fail(*where_, tpointer + "/lod", "missing");
      return {parse_lod(*lod, *where_, tpointer), true};
    }
    const auto lod = geom.find("lod");
    if (lod == geom.end()) fail(*where_, pointer + "/lod", "missing");
    return {parse_lod(*lod, *where_, pointer), false};
  }

  const json& template_of(const json& geom, const std::string& pointer) {
    const auto t = geom.find("template");
    if (t == geom.end() || !t->is_number_unsigned())
      fail(*where_, pointer + "/template", "missing or not a non-negative integer");
    if (!templates_->geometries)
      fail(*where_, pointer + "/template", "template " + value_text(*t) + " but the file has no \"geometry-templates\"");
    const std::size_t k = t->get<std::size_t>();
    if (k >= templates_->geometries->size())
      fail(*where_, pointer + "/template",
           "template " + value_text(*t) + " out of range (" + std::to_string(templates_->geometries->size()) + " templates)");
    return (*templates_->geometries)[k];
  }

  std::optional<Lod> choose_lod(const json& object, const std::string& pointer) {
    const auto geometry = object.find("geometry");
    if (geometry == object.end() || !geometry->is_array()) return std::nullopt;
    std::optional<Lod> best;
    for (std::size_t g = 0; g < geometry->size(); ++g) {
      const Lod lod = geometry_lod((*geometry)[g], pointer + "/geometry/" + std::to_string(g)).first;
      if (requested_) {
        if (compare(lod, *requested_) == 0) return lod;
      } else if (!best || compare(lod, *best) > 0) {
        best = lod;
      }
    }
    return best;
  }

  std::uint32_t material(const std::string& name) {
    const auto [it, inserted] = material_index_.try_emplace(name, static_cast<std::uint32_t>(soup_.material_names.size()));
    if (inserted) soup_.material_names.push_back(name);
    return it->second;
  }

  // A chunk vertex index (JSON) → soup index; validates the index.
  std::uint32_t chunk_vertex(const json& index, const std::string& pointer) {
    if (!index.is_number_integer() || (!index.is_number_unsigned() && index.get<long long>() < 0))
      fail(*where_, pointer, "vertex index " + value_text(index) + " is not a non-negative integer");
    const std::uint64_t i = index.get<std::uint64_t>();
    if (i >= vertices_->size())
      fail(*where_, pointer,
           "vertex index " + value_text(index) + " out of range (" + std::to_string(vertices_->size()) + " vertices)");
    std::uint32_t& m = remap_[i];
    if (m == kUnused) {
      m = static_cast<std::uint32_t>(soup_.vertices.size());
      soup_.vertices.push_back((*vertices_)[i]);
    }
    return m;
  }

  struct Instance {
    std::array<double, 16> matrix;  // row-major
    Vec3 reference;
    std::vector<std::uint32_t> remap;  // template vertex → soup index for this instance
  };

  std::uint32_t template_vertex(const json& index, const std::string& pointer, Instance& inst) {
    if (!index.is_number_unsigned())
      fail(*where_, pointer, "template vertex index " + value_text(index) + " is not a non-negative integer");
    const std::uint64_t i = index.get<std::uint64_t>();
    if (i >= templates_->vertices.size())
      fail(*where_, pointer,
           "template vertex index " + value_text(index) + " out of range (" + std::to_string(templates_->vertices.size()) +
               " template vertices)");
    std::uint32_t& m = inst.remap[i];
    if (m == kUnused) {
      const Vec3& v = templates_->vertices[i];
      const auto& M = inst.matrix;
      double h[4];
      for (int r = 0; r < 4; ++r) h[r] = M[4 * r] * v.x() + M[4 * r + 1] * v.y() + M[4 * r + 2] * v.z() + M[4 * r + 3];
      if (!(std::isfinite(h[3]) && h[3] != 0)) fail(*where_, pointer, "the transformation matrix maps the vertex to infinity");
      const Vec3 p = (h[3] == 1 ? Vec3(h[0], h[1], h[2]) : Vec3(h[0] / h[3], h[1] / h[3], h[2] / h[3])) + inst.reference;
      m = static_cast<std::uint32_t>(soup_.vertices.size());
      soup_.vertices.push_back(p);
    }
    return m;
  }

  void read_instance(const json& geom, const std::string& pointer) {
    const json& tmpl = template_of(geom, pointer);
    const std::string tpointer = "/geometry-templates/templates/" + std::to_string(geom["template"].get<std::size_t>());
    const auto b = geom.find("boundaries");
    if (b == geom.end() || !b->is_array() || b->size() != 1)
      fail(*where_, pointer + "/boundaries", "a GeometryInstance needs boundaries [reference vertex index]");
    Instance inst;
    const std::uint32_t ref = chunk_vertex((*b)[0], pointer + "/boundaries/0");
    inst.reference = soup_.vertices[ref];
    const auto m = geom.find("transformationMatrix");
    if (m == geom.end() || !m->is_array() || m->size() != 16)
      fail(*where_, pointer + "/transformationMatrix", "missing or not an array of 16 numbers");
    for (std::size_t k = 0; k < 16; ++k) {
      if (!(*m)[k].is_number() || !std::isfinite((*m)[k].get<double>()))
        fail(*where_, pointer + "/transformationMatrix/" + std::to_string(k), value_text((*m)[k]) + " is not a finite number");
      inst.matrix[k] = (*m)[k].get<double>();
    }
    inst.remap.assign(templates_->vertices.size(), kUnused);
    if (const auto t = tmpl.find("type"); t != tmpl.end() && *t == "GeometryInstance")
      fail(*where_, tpointer + "/type", "a template cannot itself be a GeometryInstance");
    read_geometry(tmpl, tpointer, &inst);
    ++instances_;
  }

  // Surface depth (array levels above a surface) of each geometry type with area.
  static int surface_depth(const std::string& type) {
    if (type == "MultiSurface" || type == "CompositeSurface") return 1;
    if (type == "Solid") return 2;
    if (type == "MultiSolid" || type == "CompositeSolid") return 3;
    return 0;
  }

  void read_geometry(const json& geom, const std::string& pointer, Instance* inst) {
    const std::string type = geom.at("type").get<std::string>();
    const int depth = surface_depth(type);
    if (depth == 0) {
      if (type == "MultiPoint" || type == "MultiLineString")
        notes_.add(type + " geometries skipped (no area)", pointer);
      else
        fail(*where_, pointer + "/type", "unknown geometry type " + value_text(geom.at("type")));
      return;
    }
    const auto b = geom.find("boundaries");
    if (b == geom.end()) fail(*where_, pointer + "/boundaries", "missing");
    // Semantics: surfaces[] and values nested one level less deep than boundaries' rings.
    const json* sem_surfaces = nullptr;
    const json* values = nullptr;
    std::string sem_pointer = pointer + "/semantics";
    if (const auto s = geom.find("semantics"); s != geom.end() && !s->is_null()) {
      if (!s->is_object()) fail(*where_, sem_pointer, value_text(*s) + " is not an object");
      const auto surf = s->find("surfaces");
      const auto val = s->find("values");
      if (surf == s->end() || !surf->is_array()) fail(*where_, sem_pointer + "/surfaces", "missing or not an array");
      sem_surfaces = &*surf;
      if (val != s->end() && !val->is_null()) values = &*val;
    }
    walk(*b, depth, values, pointer + "/boundaries", sem_pointer + "/values", sem_surfaces, inst);
  }

  void walk(const json& node, int depth, const json* values, const std::string& pointer, const std::string& vpointer,
            const json* sem_surfaces, Instance* inst) {
    if (!node.is_array()) fail(*where_, pointer, value_text(node) + " is not an array (boundaries nested to the wrong depth)");
    if (values && !values->is_array())
      fail(*where_, vpointer, value_text(*values) + " is not an array (semantic values nested to the wrong depth)");
    if (values && values->size() != node.size())
      fail(*where_, vpointer,
           std::to_string(values->size()) + " semantic values for " + std::to_string(node.size()) + " boundaries");
    for (std::size_t i = 0; i < node.size(); ++i) {
      const json* v = values ? &(*values)[i] : nullptr;
      if (v && v->is_null()) v = nullptr;
      const std::string p = pointer + "/" + std::to_string(i), vp = vpointer + "/" + std::to_string(i);
      if (depth > 1) {
        walk(node[i], depth - 1, v, p, vp, sem_surfaces, inst);
        continue;
      }
      std::string name = material_fallback_;
      if (v) {
        if (!v->is_number_unsigned() || v->get<std::size_t>() >= sem_surfaces->size())
          fail(*where_, vp,
               "semantic value " + value_text(*v) + " is not an index into the " + std::to_string(sem_surfaces->size()) +
                   " semantic surfaces");
        const json& s = (*sem_surfaces)[v->get<std::size_t>()];
        const auto t = s.is_object() ? s.find("type") : s.end();
        if (!s.is_object() || t == s.end() || !t->is_string())
          fail(*where_, vp, "semantic surface " + value_text(s) + " has no \"type\" string");
        name = t->get<std::string>();
      }
      read_surface(node[i], p, name, inst);
    }
  }

  void read_surface(const json& surface, const std::string& pointer, const std::string& name, Instance* inst) {
    if (!surface.is_array())
      fail(*where_, pointer, value_text(surface) + " is not an array of rings (boundaries nested to the wrong depth)");
    rings_.clear();
    for (std::size_t r = 0; r < surface.size(); ++r) {
      const json& ring = surface[r];
      const std::string rp = pointer + "/" + std::to_string(r);
      if (!ring.is_array())
        fail(*where_, rp, value_text(ring) + " is not an array of vertex indices (boundaries nested to the wrong depth)");
      std::vector<std::uint32_t> out;
      out.reserve(ring.size());
      for (std::size_t k = 0; k < ring.size(); ++k) {
        const std::string ip = rp + "/" + std::to_string(k);
        if (ring[k].is_array()) fail(*where_, ip, value_text(ring[k]) + " is not a vertex index (boundaries nested too deep)");
        const std::uint32_t s = inst ? template_vertex(ring[k], ip, *inst) : chunk_vertex(ring[k], ip);
        if (!out.empty() && out.back() == s) {
          notes_.add("repeated consecutive vertices removed", ip);
          continue;
        }
        out.push_back(s);
      }
      if (out.size() > 1 && out.front() == out.back()) {
        out.pop_back();
        notes_.add("rings closed by repeating their first vertex: repeat removed", rp);
      }
      std::vector<std::uint32_t> distinct = out;
      std::sort(distinct.begin(), distinct.end());
      if (std::unique(distinct.begin(), distinct.end()) - distinct.begin() < 3) {
        if (r == 0) {
          notes_.add("surfaces skipped: outer ring with fewer than 3 distinct vertices", rp);
          return;
        }
        notes_.add("inner rings (holes) skipped: fewer than 3 distinct vertices", rp);
        continue;
      }
      rings_.push_back(std::move(out));
    }
    if (rings_.empty()) {
      notes_.add("surfaces skipped: no rings", pointer);
      return;
    }
    const PolygonWithHolesTriangulation t = triangulate_polygon_with_holes(soup_.vertices, rings_);
    if (t.holes_dropped) notes_.add("surfaces with crossing rings: holes not cut out (surface filled)", pointer);
    if (t.method == PolygonTriangulationMethod::kFanZeroArea) notes_.add("zero-area surfaces (fan-triangulated)", pointer);
    if (t.method == PolygonTriangulationMethod::kFanSelfIntersecting)
      notes_.add("self-crossing surfaces (fan-triangulated)", pointer);
    const std::uint32_t m = material(name);
    if (object_index_ == kUnused && !t.triangles.empty()) {
      object_index_ = static_cast<std::uint32_t>(soup_.object_names.size());
      soup_.object_names.push_back(object_name_ ? *object_name_ : std::string());
    }
    for (const auto& tri : t.triangles) {
      soup_.triangles.push_back(tri);
      soup_.triangle_material.push_back(m);
      soup_.triangle_object.push_back(object_index_);
    }
    ++counts_.surfaces;
    if (rings_.size() > 1 && !t.holes_dropped) ++counts_.surfaces_with_holes;
  }

 public:
  std::size_t instances_ = 0;

 private:
  const CityModelReadOptions& options_;
  std::optional<Lod> requested_;
  TriangleSoup& soup_;
  Counts& counts_;
  Notes& notes_;
  const Where* where_ = nullptr;
  const std::vector<Vec3>* vertices_ = nullptr;
  const Templates* templates_ = nullptr;
  std::vector<std::uint32_t> remap_;
  std::unordered_map<std::string, std::uint32_t> material_index_;
  std::string material_fallback_;
  const std::string* object_name_ = nullptr;  // the CityObject being read
  std::uint32_t object_index_ = kUnused;      // its index in soup_.object_names, once it has a triangle
  std::vector<std::vector<std::uint32_t>> rings_;
};

// "type" and "version" of a CityJSON root (or the CityJSONSeq header): returns "1.0"/"1.1"/"2.0".
std::string check_header(const json& root, const Where& where, bool sequence) {
  if (!root.is_object()) fail(where, "", "the JSON value is not an object (not CityJSON)");
  const auto type = root.find("type");
  if (type == root.end() || *type != "CityJSON")
    fail(where, "/type", (type == root.end() ? std::string("missing") : value_text(*type)) + " is not \"CityJSON\"");
  const auto version = root.find("version");
  if (version == root.end() || !version->is_string()) fail(where, "/version", "missing or not a string");
  const std::string v = version->get<std::string>();
  for (const char* supported : {"1.0", "1.1", "2.0"}) {
    const std::string s = supported;
    if (v == s || (v.size() > s.size() && v.compare(0, s.size() + 1, s + ".") == 0)) {
      if (sequence && s == "1.0")
        fail(where, "/version", "CityJSONSeq needs CityJSON 1.1 or 2.0, the header says " + value_text(*version));
      return s;
    }
  }
  fail(where, "/version", "unsupported CityJSON version " + value_text(*version) + " (supported: 1.0, 1.1, 2.0)");
}

// metadata.referenceSystem: kept verbatim; geographic / geocentric CRSs refused.
std::string check_crs(const json& root, const Where& where, std::vector<std::string>& notes) {
  const auto metadata = root.find("metadata");
  const json* rs = nullptr;
  if (metadata != root.end() && metadata->is_object())
    if (const auto it = metadata->find("referenceSystem"); it != metadata->end()) rs = &*it;
  if (!rs || (rs->is_string() && rs->get<std::string>().empty())) {
    notes.push_back("no referenceSystem: coordinates taken as metres in an unknown projected CRS");
    return "";
  }
  if (!rs->is_string()) fail(where, "/metadata/referenceSystem", value_text(*rs) + " is not a string");
  const std::string crs = rs->get<std::string>();
  const std::string l = lower(crs);
  const auto& geographic = geographic_epsg_codes();
  std::string refused;
  if (l.find("crs84") != std::string::npos || l.find("crs:84") != std::string::npos) refused = "OGC CRS84";
  for (const int code : crs_epsg_codes(crs))
    if (std::find(geographic.begin(), geographic.end(), code) != geographic.end()) refused = "EPSG:" + std::to_string(code);
  if (!refused.empty())
    fail(where, "/metadata/referenceSystem",
         value_text(*rs) + " is a geographic or geocentric CRS (" + refused +
             "): degrees are not metres; reproject to a projected CRS first (e.g. cjio crs_reproject)");
  if (crs_epsg_codes(crs).empty())
    notes.push_back("referenceSystem " + printable_text(crs) + " names no EPSG code: taken as metres");
  return crs;
}

json parse_json(const std::string& text, const Where& where) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {  // parse_error; out_of_range 406: a number overflows a double
    std::string what = e.what();
    if (const auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    if (where.line) {  // one line of a CityJSONSeq: nlohmann's "line 1, " says nothing
      if (const auto p = what.find("line 1, "); p != std::string::npos) what.erase(p, 8);
    }
    throw InputError(where.prefix() + "not JSON (" + printable_text(what) + ")");
  }
}

struct Reader {
  std::filesystem::path path;
  const CityModelReadOptions& options;
  TriangleSoup soup;
  CityModelReport report;
  Counts counts;
  Notes notes;
  std::size_t instances = 0;

  void read_single(const json& root) {
    Where where{path.string(), 0};
    const std::string version = check_header(root, where, false);
    report.format = "CityJSON " + version;
    report.crs = check_crs(root, where, report.notes);
    const Transform transform = read_transform(root, where, version, notes);
    const std::vector<Vec3> vertices = read_vertices(root, transform, where);
    const Templates templates = read_templates(root, where);
    ModelBuilder builder(where.file, options, soup, counts, notes);
    builder.read_chunk(root, vertices, templates, where);
    instances = builder.instances_;
  }

  void read_sequence(std::istream& in) {
    Where where{path.string(), 0};
    std::string line;
    std::size_t line_number = 0;
    bool have_header = false;
    std::string version;
    Transform transform;
    Templates templates;
    json header;
    std::optional<ModelBuilder> builder;
    while (std::getline(in, line)) {
      ++line_number;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.find_first_not_of(" \t") == std::string::npos) continue;
      where.line = line_number;
      json value = parse_json(line, where);
      if (!have_header) {
        version = check_header(value, where, true);
        report.format = "CityJSONSeq " + version;
        report.crs = check_crs(value, where, report.notes);
        transform = read_transform(value, where, version, notes);
        header = std::move(value);  // keeps the templates' JSON alive
        templates = read_templates(header, where);
        builder.emplace(where.file, options, soup, counts, notes);
        // The header's own CityObjects/vertices are normally empty; read them if not.
        if (const auto co = header.find("CityObjects"); co != header.end() && co->is_object() && !co->empty())
          builder->read_chunk(header, read_vertices(header, transform, where), templates, where);
        have_header = true;
        continue;
      }
      if (!value.is_object()) fail(where, "", "the line is not a JSON object (not a CityJSONFeature)");
      const auto type = value.find("type");
      if (type == value.end() || *type != "CityJSONFeature")
        fail(where, "/type", (type == value.end() ? std::string("missing") : value_text(*type)) + " is not \"CityJSONFeature\"");
      ++report.features;
      const std::vector<Vec3> vertices = read_vertices(value, transform, where);
      builder->read_chunk(value, vertices, templates, where);
    }
    if (in.bad()) throw InputError(path.string() + ": read error");
    if (!have_header) throw InputError(path.string() + ": empty file (no CityJSON header line)");
    instances = builder->instances_;
  }
};

}  // namespace

const std::vector<int>& geographic_epsg_codes() {
  static const std::vector<int> codes{4326, 4979, 4258, 4937, 4289, 4269, 4617, 4283, 7844, 4612, 6668,
                                      6697, 4490, 4167, 4171, 4230, 4277, 4978, 4936, 9518, 9705};
  return codes;
}

bool is_cityjson_path(const std::filesystem::path& file) {
  const std::string ext = lower(file.extension().string());
  return ext == ".json" || ext == ".jsonl";
}

std::string CityModelReport::summary() const {
  std::ostringstream os;
  os << file << ": " << format << (crs.empty() ? ", no CRS" : ", CRS " + crs) << "\n";
  if (features) os << "  " << features << " features\n";
  os << "  " << objects << " objects, " << objects_with_geometry << " read, " << skipped_objects << " skipped; " << surfaces
     << " surfaces (" << surfaces_with_holes << " with holes) -> " << triangles << " triangles, " << vertices << " vertices\n";
  os << "  LoDs:";
  for (const auto& [lod, n] : lods_used) os << " " << lod << " (" << n << " objects)";
  os << "\n";
  for (const std::string& n : notes) os << "  note: " << n << "\n";
  return os.str();
}

namespace {
TriangleSoup read_cityjson_unguarded(const std::filesystem::path& file, const CityModelReadOptions& options,
                                     CityModelReport* report) {
  Reader reader{file, options, {}, {}, {}, {}, 0};
  reader.report.file = file.string();
  const std::string ext = lower(file.extension().string());
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open");
  if (ext == ".jsonl") {
    reader.read_sequence(in);
  } else {
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw InputError(file.string() + ": read error");
    std::optional<json> root;
    try {
      root = parse_json(text, Where{file.string(), 0});
    } catch (const InputError&) {
      // A CityJSONSeq saved as .json: the first line alone is a CityJSON header, more follow.
      const std::size_t eol = text.find('\n');
      const bool more = eol != std::string::npos && text.find_first_not_of(" \t\r\n", eol) != std::string::npos;
      const json first = more ? json::parse(text.substr(0, eol), nullptr, false) : json();
      if (!(first.is_object() && first.value("type", "") == "CityJSON")) throw;
    }
    if (root) {
      reader.read_single(*root);
    } else {
      reader.report.notes.push_back("CityJSONSeq content (one JSON object per line) in a " + ext + " file");
      std::istringstream lines(text);
      reader.read_sequence(lines);
    }
  }
  CityModelReport& r = reader.report;
  r.objects = reader.counts.objects;
  r.objects_with_geometry = reader.counts.objects_with_geometry;
  r.skipped_objects = reader.counts.skipped_objects;
  r.surfaces = reader.counts.surfaces;
  r.surfaces_with_holes = reader.counts.surfaces_with_holes;
  r.triangles = reader.soup.triangles.size();
  r.vertices = reader.soup.vertices.size();
  r.lods_used = reader.counts.lods_used;
  if (reader.instances) r.notes.push_back(std::to_string(reader.instances) + " geometry instances (templates) placed");
  reader.notes.emit(r.notes);
  if (r.triangles == 0)
    throw InputError(file.string() + ": no triangles (" + std::to_string(r.objects) + " objects, " +
                     std::to_string(r.skipped_objects) + " skipped" +
                     (options.lod ? ", requested LoD " + printable_text(*options.lod) : std::string()) + ")");
  if (report) *report = std::move(r);
  return std::move(reader.soup);
}

}  // namespace

TriangleSoup read_cityjson(const std::filesystem::path& file, const CityModelReadOptions& options, CityModelReport* report) {
  try {
    return read_cityjson_unguarded(file, options, report);
  } catch (const nlohmann::json::exception& e) {
    // Every member is checked before use; this is a safety net so that no nlohmann exception
    // escapes as anything but an input error.
    throw InputError(file.string() + ": malformed CityJSON (" + printable_text(e.what()) + ")");
  }
}

}  // namespace skyband
