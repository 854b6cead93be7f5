#include "io/scene_file.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <system_error>

#include <toml++/toml.h>

#include "geometry/core/input_error.h"
#include "io/mesh_reader.h"
#include "io/scene_crs.h"
#include "io/toml_ascii.h"
#include "io/utf8_text.h"
#include "lighting/brdf/material.h"
#include "lighting/sun/sun_position.h"

namespace skyband {
namespace {

// Keys a scene may hold (leaves). Tables whose sub-keys are free: materials.assign.
const std::set<std::string>& known_keys() {
  static const std::set<std::string> k = {"meshes",
                                          "materials.default",
                                          "camera.position",
                                          "camera.look_at",
                                          "camera.up",
                                          "camera.fov_deg",
                                          "sun.altitude_deg",
                                          "sun.azimuth_deg",
                                          "sun.latitude_deg",
                                          "sun.longitude_deg",
                                          "sun.elevation_m",
                                          "sun.time",
                                          "sun.utc_offset_hours",
                                          "sky.model",
                                          "sky.aod550",
                                          "sky.angstrom_alpha",
                                          "sky.ozone_du",
                                          "sky.zenith_luminance_cd_m2",
                                          "quality.bands",
                                          "quality.tolerance",
                                          "quality.visibility",
                                          "quality.epsilon",
                                          "quality.samples",
                                          "quality.paper_scale",
                                          "quality.reuse_block",
                                          "quality.reuse_tolerance",
                                          "image.width",
                                          "image.height",
                                          "image.exposure"};
  return k;
}

// A string as a TOML basic string for messages: quotes and backslashes escaped, control
// characters written as escapes (utf8_text.h), so the message stays whole and on one line.
std::string toml_quoted(std::string_view v) {
  std::string q;
  for (const char c : v) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return '"' + printable_text(q) + '"';
}

std::string two_digits(unsigned v) {
  char b[8];
  std::snprintf(b, sizeof b, "%02u", v % 100u);
  return b;
}

// TOML's forms (https://toml.io/en/v1.0.0): what parse_iso8601 reads back for sun.time.
std::string date_text(const toml::date& d) {
  char b[16];
  std::snprintf(b, sizeof b, "%04u-%02u-%02u", unsigned{d.year}, unsigned{d.month}, unsigned{d.day});
  return b;
}
std::string time_text(const toml::time& t) {
  std::string s = two_digits(t.hour) + ":" + two_digits(t.minute) + ":" + two_digits(t.second);
  if (t.nanosecond > 0 && t.nanosecond <= 999999999u) {
    char b[16];
    std::snprintf(b, sizeof b, "%09u", static_cast<unsigned>(t.nanosecond));
    std::string digits = b;
    while (digits.back() == '0') digits.pop_back();
    s += "." + digits;
  }
  return s;
}
std::string date_time_text(const toml::date_time& dt) {
  std::string s = date_text(dt.date) + "T" + time_text(dt.time);
  if (dt.offset) {
    const int minutes = dt.offset->minutes;
    if (minutes == 0) return s + "Z";
    const unsigned m = static_cast<unsigned>(minutes < 0 ? -minutes : minutes);
    s += minutes < 0 ? '-' : '+';  // built with += : GCC 12 warns falsely (-Wrestrict) on "+" + string
    s += two_digits(m / 60);
    s += ':';
    s += two_digits(m % 60);
  }
  return s;
}

std::string float_text(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v < 0 ? "-inf" : "inf";
  char b[64];
  const auto [end, ec] = std::to_chars(b, b + sizeof b, v);  // shortest round-trip form
  std::string s(b, end);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

// A value as the user wrote it, for messages — our own formatter, never toml++'s: 3.3.0's has a
// float-cast overflow (undefined behaviour) when it prints an array holding a float below 0.1
// (found by fuzzing: `meshes = [0.01]`). Long arrays and tables are cut after a few items.
std::string node_text(const toml::node& n, int depth = 0) {
  if (const auto* v = n.as_string()) return toml_quoted(v->get());
  if (const auto* v = n.as_integer()) return std::to_string(v->get());
  if (const auto* v = n.as_floating_point()) return float_text(v->get());
  if (const auto* v = n.as_boolean()) return v->get() ? "true" : "false";
  if (const auto* v = n.as_date()) return date_text(v->get());
  if (const auto* v = n.as_time()) return time_text(v->get());
  if (const auto* v = n.as_date_time()) return date_time_text(v->get());
  constexpr std::size_t kItems = 8;
  if (const auto* a = n.as_array()) {
    if (depth >= 3) return a->empty() ? "[]" : "[…]";
    std::string s = "[";
    for (std::size_t i = 0; i < a->size() && i < kItems; ++i) s += (i ? ", " : "") + node_text(*a->get(i), depth + 1);
    return s + (a->size() > kItems ? ", …]" : "]");
  }
  if (const auto* t = n.as_table()) {
    if (depth >= 3) return t->empty() ? "{}" : "{…}";
    std::string s = "{";
    std::size_t i = 0;
    for (const auto& [k, v] : *t) {
      if (i == kItems) {
        s += ", …";
        break;
      }
      s += (i++ ? ", " : "") + printable_text(k.str()) + " = " + node_text(v, depth + 1);
    }
    return s + "}";
  }
  return "?";
}

class Reader {
 public:
  Reader(const toml::table& root, std::string file, const AsciiToml& text, std::map<std::string, std::string> overrides)
      : root_(root), file_(std::move(file)), text_(text), overrides_(std::move(overrides)) {}

  // "file:line:col: key = value" or "--set key=value" (line:col of the user's file).
  std::string where(const std::string& key, const toml::node* n) const {
    if (auto it = overrides_.find(key); it != overrides_.end()) return "--set " + printable_text(it->second);
    std::string w = file_;
    if (n && n->source().begin.line > 0 && !(n->source().path && *n->source().path == "--set")) {
      const auto& b = n->source().begin;
      w += ":" + std::to_string(b.line) + ":" + std::to_string(text_.original_column(b.line, b.column));
    }
    return w + ": " + printable_text(key) + (n ? " = " + node_text(*n) : "");
  }
  [[noreturn]] void fail(const std::string& key, const toml::node* n, const std::string& why) const {
    throw InputError(where(key, n) + ": " + why);
  }
  const toml::node* get(const std::string& key) const { return root_.at_path(key).node(); }

  std::optional<double> number(const std::string& key, double lo, double hi, const char* range_text) const {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    double v;
    if (const auto* i = n->as_integer())
      v = static_cast<double>(i->get());
    else if (const auto* f = n->as_floating_point())
      v = f->get();
    else
      fail(key, n, "expected a number");
    if (!std::isfinite(v)) fail(key, n, "not a finite number");
    if (v < lo || v > hi) fail(key, n, std::string("must be ") + range_text);
    return v;
  }
  std::optional<int> integer(const std::string& key, int lo, int hi) const {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    const auto* i = n->as_integer();
    if (!i) fail(key, n, "expected an integer");
    if (i->get() < lo || i->get() > hi) fail(key, n, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return static_cast<int>(i->get());
  }
  std::optional<bool> boolean(const std::string& key) const {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    const auto* b = n->as_boolean();
    if (!b) fail(key, n, "expected true or false");
    return b->get();
  }
  // A string value; a control character in it (from an escape such as \u0000) is an error: no
  // name, path or time holds one, and a NUL would cut the messages that quote it.
  const std::string& text(const std::string& key, const toml::node& n) const {
    const auto* s = n.as_string();
    if (!s) fail(key, &n, "expected a string");
    if (!is_printable_text(s->get())) fail(key, &n, "the string holds a control character");
    return s->get();
  }
  std::optional<std::string> string(const std::string& key, bool allow_datetime = false) const {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    if (n->is_string()) return text(key, *n);
    if (allow_datetime && (n->is_date_time() || n->is_date() || n->is_time())) return node_text(*n);
    fail(key, n, "expected a string");
  }
  std::optional<Vec3> vec3(const std::string& key) const {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    const auto* a = n->as_array();
    if (!a || a->size() != 3) fail(key, n, "expected an array of 3 numbers [x, y, z] (metres)");
    Vec3 v;
    for (std::size_t i = 0; i < 3; ++i) {
      const toml::node& e = *a->get(i);
      if (const auto* x = e.as_integer())
        v[static_cast<int>(i)] = static_cast<double>(x->get());
      else if (const auto* f = e.as_floating_point())
        v[static_cast<int>(i)] = f->get();
      else
        fail(key, n, "expected an array of 3 numbers [x, y, z] (metres)");
      if (!std::isfinite(v[static_cast<int>(i)])) fail(key, n, "not finite");
    }
    return v;
  }

  // Every leaf must be a known key (materials.assign.* free).
  void check_unknown(const toml::table& t, const std::string& prefix) const {
    for (const auto& [k, v] : t) {
      const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
      if (key == "materials.assign") {
        const auto* at = v.as_table();
        if (!at) fail(key, &v, "expected a table of usemtl-name = \"material\"");
        for (const auto& [mk, mv] : *at) {
          if (!mv.is_string()) fail(key + "." + std::string(mk.str()), &mv, "expected a material name string");
          text(key + "." + std::string(mk.str()), mv);
        }
        continue;
      }
      if (const auto* sub = v.as_table(); sub && !known_keys().count(key)) {
        check_unknown(*sub, key);
        continue;
      }
      if (!known_keys().count(key)) fail(key, &v, "unknown key");
    }
  }

 private:
  const toml::table& root_;
  std::string file_;
  const AsciiToml& text_;
  std::map<std::string, std::string> overrides_;
};

// Applies "key=value" to the table; records key → original text.
void apply_override(toml::table& root, const std::string& text, std::map<std::string, std::string>& origins) {
  const std::string shown = "--set '" + printable_text(text) + "'";
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError(shown + ": expected key=value (e.g. sun.altitude_deg=17)");
  const std::string key = text.substr(0, eq), value = text.substr(eq + 1);
  for (char c : key)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
      throw InputError(shown + ": key '" + printable_text(key) + "' may hold only letters, digits, '_', '-' and '.'");
  if (const std::size_t bad = first_invalid_utf8(value); bad != std::string::npos)
    throw InputError(shown + ": the value is not valid UTF-8 (at byte " + std::to_string(eq + 1 + bad) + ")");
  if (!is_printable_text(value)) throw InputError(shown + ": the value holds a control character");
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const auto dot = key.find('.', start);
    parts.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (parts.back().empty()) throw InputError(shown + ": empty component in key '" + key + "'");
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  // The value as TOML (numbers, booleans, strings in quotes, arrays); else as a plain string.
  toml::table* t = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    toml::node* n = t->get(parts[i]);
    if (!n) {
      t->insert_or_assign(parts[i], toml::table{});
      n = t->get(parts[i]);
    }
    if (!n->is_table()) throw InputError(shown + ": '" + parts[i] + "' is not a table in the scene");
    t = n->as_table();
  }
  bool done = false;
  try {
    const AsciiToml doc("v = " + value, "--set");  // toml++ sees ASCII only (toml_ascii.h)
    toml::table parsed = toml::parse(std::string_view(doc.text()), std::string_view("--set"));
    if (toml::node* v = parsed.get("v"); v && (v->is_string() || v->is_number() || v->is_boolean() || v->is_array())) {
      t->insert_or_assign(parts.back(), std::move(*v));
      done = true;
    }
  } catch (const toml::parse_error&) {  // not a TOML value: a plain string
  } catch (const InputError&) {         // e.g. a bare non-ASCII word (sky.model=Җ): a plain string
  }
  if (!done) t->insert_or_assign(parts.back(), value);
  origins[key] = text;
}

}  // namespace

SceneDescription parse_scene(std::string_view text, const std::filesystem::path& name, std::span<const std::string> overrides) {
  const std::string file = name.string();
  const AsciiToml ascii(text, file);  // toml++ 3.3.0 never sees a non-ASCII character (toml_ascii.h)
  toml::table root;
  try {
    root = toml::parse(std::string_view(ascii.text()), std::string_view(file));
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    throw InputError(file + ":" + std::to_string(b.line) + ":" + std::to_string(ascii.original_column(b.line, b.column)) + ": " +
                     printable_text(e.description()));
  }
  std::map<std::string, std::string> origins;
  for (const std::string& o : overrides) apply_override(root, o, origins);
  const Reader r(root, file, ascii, origins);
  r.check_unknown(root, "");

  SceneDescription s;
  s.file = name;
  const std::filesystem::path base = name.has_parent_path() ? name.parent_path() : std::filesystem::path(".");

  // meshes
  {
    const toml::node* n = r.get("meshes");
    if (!n) throw InputError(file + ": missing key 'meshes' (an array of mesh file paths)");
    const auto* a = n->as_array();
    if (!a || a->empty()) r.fail("meshes", n, "expected a non-empty array of mesh file paths");
    for (const toml::node& e : *a) {
      if (!e.is_string() || e.as_string()->get().empty()) r.fail("meshes", n, "every entry must be a non-empty path string");
      const std::string& entry = r.text("meshes", e);
      const std::filesystem::path p = std::filesystem::path(entry).is_absolute() ? std::filesystem::path(entry) : base / entry;
      // The error_code form: a path the system refuses (a component over 255 bytes: "File name
      // too long") is the user's input, not an internal error.
      std::error_code ec;
      const std::filesystem::file_status status = std::filesystem::status(p, ec);
      if (status.type() == std::filesystem::file_type::not_found)
        r.fail("meshes", &e, "file not found: " + printable_text(p.string()));
      if (ec) r.fail("meshes", &e, "cannot use the mesh path '" + printable_text(p.string()) + "': " + ec.message());
      if (!std::filesystem::is_regular_file(status)) r.fail("meshes", &e, "not a regular file: " + printable_text(p.string()));
      s.meshes.push_back(p);
    }
  }
  // materials
  if (auto d = r.string("materials.default")) {
    try {
      find_material(*d, "materials.default");
    } catch (const InputError& e) {
      r.fail("materials.default", r.get("materials.default"), e.what());
    }
    s.default_material = *d;
  }
  if (const toml::node* n = r.get("materials.assign")) {
    for (const auto& [k, v] : *n->as_table()) {
      const std::string key = "materials.assign." + std::string(k.str());
      const std::string& material = r.text(key, v);
      try {
        find_material(material, key);
      } catch (const InputError& e) {
        r.fail(key, &v, e.what());
      }
      s.material_assignment[std::string(k.str())] = material;
    }
  }
  // camera + image
  {
    const auto pos = r.vec3("camera.position");
    const auto at = r.vec3("camera.look_at");
    if (!pos) throw InputError(file + ": missing key 'camera.position' ([x, y, z], metres)");
    if (!at) throw InputError(file + ": missing key 'camera.look_at' ([x, y, z], metres)");
    s.camera.position = *pos;
    s.camera.look_at = *at;
    if (auto up = r.vec3("camera.up")) s.camera.up = *up;
    if (auto f = r.number("camera.fov_deg", 1e-3, 179.0, "in [0.001, 179] degrees")) s.camera.vertical_fov_deg = *f;
    if (auto w = r.integer("image.width", 1, 16384)) s.camera.width = *w;
    if (auto h = r.integer("image.height", 1, 16384)) s.camera.height = *h;
    if ((*at - *pos).norm() == 0) r.fail("camera.look_at", r.get("camera.look_at"), "equals camera.position");
    if (!(s.camera.up.norm() > 0) || (*at - *pos).normalized().cross(s.camera.up.normalized()).norm() < 1e-9)
      r.fail("camera.up", r.get("camera.up"), "zero or parallel to the view direction");
    if (auto e = r.number("image.exposure", 1e-300, 1e300, "> 0")) s.exposure = *e;
  }
  // sun
  {
    const bool by_angle = r.get("sun.altitude_deg") || r.get("sun.azimuth_deg");
    const bool by_place = r.get("sun.latitude_deg") || r.get("sun.longitude_deg") || r.get("sun.time") ||
                          r.get("sun.utc_offset_hours") || r.get("sun.elevation_m");
    if (by_angle && by_place)
      throw InputError(file + ": [sun] takes either altitude_deg/azimuth_deg or latitude_deg/longitude_deg/time, not both");
    if (by_place) {
      SpaInput in;
      const auto lat = r.number("sun.latitude_deg", -90, 90, "in [-90, 90] degrees");
      const auto lon = r.number("sun.longitude_deg", -180, 180, "in [-180, 180] degrees (east positive)");
      const auto time = r.string("sun.time", true);
      if (!lat || !lon || !time)
        throw InputError(file + ": sun from place and time needs sun.latitude_deg, sun.longitude_deg and sun.time");
      in.latitude_deg = *lat;
      in.longitude_deg = *lon;
      if (auto el = r.number("sun.elevation_m", -500, 9000, "in [-500, 9000] metres")) in.elevation_m = *el;
      const auto tz = r.number("sun.utc_offset_hours", -18, 18, "in [-18, 18] hours");
      try {
        in.time = parse_iso8601(*time, "sun.time", tz);
      } catch (const InputError& e) {
        r.fail("sun.time", r.get("sun.time"), e.what());
      }
      SpaResult res;
      try {
        res = sun_position_spa(in);  // its range errors name no file: say which key
      } catch (const InputError& e) {
        r.fail("sun.time", r.get("sun.time"), e.what());
      }
      s.sun_altitude_deg = 90.0 - res.zenith_deg;
      s.sun_azimuth_deg = res.azimuth_deg;
      std::ostringstream src;
      src << "NREL SPA: lat " << *lat << " lon " << *lon << " time " << *time;
      s.sun_source = src.str();
    } else {
      if (auto a = r.number("sun.altitude_deg", -90, 90, "in [-90, 90] degrees")) s.sun_altitude_deg = *a;
      if (auto a = r.number("sun.azimuth_deg", -360, 360, "in [-360, 360] degrees (clockwise from north)")) {
        double az = std::fmod(*a, 360.0);
        s.sun_azimuth_deg = az < 0 ? az + 360.0 : az;
      }
    }
  }
  // sky
  if (auto m = r.string("sky.model")) {
    try {
      s.sky_spec = parse_sky_model(*m, "sky.model");
    } catch (const InputError& e) {
      r.fail("sky.model", r.get("sky.model"), e.what());
    }
    s.sky_model = *m;
  } else {
    s.sky_spec = parse_sky_model(s.sky_model, "sky.model");
  }
  if (auto v = r.number("sky.aod550", 0, 10, "in [0, 10]")) s.atmosphere.aod550 = *v;
  if (auto v = r.number("sky.angstrom_alpha", -1, 4, "in [-1, 4]")) s.atmosphere.angstrom_alpha = *v;
  if (auto v = r.number("sky.ozone_du", 0, 1000, "in [0, 1000] DU")) s.atmosphere.ozone_du = *v;
  if (auto v = r.number("sky.zenith_luminance_cd_m2", 0, 1e7, "in [0, 1e7] cd/m2")) {
    if (s.sky_spec.physical)
      r.fail("sky.zenith_luminance_cd_m2", r.get("sky.zenith_luminance_cd_m2"), "applies to CIE skies only");
    s.sky_spec.zenith_luminance_cd_m2 = *v;
  }
  try {
    s.atmosphere.validate();
  } catch (const InputError& e) {
    throw InputError(file + ": [sky]: " + e.what());
  }
  // quality
  if (auto v = r.string("quality.visibility")) {
    if (*v == "auto")
      s.visibility = SkyFactorsMethod::automatic;
    else if (*v == "exact")
      s.visibility = SkyFactorsMethod::exact;
    else if (*v == "bands")
      s.visibility = SkyFactorsMethod::bands;
    else
      r.fail("quality.visibility", r.get("quality.visibility"), "must be \"auto\", \"exact\" or \"bands\"");
  }
  if (auto v = r.integer("quality.bands", 1, 4096)) s.bands = *v;
  if (auto v = r.number("quality.tolerance", 0, 1, "in [0, 1] (0 = fixed number of bands)")) s.tolerance = *v;
  if (auto v = r.number("quality.epsilon", 1e-12, 0.999, "in (0, 1)")) s.epsilon = *v;
  if (auto v = r.integer("quality.samples", 1, 256)) s.samples = *v;
  if (auto v = r.boolean("quality.paper_scale")) s.paper_scale = *v;
  if (auto v = r.integer("quality.reuse_block", 1, 1024)) s.reuse_block = *v;
  if (auto v = r.number("quality.reuse_tolerance", 0, 0.5, "in [0, 0.5] (0 = off)")) s.reuse_tolerance = *v;
  return s;
}

SceneDescription load_scene_file(const std::filesystem::path& file, std::span<const std::string> overrides) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open scene file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_scene(ss.str(), file, overrides);
}

TriangleSoup load_scene_geometry(const SceneDescription& scene, std::vector<std::string>* report) {
  TriangleSoup all;
  SceneCrs crs;
  for (const auto& path : scene.meshes) {
    MeshReadReport rep;
    TriangleSoup soup = read_mesh(path, &rep, crs.next({}));
    crs.add(rep);
    // Map usemtl names to built-in material names.
    std::vector<std::string> names;
    const std::size_t slots = std::max<std::size_t>(1, soup.material_names.size());
    for (std::size_t i = 0; i < slots; ++i) {
      const std::string usemtl = i < soup.material_names.size() ? soup.material_names[i] : std::string();
      std::string mat = scene.default_material;
      if (auto it = scene.material_assignment.find(usemtl); it != scene.material_assignment.end())
        mat = it->second;
      else
        for (const Material& m : builtin_materials())
          if (m.name == usemtl) mat = usemtl;
      names.push_back(mat);
    }
    soup.material_names = names;
    if (soup.triangle_material.empty()) soup.triangle_material.assign(soup.triangles.size(), 0);
    all.append(soup);
    if (report) report->push_back(rep.summary());
  }
  return all;
}

}  // namespace skyband
