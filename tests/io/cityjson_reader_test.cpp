#define BOOST_TEST_MODULE cityjson_reader
#include <boost/test/unit_test.hpp>

#include <unistd.h>
#include <nlohmann/json.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "geometry/core/input_error.h"
#include "geometry/mesh/mesh_defects.h"
#include "io/cityjson_reader.h"
#include "shared_data.h"

using namespace skyband;
namespace fs = std::filesystem;
namespace tt = boost::test_tools;
using json = nlohmann::json;

namespace {

fs::path shared(const std::string& name) {
  return fs::path(SKYBAND_SHARED_DATA) / "cityjson" / name;
}

fs::path temp_path() {
  return fs::temp_directory_path() / ("skyband_cityjson_reader_test_" + std::to_string(::getpid()));
}

fs::path temp_dir() {
  fs::create_directories(temp_path());
  return temp_path();
}

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

json load(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

// ---- An independent walk over the JSON (the test's own, written from the specification) ----
// A selection says which geometries of which objects the reader is expected to read.
using Select = std::function<bool(const std::string& object_type, const json& object, const json& geometry)>;

struct Walk {
  std::size_t objects = 0, objects_read = 0, surfaces = 0, surfaces_with_holes = 0, triangles = 0;
  // Σ over surfaces of (|N(outer)| − Σ |N(inner)|) / 2, N = Newell vector area ×2 (relative to the
  // first used vertex): the area of planar surfaces, computed without triangulating.
  double area_m2 = 0;
  std::map<std::string, std::size_t> triangles_by_material;
  std::vector<std::array<double, 3>> used_vertices;  // each chunk's used vertices, i·scale + translate
};

// Triangles of a surface: a triangulated polygon with V distinct vertices and h holes has
// V + 2h − 2 triangles (Euler's formula for a triangulated disc with h holes); degenerate rings
// (< 3 distinct indices after removing cyclic consecutive repeats) are dropped as the reader does.
void walk_chunk(const json& chunk, const json& transform, const Select& select, Walk& w) {
  const json& vertices = chunk.at("vertices");
  std::set<std::size_t> used;
  auto coordinate = [&](std::size_t i, int k) {
    return transform.is_null() ? vertices[i][k].get<double>()
                               : static_cast<double>(vertices[i][k].get<long long>()) * transform["scale"][k].get<double>() +
                                     transform["translate"][k].get<double>();
  };
  // Relative to a local origin (the first vertex) so that areas do not cancel at x ≈ 10⁵ m.
  auto position = [&](std::size_t i) {
    return Vec3(coordinate(i, 0) - coordinate(0, 0), coordinate(i, 1) - coordinate(0, 1), coordinate(i, 2) - coordinate(0, 2));
  };
  for (const auto& item : chunk.at("CityObjects").items()) {
    const json& o = item.value();  // not a structured binding: clang 14 cannot capture one in a lambda
    ++w.objects;
    bool read = false;
    for (const json& g : o.value("geometry", json::array())) {
      if (!select(o.at("type"), o, g)) continue;
      const std::string type = g.at("type");
      const int depth = type == "Solid" ? 2 : (type == "MultiSolid" || type == "CompositeSolid") ? 3 : 1;
      std::function<void(const json&, const json*, int)> rec = [&](const json& b, const json* values, int d) {
        for (std::size_t i = 0; i < b.size(); ++i) {
          const json* v = values && !values->is_null() ? &(*values)[i] : nullptr;
          if (d > 1) {
            rec(b[i], v, d - 1);
            continue;
          }
          std::size_t corners = 0, rings = 0;
          bool outer_ok = true;
          double area = 0;
          for (std::size_t r = 0; r < b[i].size(); ++r) {
            std::vector<std::size_t> ring;
            for (const json& k : b[i][r])
              if (ring.empty() || ring.back() != k.get<std::size_t>()) ring.push_back(k);
            if (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
            if (std::set<std::size_t>(ring.begin(), ring.end()).size() < 3) {
              if (r == 0) outer_ok = false;
              continue;
            }
            corners += ring.size();
            ++rings;
            Vec3 n = Vec3::Zero();
            for (std::size_t k = 0; k < ring.size(); ++k) n += position(ring[k]).cross(position(ring[(k + 1) % ring.size()]));
            area += (r == 0 ? 0.5 : -0.5) * n.norm();
            used.insert(ring.begin(), ring.end());
          }
          if (!outer_ok) continue;
          const std::size_t t = corners + 2 * (rings - 1) - 2;
          ++w.surfaces;
          if (rings > 1) ++w.surfaces_with_holes;
          w.area_m2 += area;
          w.triangles += t;
          std::string material = o.at("type");
          if (v && !v->is_null()) material = g.at("semantics").at("surfaces").at(v->get<std::size_t>()).at("type");
          w.triangles_by_material[material] += t;
          read = true;
        }
      };
      const json* values = g.contains("semantics") ? &g["semantics"]["values"] : nullptr;
      rec(g.at("boundaries"), values, depth);
    }
    if (read) ++w.objects_read;
  }
  for (const std::size_t i : used) {
    w.used_vertices.push_back({coordinate(i, 0), coordinate(i, 1), coordinate(i, 2)});
  }
}

Walk walk_file(const fs::path& p, const Select& select) {
  Walk w;
  if (p.extension() == ".jsonl") {
    std::ifstream in(p);
    std::string line;
    json header;
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      const json j = json::parse(line);
      if (j.at("type") == "CityJSON")
        header = j;
      else
        walk_chunk(j, header.at("transform"), select, w);
    }
  } else {
    const json j = load(p);
    walk_chunk(j, j.value("transform", json()), select, w);
  }
  return w;
}

std::map<std::string, std::size_t> triangles_by_material(const TriangleSoup& s) {
  std::map<std::string, std::size_t> out;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) ++out[s.material_names.at(s.triangle_material.at(t))];
  return out;
}

std::vector<std::array<double, 3>> sorted_vertices(const TriangleSoup& s) {
  std::vector<std::array<double, 3>> v;
  for (const Vec3& p : s.vertices) v.push_back({p.x(), p.y(), p.z()});
  std::sort(v.begin(), v.end());
  return v;
}

double unsigned_area(const TriangleSoup& s, const Vec3& origin) {
  double a = 0;
  for (const auto& t : s.triangles)
    a += 0.5 * (s.vertices[t[1]] - origin - (s.vertices[t[0]] - origin))
                   .cross(s.vertices[t[2]] - origin - (s.vertices[t[0]] - origin))
                   .norm();
  return a;
}

Vec3 vector_area(const TriangleSoup& s, const Vec3& origin) {
  Vec3 a = Vec3::Zero();
  for (const auto& t : s.triangles)
    a += 0.5 *
         (s.vertices[t[1]] - origin - (s.vertices[t[0]] - origin)).cross(s.vertices[t[2]] - origin - (s.vertices[t[0]] - origin));
  return a;
}

double timed_read_ms(const fs::path& p, TriangleSoup& soup, CityModelReport& report, const CityModelReadOptions& o = {}) {
  const auto start = std::chrono::steady_clock::now();
  soup = read_cityjson(p, o, &report);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  BOOST_TEST_MESSAGE(p.filename().string() << ": read in " << ms << " ms\n" << report.summary());
  return ms;
}

bool has_note(const CityModelReport& r, const std::string& part) {
  return std::any_of(r.notes.begin(), r.notes.end(), [&](const std::string& n) { return n.find(part) != std::string::npos; });
}

// The message of the InputError that reading `p` throws ("" if none).
std::string error_of(const fs::path& p, const CityModelReadOptions& o = {}) {
  try {
    read_cityjson(p, o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const Select kEverything = [](const std::string&, const json&, const json&) { return true; };

// A minimal CityJSON 2.0 document around one object's geometry.
std::string model(const std::string& geometry, const std::string& vertices, const std::string& extra = "",
                  const std::string& type = "Building") {
  return R"({"type":"CityJSON","version":"2.0","transform":{"scale":[0.001,0.001,0.001],"translate":[85000,446000,0]},)"
         R"("metadata":{"referenceSystem":"https://www.opengis.net/def/crs/EPSG/0/7415"},)" +
         extra + R"("CityObjects":{"b1":{"type":")" + type + R"(","geometry":[)" + geometry + R"(]}},"vertices":)" + vertices +
         "}";
}

// Unit cube as integers ×1000 (scale 0.001 → 1 m), outward-oriented Solid faces.
const std::string kCubeVertices =
    "[[0,0,0],[1000,0,0],[1000,1000,0],[0,1000,0],[0,0,1000],[1000,0,1000],[1000,1000,1000],[0,1000,1000]]";
const std::string kCubeShell = "[[[0,3,2,1]],[[4,5,6,7]],[[0,1,5,4]],[[1,2,6,5]],[[2,3,7,6]],[[3,0,4,7]]]";

}  // namespace

// ---- Shared real files -----------------------------------------------------------------------

BOOST_AUTO_TEST_CASE(delft_counts_materials_and_vertices_match_an_independent_walk, *skyband::test::needs_shared_data()) {
  const fs::path p = shared("delft.city.json");
  TriangleSoup soup;
  CityModelReport r;
  timed_read_ms(p, soup, r);
  const Walk w = walk_file(p, kEverything);  // every object has one LoD 1 geometry (README)
  BOOST_TEST(r.format == "CityJSON 2.0");
  BOOST_TEST(r.crs == "https://www.opengis.net/def/crs/EPSG/0/7415");
  // README: 160 Building + terrain, roads, water, vegetation; the walk counts 570 objects.
  BOOST_TEST(r.objects == w.objects);
  BOOST_TEST(r.objects == 570u);
  BOOST_TEST(r.objects_with_geometry == w.objects_read);
  BOOST_TEST(r.skipped_objects == 0u);
  BOOST_TEST(r.surfaces == w.surfaces);
  BOOST_TEST(r.triangles == w.triangles);
  BOOST_TEST(soup.triangle_count() == w.triangles);
  BOOST_TEST(r.lods_used == (std::map<std::string, std::size_t>{{"1", 570}}));
  // No semantics in this file: every triangle is named after its object's type.
  BOOST_TEST(triangles_by_material(soup) == w.triangles_by_material);
  BOOST_TEST(w.triangles_by_material.count("Building") == 1u);
  BOOST_TEST(w.triangles_by_material.count("Road") == 1u);
  // The transform: the soup's vertices are exactly i·scale + translate of the used vertices.
  BOOST_TEST(soup.vertices.size() == w.used_vertices.size());
  auto expected = w.used_vertices;
  std::sort(expected.begin(), expected.end());
  BOOST_TEST((sorted_vertices(soup) == expected));
  // ... and close to what the file means exactly: i/1000 + translate with the header's decimals
  // (84616.468, 447422.999, -0.452), evaluated in 80-bit long double (error ≤ 2⁻⁶⁴ relative).
  // Bound of the double formula: ½ ulp(i·ŝ) (product) + |i|·½ ulp(0.001) (scale not exact)
  // (< 1 ulp(i·s)) + ½ ulp(t) (translate not exact) + ½ ulp(x) (sum) < 2.5 ulp(M),
  // M = max(|i·s|, |t|, |x|):
  // relative to the terms, not to x, which may cancel (z ≈ 0.1 m = i·0.001 − 0.452).
  const json j = load(p);
  const double translate[3] = {84616.468, 447422.999, -0.452};
  const long double translate_exact[3] = {84616.468L, 447422.999L, -0.452L};
  std::size_t outside_bound = 0;
  std::array<double, 3> computed;  // of vertex 0, checked below
  for (std::size_t v = j["vertices"].size(); v-- > 0;)
    for (int k = 0; k < 3; ++k) {
      const long long i = j["vertices"][v][k];
      const double product = static_cast<double>(i) * 0.001;
      computed[k] = product + translate[k];
      const long double exact = i / 1000.0L + translate_exact[k];
      const double m = std::max({std::abs(product), std::abs(translate[k]), std::abs(computed[k])});
      const double ulp = std::nextafter(m, INFINITY) - m;
      if (!(std::abs(static_cast<long double>(computed[k]) - exact) <= 2.5L * ulp)) ++outside_bound;
    }
  BOOST_TEST(outside_bound == 0u);                                             // over all 18,262 × 3 coordinates
  BOOST_TEST(std::binary_search(expected.begin(), expected.end(), computed));  // vertex 0 is used
}

// One geometry of one object alone in a CityJSON 2.0 file, its vertices re-indexed (so that the
// file holds only what the geometry uses), with `transform` and `vertices` from `source`.
fs::path single_geometry_file(const json& source, const json& transform, const std::string& id, std::size_t g) {
  json one = {{"type", "CityJSON"}, {"version", "2.0"}, {"transform", transform}};
  json object = source["CityObjects"][id];
  object.erase("children");
  object.erase("parents");
  object["geometry"] = json::array({source["CityObjects"][id]["geometry"][g]});
  std::map<std::size_t, std::size_t> remap;
  json vertices = json::array();
  std::function<void(json&)> reindex = [&](json& b) {
    for (json& x : b) {
      if (x.is_array()) {
        reindex(x);
        continue;
      }
      const auto [it, inserted] = remap.try_emplace(x.get<std::size_t>(), vertices.size());
      if (inserted) vertices.push_back(source["vertices"][x.get<std::size_t>()]);
      x = it->second;
    }
  };
  reindex(object["geometry"][0]["boundaries"]);
  one["CityObjects"] = json::object({{id, object}});
  one["vertices"] = vertices;
  return write_file("single_geometry.city.json", one.dump());
}

// Open edges of a geometry's rings (an edge = unordered pair of distinct positions; open = used
// by exactly one ring side), counted on the file's integers: what a crack-free reader keeps.
std::size_t open_ring_edges(const json& source, const std::string& id, std::size_t g) {
  std::map<std::pair<std::vector<long long>, std::vector<long long>>, int> uses;
  std::function<void(const json&)> rec = [&](const json& b) {
    if (!b[0].is_array()) {  // a ring
      for (std::size_t i = 0; i < b.size(); ++i) {
        std::vector<long long> p = source["vertices"][b[i].get<std::size_t>()],
                               q = source["vertices"][b[(i + 1) % b.size()].get<std::size_t>()];
        if (p == q) continue;
        if (q < p) std::swap(p, q);
        ++uses[{p, q}];
      }
      return;
    }
    for (const json& x : b) rec(x);
  };
  rec(source["CityObjects"][id]["geometry"][g]["boundaries"]);
  return static_cast<std::size_t>(std::count_if(uses.begin(), uses.end(), [](const auto& e) { return e.second == 1; }));
}

BOOST_AUTO_TEST_CASE(bag_solids_give_closed_meshes_at_every_lod, *skyband::test::needs_shared_data()) {
  // Every 3D BAG BuildingPart Solid (v1: 3 parts, 2024 CityJSONSeq: 3 parts; LoD 1.2, 1.3 and
  // 2.2 each; 4 of the v1 LoD 2.2 surfaces have holes) is closed at ring level in the file (a
  // Python count made while writing this test: every ring edge used exactly twice, in opposite
  // directions); read alone, each must give a closed, consistently oriented triangle mesh. A hole
  // filled instead of cut out would use the hole's edges three times (non-manifold).
  std::vector<std::pair<json, json>> chunks;  // (chunk, transform)
  const json v1 = load(shared("3dbag_v1_sample_denhaag.city.json"));
  chunks.emplace_back(v1, v1["transform"]);
  std::ifstream in(shared("3dbag_v20240420_small.city.jsonl"));
  std::string line;
  json header;
  while (std::getline(in, line)) {
    const json j = json::parse(line);
    if (j["type"] == "CityJSON")
      header = j;
    else
      chunks.emplace_back(j, header["transform"]);
  }
  std::size_t solids = 0;
  for (const auto& [chunk, transform] : chunks)
    for (const auto& [id, o] : chunk["CityObjects"].items())
      for (std::size_t g = 0; g < o["geometry"].size(); ++g) {
        if (o["geometry"][g]["type"] != "Solid") continue;
        ++solids;
        BOOST_TEST_CONTEXT(id << " geometry " << g) {
          BOOST_TEST(open_ring_edges(chunk, id, g) == 0u);
          const TriangleSoup soup = read_cityjson(single_geometry_file(chunk, transform, id, g));
          const MeshDefects d = analyse_defects(soup);
          BOOST_TEST(soup.triangle_count() >= 12u);  // at least a box
          BOOST_TEST(d.boundary_edges == 0u);
          BOOST_TEST(d.non_manifold_edges == 0u);
          BOOST_TEST(d.inconsistently_oriented_edges == 0u);
        }
      }
  BOOST_TEST(solids == 18u);  // README: 3 + 3 parts × 3 LoDs
}

BOOST_AUTO_TEST_CASE(delft_building_solids_keep_the_files_open_edges_and_add_none, *skyband::test::needs_shared_data()) {
  // The delft LoD 1 Solids (3dfier) are not closed in the file: their walls have T-junctions and
  // some shells have gaps (a Python check: every one of the 160 has ring edges used once, and
  // the worst one's vector area is 0.6 × its area). The reader must add no crack: the soup's open
  // edges (after welding equal positions) are exactly the file's open ring edges.
  const json j = load(shared("delft.city.json"));
  std::size_t buildings = 0, open_total = 0;
  for (const auto& [id, o] : j["CityObjects"].items()) {
    if (o["type"] != "Building") continue;
    ++buildings;
    const std::size_t expected = open_ring_edges(j, id, 0);
    open_total += expected;
    const MeshDefects d = analyse_defects(read_cityjson(single_geometry_file(j, j["transform"], id, 0)));
    BOOST_TEST(d.boundary_edges == expected, id);
  }
  BOOST_TEST(buildings == 160u);  // README: 160 Building LoD1 Solids
  BOOST_TEST(open_total > 0u);    // the check above is not vacuous
}

BOOST_AUTO_TEST_CASE(bag_v1_default_reads_the_highest_lod_of_the_building_parts, *skyband::test::needs_shared_data()) {
  const fs::path p = shared("3dbag_v1_sample_denhaag.city.json");
  TriangleSoup soup;
  CityModelReport r;
  timed_read_ms(p, soup, r);
  BOOST_TEST(r.format == "CityJSON 1.0");
  BOOST_TEST(r.crs == "urn:ogc:def:crs:EPSG::7415");
  // README: 3 Building (LoD 0 only) + 3 BuildingPart (LoD 1.2, 1.3, 2.2): parts at 2.2, and the
  // parents' LoD 0 footprints skipped as superseded by their children.
  const Walk w = walk_file(p, [](const std::string& type, const json&, const json& g) {
    return type == "BuildingPart" && g["lod"].dump() == "2.2";  // lod is a JSON number in 1.0
  });
  BOOST_TEST(r.objects == 6u);
  BOOST_TEST(r.objects_with_geometry == 3u);
  BOOST_TEST(r.skipped_objects == 3u);
  BOOST_TEST(r.lods_used == (std::map<std::string, std::size_t>{{"2.2", 3}}));
  BOOST_TEST(has_note(r, "parent objects skipped"));
  BOOST_TEST(r.surfaces == w.surfaces);
  BOOST_TEST(r.triangles == w.triangles);
  BOOST_TEST(triangles_by_material(soup) == w.triangles_by_material);
  // Semantic surface types as material names, nothing named after the object type.
  for (const auto& [name, n] : triangles_by_material(soup))
    BOOST_TEST((name == "RoofSurface" || name == "WallSurface" || name == "GroundSurface"), name);
  BOOST_TEST(w.triangles_by_material.at("RoofSurface") > 0u);
  auto expected = w.used_vertices;
  std::sort(expected.begin(), expected.end());
  BOOST_TEST((sorted_vertices(soup) == expected));

  // Holes: the walk finds 4 surfaces with inner rings in the LoD 2.2 solids (a Python count
  // agrees: [19, 4], [12, 6], [14, 4] and [19, 8] ring sizes); the triangles' area must be
  // outer − holes, not outer (the 4 holes' Newell areas add up to tens of m²).
  BOOST_TEST(w.surfaces_with_holes == 4u);
  BOOST_TEST(r.surfaces_with_holes == 4u);
  // Tolerance: 3D BAG surfaces are planar up to the mm rounding of their vertices, which changes
  // a polygon's area at second order (≈ (10⁻³ m / 10 m)² relative); 10⁻⁶ relative covers it and
  // is far below the ≥ 10⁻³ relative change a filled hole would make.
  BOOST_TEST(unsigned_area(soup, soup.vertices[0]) == w.area_m2, tt::tolerance(1e-6));
  BOOST_TEST_MESSAGE("3D BAG v1 LoD 2.2 area " << w.area_m2 << " m2");
}

BOOST_AUTO_TEST_CASE(bag_v1_explicit_lod_selects_exactly_that_lod, *skyband::test::needs_shared_data()) {
  const fs::path p = shared("3dbag_v1_sample_denhaag.city.json");
  CityModelReport r12, r22, r0;
  const TriangleSoup s12 = read_cityjson(p, {.lod = "1.2"}, &r12);
  const TriangleSoup s22 = read_cityjson(p, {.lod = "2.2"}, &r22);
  const TriangleSoup s0 = read_cityjson(p, {.lod = "0"}, &r0);
  auto lod_is = [](const std::string& lod) {
    return [lod](const std::string&, const json&, const json& g) { return g["lod"].dump() == lod; };
  };
  const Walk w12 = walk_file(p, lod_is("1.2")), w22 = walk_file(p, lod_is("2.2")), w0 = walk_file(p, lod_is("0"));
  BOOST_TEST(r12.triangles == w12.triangles);
  BOOST_TEST(r22.triangles == w22.triangles);
  BOOST_TEST(r0.triangles == w0.triangles);
  BOOST_TEST(r12.triangles < r22.triangles);  // LoD 1.2 blocks are simpler than LoD 2.2 roofs
  // The 3 Buildings have no 1.2: skipped and counted; with "0" the 3 parts are skipped instead.
  BOOST_TEST(r12.skipped_objects == 3u);
  BOOST_TEST(r12.lods_used == (std::map<std::string, std::size_t>{{"1.2", 3}}));
  BOOST_TEST(has_note(r12, "no geometry of the requested LoD 1.2"));
  BOOST_TEST(r0.skipped_objects == 3u);
  BOOST_TEST(r0.lods_used == (std::map<std::string, std::size_t>{{"0", 3}}));
  BOOST_TEST(triangles_by_material(s0).count("Building") == 1u);  // LoD 0 has no semantics: object type
  // "2.20" is numerically 2.2 component by component? No: {2, 20} ≠ {2, 2}; "2.2.0" = {2, 2, 0} is.
  CityModelReport r220;
  read_cityjson(p, {.lod = "2.2.0"}, &r220);
  BOOST_TEST(r220.triangles == r22.triangles);
  BOOST_TEST(error_of(p, {.lod = "5"}).find("no triangles") != std::string::npos);
  BOOST_TEST(error_of(p, {.lod = "two"}).find("'two' is not a LoD") != std::string::npos);

  // keep_lower_lod_parents: the parents' LoD 0 footprints come back on top of the 2.2 parts.
  CityModelReport rk;
  read_cityjson(p, {.lod = std::nullopt, .keep_lower_lod_parents = true}, &rk);
  BOOST_TEST(rk.triangles == w22.triangles + w0.triangles);
  BOOST_TEST(rk.lods_used == (std::map<std::string, std::size_t>{{"0", 3}, {"2.2", 3}}));
}

BOOST_AUTO_TEST_CASE(bag_2024_cityjsonseq_is_read_feature_by_feature, *skyband::test::needs_shared_data()) {
  const fs::path p = shared("3dbag_v20240420_small.city.jsonl");
  TriangleSoup soup;
  CityModelReport r;
  timed_read_ms(p, soup, r);
  BOOST_TEST(r.format == "CityJSONSeq 2.0");
  BOOST_TEST(r.crs == "https://www.opengis.net/def/crs/EPSG/0/7415");
  BOOST_TEST(r.features == 3u);  // README: a header and 3 CityJSONFeature lines
  BOOST_TEST(r.objects == 6u);   // each feature: a Building (LoD 0) and a BuildingPart
  BOOST_TEST(r.lods_used == (std::map<std::string, std::size_t>{{"2.2", 3}}));
  const Walk w = walk_file(
      p, [](const std::string& type, const json&, const json& g) { return type == "BuildingPart" && g["lod"] == "2.2"; });
  BOOST_TEST(r.triangles == w.triangles);
  BOOST_TEST(triangles_by_material(soup) == w.triangles_by_material);
  // Each feature's own vertices with the header's transform (the walk does the same per feature).
  auto expected = w.used_vertices;
  std::sort(expected.begin(), expected.end());
  BOOST_TEST((sorted_vertices(soup) == expected));
  CityModelReport r12;
  read_cityjson(p, {.lod = "1.2"}, &r12);
  BOOST_TEST(r12.triangles < r.triangles);
}

BOOST_AUTO_TEST_CASE(rotterdam_without_crs_and_with_degenerate_rings, *skyband::test::needs_shared_data()) {
  const fs::path p = shared("rotterdam_subset.city.json");
  TriangleSoup soup;
  CityModelReport r;
  timed_read_ms(p, soup, r);
  BOOST_TEST(r.crs == "");
  BOOST_TEST(has_note(r, "no referenceSystem: coordinates taken as metres in an unknown projected CRS"));
  BOOST_TEST(r.objects == 16u);  // README: 16 Building LoD2 MultiSurfaces
  const Walk w = walk_file(p, kEverything);
  BOOST_TEST(r.surfaces == w.surfaces);
  BOOST_TEST(r.triangles == w.triangles);
  BOOST_TEST(triangles_by_material(soup) == w.triangles_by_material);
  // The file has rings with repeated vertices and rings of < 3 distinct vertices (counted by a
  // Python walk while writing this test: 12 such rings, 5 closed by repeating the first vertex):
  // repaired or skipped, with notes, never an error.
  BOOST_TEST(has_note(r, "fewer than 3 distinct vertices"));
  BOOST_TEST(has_note(r, "repeating their first vertex"));
}

BOOST_AUTO_TEST_CASE(shared_files_read_fast_enough, *skyband::test::needs_shared_data()) {
  // Not a benchmark: a guard against accidental quadratic behaviour. delft (1.46 MB, 36 k
  // surfaces) reads in ~100 ms on the development machine; 5 s leaves room for a loaded CI box.
  for (const char* name : {"delft.city.json", "3dbag_v1_sample_denhaag.city.json", "3dbag_v20240420_small.city.jsonl",
                           "rotterdam_subset.city.json"}) {
    TriangleSoup soup;
    CityModelReport r;
    BOOST_TEST(timed_read_ms(shared(name), soup, r) < 5000.0, name);
  }
}

// ---- Hand-made models ------------------------------------------------------------------------

BOOST_AUTO_TEST_CASE(square_with_square_hole_has_outer_minus_hole_area) {
  // 10 m × 10 m square with a 4 m × 4 m hole (integers ×1000, scale 0.001), RoofSurface.
  const std::string geometry = R"({"type":"MultiSurface","lod":"2","boundaries":[[[0,1,2,3],[4,7,6,5]]],)"
                               R"("semantics":{"surfaces":[{"type":"RoofSurface"}],"values":[0]}})";
  const std::string vertices =
      "[[0,0,5000],[10000,0,5000],[10000,10000,5000],[0,10000,5000],"
      "[3000,3000,5000],[7000,3000,5000],[7000,7000,5000],[3000,7000,5000]]";
  CityModelReport r;
  const TriangleSoup s = read_cityjson(write_file("hole.city.json", model(geometry, vertices)), {}, &r);
  // Closed form: 10² − 4² = 84 m², counter-clockwise seen from +z as the outer ring. The corners
  // are multiples of 1 m + (85000, 446000) m, exact in double: only the sums round (1e-13).
  const Vec3 a = vector_area(s, s.vertices[0]);
  BOOST_TEST(a.z() == 84.0, tt::tolerance(1e-13));
  BOOST_TEST(unsigned_area(s, s.vertices[0]) == 84.0, tt::tolerance(1e-13));
  BOOST_TEST(s.triangle_count() == 8u);  // V + 2h − 2 = 8 + 2 − 2
  BOOST_TEST(r.surfaces_with_holes == 1u);
  BOOST_TEST(s.material_names == std::vector<std::string>{"RoofSurface"});
  BOOST_TEST(s.vertices[0].x() == 85000.0);  // 0 · 0.001 + 85000
  BOOST_TEST(s.vertices[1].x() == 85010.0);  // 10000 · 0.001 + 85000 = 10.000000000000000208 + 85000 → 85010
}

BOOST_AUTO_TEST_CASE(cityjson_1_0_without_transform_reads_real_vertices) {
  const std::string text = R"({"type":"CityJSON","version":"1.0","metadata":{"referenceSystem":"urn:ogc:def:crs:EPSG::28992"},)"
                           R"("CityObjects":{"t":{"type":"TINRelief","geometry":[{"type":"CompositeSurface","lod":1,)"
                           R"("boundaries":[[[0,1,2]],[[0,2,3]]]}]}},)"
                           R"("vertices":[[0.5,0.25,1.125],[2.5,0.25,1.125],[2.5,3.25,1.125],[0.5,3.25,1.125]]})";
  CityModelReport r;
  const TriangleSoup s = read_cityjson(write_file("v10.json", text), {}, &r);
  BOOST_TEST(r.format == "CityJSON 1.0");
  BOOST_TEST(r.lods_used == (std::map<std::string, std::size_t>{{"1", 1}}));
  BOOST_TEST(s.triangle_count() == 2u);
  BOOST_TEST(s.material_names == std::vector<std::string>{"TINRelief"});  // a ground name
  BOOST_TEST(s.vertices[2].y() == 3.25);                                  // verbatim (exact binary fractions)
  BOOST_TEST(vector_area(s, s.vertices[0]).z() == 6.0);                   // 2 × 3 m, exact
}

// A translation of 1e15 m has doubles spaced 0.125 m apart (2^(49 − 52)): with a scale of 0.001 the
// vertices are rounded to 0.125 m, which the report says; at 85000 m the spacing is 1.5e-11 m
// (2^(16 − 52)), finer than the scale, and nothing is said.
BOOST_AUTO_TEST_CASE(a_translation_coarser_than_the_scale_is_reported) {
  const std::string geometry = R"({"type":"Solid","lod":"1","boundaries":[)" + kCubeShell + "]}";
  std::string text = model(geometry, kCubeVertices);
  CityModelReport fine;
  (void)read_cityjson(write_file("translate_fine.city.json", text), {}, &fine);
  BOOST_TEST(!has_note(fine, "coarser than the scale"));
  text.replace(text.find("[85000,446000,0]"), 16, "[1e15,446000,0]");
  CityModelReport coarse;
  const TriangleSoup s = read_cityjson(write_file("translate_coarse.city.json", text), {}, &coarse);
  BOOST_TEST(has_note(coarse, "transform translate 1e+15 holds coordinates only to 0.125 m, coarser than the scale 0.001"));
  BOOST_TEST(!has_note(coarse, "translate 446000"));
  BOOST_TEST(s.triangle_count() == 12u);
}

BOOST_AUTO_TEST_CASE(solid_multisolid_compositesolid_nesting_and_closed_cubes) {
  for (const char* type : {"Solid", "MultiSolid", "CompositeSolid"}) {
    const bool multi = std::string(type) != "Solid";
    const std::string boundaries = multi ? "[[" + kCubeShell + "]]" : "[" + kCubeShell + "]";
    // semantics.values nested like the surfaces: one level less than the rings.
    const std::string values = multi ? "[[[0,1,2,2,2,2]]]" : "[[0,1,2,2,2,2]]";
    const std::string geometry = std::string(R"({"type":")") + type + R"(","lod":"1.2","boundaries":)" + boundaries +
                                 R"(,"semantics":{"surfaces":[{"type":"GroundSurface"},{"type":"RoofSurface"},)"
                                 R"({"type":"WallSurface"}],"values":)" +
                                 values + "}}";
    const TriangleSoup s = read_cityjson(write_file("solid.city.json", model(geometry, kCubeVertices)));
    BOOST_TEST_CONTEXT(type) {
      BOOST_TEST(s.triangle_count() == 12u);  // 6 quads
      const MeshDefects d = analyse_defects(s);
      BOOST_TEST(d.boundary_edges == 0u);
      BOOST_TEST(d.non_manifold_edges == 0u);
      BOOST_TEST(d.inconsistently_oriented_edges == 0u);
      const auto m = triangles_by_material(s);
      BOOST_TEST(m.at("GroundSurface") == 2u);
      BOOST_TEST(m.at("RoofSurface") == 2u);
      BOOST_TEST(m.at("WallSurface") == 8u);
      // Outward orientation: the vector area of a closed surface is 0 and its volume
      // (divergence theorem, V = Σ (a·(b×c))/6) is +1 m³.
      double volume = 0;
      for (const auto& t : s.triangles) {
        const Vec3 o = s.vertices[0];
        volume += (s.vertices[t[0]] - o).dot((s.vertices[t[1]] - o).cross(s.vertices[t[2]] - o)) / 6.0;
      }
      BOOST_TEST(volume == 1.0, tt::tolerance(1e-12));  // unit cube, corners exact
    }
  }
}

BOOST_AUTO_TEST_CASE(null_semantic_values_fall_back_to_the_object_type) {
  const std::string geometry = R"({"type":"MultiSurface","lod":"1","boundaries":[[[0,1,2]],[[0,2,3]]],)"
                               R"("semantics":{"surfaces":[{"type":"TrafficArea"}],"values":[0,null]}})";
  const TriangleSoup s = read_cityjson(write_file("road.city.json", model(geometry, kCubeVertices, "", "Road")));
  const auto m = triangles_by_material(s);
  BOOST_TEST(m.at("TrafficArea") == 1u);
  BOOST_TEST(m.at("Road") == 1u);
}

BOOST_AUTO_TEST_CASE(geometry_instance_places_the_template) {
  // Template: a 1 m × 1 m square at z = 0 (real template vertices); instance: scaled ×2 in x,
  // ×3 in y, then translated to the reference point vertex 0 = (85000, 446000, 7) m.
  const std::string extra = R"("geometry-templates":{"templates":[{"type":"MultiSurface","lod":"2","boundaries":[[[0,1,2,3]]]}],)"
                            R"("vertices-templates":[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]},)";
  const std::string geometry =
      R"({"type":"GeometryInstance","template":0,"boundaries":[0],"transformationMatrix":[2,0,0,0, 0,3,0,0, 0,0,1,0, 0,0,0,1]})";
  CityModelReport r;
  const TriangleSoup s =
      read_cityjson(write_file("instance.city.json", model(geometry, "[[0,0,7000]]", extra, "SolitaryVegetationObject")), {}, &r);
  BOOST_TEST(s.triangle_count() == 2u);
  BOOST_TEST(r.lods_used == (std::map<std::string, std::size_t>{{"2", 1}}));
  BOOST_TEST(has_note(r, "1 geometry instances"));
  // Closed form: 2 × 3 = 6 m²; the far corner (1,1,0) maps to (2, 3, 0) + (85000, 446000, 7).
  BOOST_TEST(vector_area(s, Vec3(85000, 446000, 7)).z() == 6.0);
  const bool far_corner =
      std::any_of(s.vertices.begin(), s.vertices.end(), [](const Vec3& v) { return v == Vec3(85002, 446003, 7); });
  BOOST_TEST(far_corner);
  // A template index out of range is an error naming the path.
  const std::string bad =
      R"({"type":"GeometryInstance","template":3,"boundaries":[0],"transformationMatrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]})";
  const std::string e = error_of(write_file("bad_instance.city.json", model(bad, "[[0,0,0]]", extra)));
  BOOST_TEST(e.find("/CityObjects/b1/geometry/0/template") != std::string::npos, e);
  BOOST_TEST(e.find("out of range (1 templates)") != std::string::npos, e);
}

BOOST_AUTO_TEST_CASE(degenerate_rings_are_skipped_with_notes_not_errors) {
  // Surface 0: a ring of 2 distinct vertices (skipped); surface 1: a valid triangle closed by
  // repeating its first vertex; surface 2: a quad whose hole has 2 distinct vertices (hole dropped).
  const std::string geometry = R"({"type":"MultiSurface","lod":"2","boundaries":[[[0,1,0]],[[0,1,2,0]],[[0,1,2,3],[4,5,4]]]})";
  CityModelReport r;
  const TriangleSoup s = read_cityjson(write_file("degenerate.city.json", model(geometry, kCubeVertices)), {}, &r);
  BOOST_TEST(r.surfaces == 2u);
  BOOST_TEST(s.triangle_count() == 3u);  // 1 + 2
  BOOST_TEST(has_note(
      r,
      "1 x surfaces skipped: outer ring with fewer than 3 distinct vertices (first: /CityObjects/b1/geometry/0/boundaries/0/0)"));
  BOOST_TEST(has_note(r, "inner rings (holes) skipped"));
  BOOST_TEST(has_note(r, "repeating their first vertex"));
}

// ---- Errors: one small file per case; the message names file, path/id and value ------------

BOOST_AUTO_TEST_CASE(errors_name_file_path_and_value) {
  struct Case {
    std::string name, text;
    std::vector<std::string> expected;  // substrings of the message
  };
  const std::string ok_geometry = R"({"type":"MultiSurface","lod":"2","boundaries":[[[0,1,2]]]})";
  const std::vector<Case> cases{
      {"not_json.city.json", "{\"type\": \"CityJSON\",\n \"version\": 2.0,, }", {"not_json.city.json", "not JSON", "line 2"}},
      {"wrong_type.city.json",
       R"({"type":"FeatureCollection","features":[]})",
       {"/type", "\"FeatureCollection\" is not \"CityJSON\""}},
      {"version.city.json",
       R"({"type":"CityJSON","version":"3.0","CityObjects":{},"vertices":[]})",
       {"/version", "unsupported CityJSON version \"3.0\""}},
      {"index.city.json",
       model(R"({"type":"MultiSurface","lod":"2","boundaries":[[[0,1,99]]]})", kCubeVertices),
       {"/CityObjects/b1/geometry/0/boundaries/0/0/2", "vertex index 99 out of range (8 vertices)"}},
      {"negative_index.city.json",
       model(R"({"type":"MultiSurface","lod":"2","boundaries":[[[0,1,-2]]]})", kCubeVertices),
       {"/CityObjects/b1/geometry/0/boundaries/0/0/2", "vertex index -2 is not a non-negative integer"}},
      {"non_integer.city.json",
       model(ok_geometry, "[[0,0,0],[1000,0,0],[0,1000.5,0]]"),
       {"/vertices/2/1", "coordinate 1000.5 is not an integer"}},
      {"huge.city.json", model(ok_geometry, "[[0,0,0],[1000,0,0],[0,18014398509481984,0]]"), {"/vertices/2/1", "exceeds 2^53"}},
      {"nesting.city.json",
       model(R"({"type":"Solid","lod":"2","boundaries":[[[0,1,2]]]})", kCubeVertices),
       {"/CityObjects/b1/geometry/0/boundaries/0/0/0", "0 is not an array of vertex indices"}},
      {"unknown_geometry.city.json",
       model(R"({"type":"Polyhedron","lod":"2","boundaries":[]})", kCubeVertices),
       {"/CityObjects/b1/geometry/0/type", "unknown geometry type \"Polyhedron\""}},
      {"no_lod.city.json",
       model(R"({"type":"MultiSurface","boundaries":[[[0,1,2]]]})", kCubeVertices),
       {"/CityObjects/b1/geometry/0/lod", "missing"}},
      {"bad_semantics.city.json",
       model(R"({"type":"MultiSurface","lod":"2","boundaries":[[[0,1,2]]],"semantics":{"surfaces":[],"values":[4]}})",
             kCubeVertices),
       {"/CityObjects/b1/geometry/0/semantics/values/0", "semantic value 4 is not an index into the 0 semantic surfaces"}},
      {"wgs84.city.json",
       R"({"type":"CityJSON","version":"1.0","metadata":{"referenceSystem":"urn:ogc:def:crs:EPSG::4326"},"CityObjects":{},"vertices":[]})",
       {"/metadata/referenceSystem", "\"urn:ogc:def:crs:EPSG::4326\"", "geographic", "EPSG:4326", "degrees are not metres"}},
      {"plateau.city.json",
       R"({"type":"CityJSON","version":"2.0","transform":{"scale":[1,1,1],"translate":[0,0,0]},)"
       R"("metadata":{"referenceSystem":"https://www.opengis.net/def/crs/EPSG/0/6697"},"CityObjects":{},"vertices":[]})",
       {"EPSG:6697", "geographic"}},
      {"empty.city.json",
       model(R"({"type":"MultiSurface","lod":"2","boundaries":[[[0,1,0]]]})", kCubeVertices),
       {"empty.city.json: no triangles (1 objects"}},
      {"no_vertices.city.json", R"({"type":"CityJSON","version":"2.0","CityObjects":{}})", {"/vertices", "missing"}},
      {"bad_transform.city.json",
       R"({"type":"CityJSON","version":"2.0","transform":{"scale":[0.001,0,0.001],"translate":[0,0,0]},"CityObjects":{},"vertices":[]})",
       {"/transform/scale/1", "scale 0"}},
      {"scale_subnormal.city.json",
       R"({"type":"CityJSON","version":"2.0","transform":{"scale":[0.001,0.001,1e-320],"translate":[0,0,0]},"CityObjects":{},"vertices":[]})",
       {"/transform/scale/2", "scale 1e-320 is below 1e-12 m"}},
      {"overflow.city.json",
       R"({"type":"CityJSON","version":"1.0","CityObjects":{},"vertices":[[0,1e999,0]]})",
       {"not JSON", "number overflow", "1e999"}},
      {"inf.city.json",
       R"({"type":"CityJSON","version":"2.0","transform":{"scale":[1e300,1,1],"translate":[0,0,0]},"CityObjects":{},)"
       R"("vertices":[[1000000000,0,0]]})",
       {"/vertices/0/0", "coordinate 1000000000 is not finite after the transform"}},
      {"seq.city.jsonl",
       R"({"type":"CityJSON","version":"2.0","transform":{"scale":[0.001,0.001,0.001],"translate":[0,0,0]},"CityObjects":{},"vertices":[]})"
       "\n"
       R"({"type":"CityJSONFeature","id":"f1","CityObjects":{"f1":{"type":"Building","geometry":[)" +
           ok_geometry +
           R"(]}},"vertices":[[0,0,0],[1000,0,0],[0,1000,0]]})"
           "\n"
           R"({"type":"CityJSONFeature","id":"f2","CityObjects":{"f2":{"type":"Building","geometry":[)" +
           ok_geometry +
           R"(]}},"vertices":[[0,0,0],[1000,0,0]]})"
           "\n",
       {"seq.city.jsonl:3: ", "/CityObjects/f2/geometry/0/boundaries/0/0/2", "vertex index 2 out of range (2 vertices)"}},
      {"seq_type.city.jsonl",
       R"({"type":"CityJSON","version":"2.0","transform":{"scale":[1,1,1],"translate":[0,0,0]},"CityObjects":{},"vertices":[]})"
       "\n\n"
       R"({"type":"Feature"})",
       {"seq_type.city.jsonl:3: /type", "\"Feature\" is not \"CityJSONFeature\""}},
      {"seq_not_json.city.jsonl",
       R"({"type":"CityJSON","version":"2.0","transform":{"scale":[1,1,1],"translate":[0,0,0]},"CityObjects":{},"vertices":[]})"
       "\n{oops}\n",
       {"seq_not_json.city.jsonl:2: not JSON"}},
      {"seq_v10.city.jsonl",
       R"({"type":"CityJSON","version":"1.0","CityObjects":{},"vertices":[]})",
       {"seq_v10.city.jsonl:1: /version", "CityJSONSeq needs CityJSON 1.1 or 2.0"}},
  };
  for (const Case& c : cases) {
    const fs::path p = write_file(c.name, c.text);
    const std::string e = error_of(p);
    BOOST_TEST_MESSAGE(e);
    BOOST_TEST_CONTEXT(c.name << ": " << e) {
      BOOST_TEST(e.find(p.string()) == 0u);  // starts with the file name
      for (const std::string& part : c.expected) BOOST_TEST(e.find(part) != std::string::npos, part);
      BOOST_TEST(e.find('\n') == std::string::npos);  // one line
    }
  }
}

BOOST_AUTO_TEST_CASE(members_in_any_order_duplicates_and_json_edge_cases) {
  // The same model with its members in other orders (CityObjects before transform and vertices,
  // as cjio writes them) gives the same soup, vertex for vertex.
  const std::string geometry = R"({"type":"Solid","lod":"1","boundaries":[)" + kCubeShell + "]}";
  const std::string canonical = model(geometry, kCubeVertices);
  const json j = json::parse(canonical);
  json reordered_members = json::array();
  for (const char* key : {"vertices", "CityObjects", "metadata", "transform", "version", "type"})
    reordered_members.push_back(json::array({key, j.at(key)}));
  std::string reordered = "{";
  for (const json& m : reordered_members) {
    if (reordered.size() > 1) reordered += ',';
    reordered += m[0].dump();
    reordered += ':';
    reordered += m[1].dump();
  }
  reordered += '}';
  const TriangleSoup a = read_cityjson(write_file("canonical.city.json", canonical));
  const TriangleSoup b = read_cityjson(write_file("reordered.city.json", reordered));
  BOOST_TEST(b.triangle_count() == 12u);
  BOOST_TEST(sorted_vertices(a) == sorted_vertices(b));
  BOOST_TEST(a.triangles == b.triangles);

  // Of members with equal names the last counts (JSON objects keep one value per name).
  std::string twice = canonical;
  twice.insert(twice.find(R"("vertices":)"), R"("vertices":"ignored",)");
  BOOST_TEST(read_cityjson(write_file("twice.city.json", twice)).triangle_count() == 12u);

  // An integer beyond 64 bits is a JSON number like any other: fine in an attribute, too big
  // for a transformed vertex.
  std::string big = canonical;
  big.insert(big.find(R"("geometry":)"), R"("attributes":{"n":123456789012345678901234567890},)");
  BOOST_TEST(read_cityjson(write_file("big_attribute.city.json", big)).triangle_count() == 12u);
  std::string big_vertex = canonical;
  big_vertex.replace(big_vertex.find("[0,1000,1000]]"), 14, "[0,1000,123456789012345678901234567890]]");
  const std::string e1 = error_of(write_file("big_vertex.city.json", big_vertex));
  BOOST_TEST(e1.find("/vertices/7/2: integer coordinate 123456789012345678901234567890 exceeds 2^53") != std::string::npos, e1);

  // A missing quote is reported where the grammar breaks, not where simdjson's first pass notices
  // an odd number of quotes (the end of the text).
  std::string unquoted = canonical;
  unquoted.erase(unquoted.find(R"("version")"), 1);
  const std::size_t cut = unquoted.find(R"("metadata")") + 1;
  std::string quote = unquoted.substr(0, cut);
  quote += '\n';  // inside a string once the quotes are off by one
  quote += unquoted.substr(cut);
  const std::string e2 = error_of(write_file("quote.city.json", quote));
  BOOST_TEST(e2.find("not JSON (") != std::string::npos, e2);
  BOOST_TEST(e2.find("line 1, column") != std::string::npos, e2);

  // Nesting beyond 1024 levels, content after the value, a value not closed: not JSON, one line.
  const std::string deep = R"({"type":"CityJSON","version":"2.0","x":)" + std::string(1100, '[') + std::string(1100, ']') +
                           R"(,"CityObjects":{},"vertices":[]})";
  for (const auto& [name, text, part] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"deep.city.json", deep, "nested deeper than 1024 levels"},
           {"after.city.json", canonical + " x", "unexpected 'x' after the JSON value at line 1"},
           {"open.city.json", canonical.substr(0, canonical.size() - 1), "unexpected end of input"},
           {"ctrl.city.json",
            R"({"type":"CityJSON","version":"2.)"
            "\x01"
            R"("})",
            "unescaped control character in a string"},
           {"utf8.city.json",
            R"({"type":"CityJSON","version":"2.)"
            "\xC3\x28"
            R"("})",
            "invalid UTF-8 at line 1"}}) {
    const std::string e = error_of(write_file(name, text));
    BOOST_TEST(e.find("not JSON (") != std::string::npos, name << ": " << e);
    BOOST_TEST(e.find(part) != std::string::npos, name << ": " << e);
    BOOST_TEST(e.find('\n') == std::string::npos, name);
  }
}

BOOST_AUTO_TEST_CASE(crs_forms_are_kept_and_epsg_codes_parsed) {
  const std::string geometry = R"({"type":"MultiSurface","lod":"2","boundaries":[[[0,1,2]]]})";
  for (const std::string crs : {"urn:ogc:def:crs:EPSG::7415", "https://www.opengis.net/def/crs/EPSG/0/7415", "EPSG:28992"}) {
    std::string text = model(geometry, kCubeVertices);
    const std::string from = "https://www.opengis.net/def/crs/EPSG/0/7415";
    text.replace(text.find(from), from.size(), crs);
    CityModelReport r;
    read_cityjson(write_file("crs.city.json", text), {}, &r);
    BOOST_TEST(r.crs == crs);
    BOOST_TEST(!has_note(r, "referenceSystem"));
  }
  // A compound URN with a geographic horizontal part is refused; a geocentric CRS too.
  for (const std::string crs : {"urn:ogc:def:crs,crs:EPSG::4258,crs:EPSG::5709", "https://www.opengis.net/def/crs/EPSG/0/4978",
                                "http://www.opengis.net/def/crs/OGC/1.3/CRS84"}) {
    std::string text = model(geometry, kCubeVertices);
    const std::string from = "https://www.opengis.net/def/crs/EPSG/0/7415";
    text.replace(text.find(from), from.size(), crs);
    BOOST_TEST(error_of(write_file("crs_bad.city.json", text)).find("geographic or geocentric") != std::string::npos, crs);
  }
}

BOOST_AUTO_TEST_CASE(cityjsonseq_content_in_a_json_file_is_recognised, *skyband::test::needs_shared_data()) {
  // The shared .jsonl's bytes under a .json name (a temp file; the shared file itself is untouched).
  std::ifstream in(shared("3dbag_v20240420_small.city.jsonl"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CityModelReport r, seq;
  read_cityjson(write_file("seq_as.city.json", bytes), {}, &r);
  read_cityjson(shared("3dbag_v20240420_small.city.jsonl"), {}, &seq);
  BOOST_TEST(r.format == "CityJSONSeq 2.0");
  BOOST_TEST(r.triangles == seq.triangles);
  BOOST_TEST(has_note(r, "CityJSONSeq content"));
}

BOOST_AUTO_TEST_CASE(cleanup) {
  fs::remove_all(temp_path());
  BOOST_TEST(!fs::exists(temp_path()));
}

BOOST_AUTO_TEST_CASE(each_triangle_names_its_city_object) {
  // Two cubes in two objects and one object without geometry: 12 triangles per cube (6 quads,
  // 2 triangles each), each triangle pointing at its own CityObject id.
  const std::string text =
      R"({"type":"CityJSON","version":"2.0","transform":{"scale":[0.001,0.001,0.001],"translate":[0,0,0]},)"
      R"("CityObjects":{"a":{"type":"Building","geometry":[{"type":"Solid","lod":"1","boundaries":[)" +
      kCubeShell +
      R"(]}]},"empty":{"type":"Building"},"b":{"type":"Building","geometry":[{"type":"Solid","lod":"1","boundaries":[)" +
      kCubeShell + R"(]}]}},"vertices":)" + kCubeVertices + "}";
  const TriangleSoup s = read_cityjson(write_file("objects.city.json", text));
  BOOST_TEST(s.triangle_count() == 24u);
  BOOST_TEST(s.triangle_object.size() == 24u);
  std::map<std::string, std::size_t> per_object;
  for (const std::uint32_t o : s.triangle_object) ++per_object[s.object_names.at(o)];
  BOOST_TEST((per_object == std::map<std::string, std::size_t>{{"a", 12}, {"b", 12}}));

  // append keeps each soup's objects apart (even with equal names) and gives a soup without
  // objects one unnamed object.
  TriangleSoup joined = s;
  joined.append(s);
  TriangleSoup plain;
  append_box(plain, Vec3(5, 5, 0), Vec3(6, 6, 1));
  joined.append(plain);
  BOOST_TEST(joined.object_names.size() == 5u);
  BOOST_TEST(joined.triangle_object.size() == joined.triangle_count());
  BOOST_TEST(joined.triangle_object[30] == joined.triangle_object[24]);
  BOOST_TEST(joined.triangle_object[24] != joined.triangle_object[0]);
  BOOST_TEST(joined.object_names.back() == "");
  BOOST_TEST(joined.triangle_object.back() == 4u);
}
