#define BOOST_TEST_MODULE citygml_reader
#include <boost/test/unit_test.hpp>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/core/input_error.h"
#include "input_error_of.h"
#include "io/citygml_reader.h"
#include "io/mesh_reader.h"
#include "lighting/climate/climate_irradiation.h"
#include "shared_data.h"

using namespace skyband;
namespace fs = std::filesystem;
namespace tt = boost::test_tools;

namespace {

// Options reading each object at exactly LoD `lod`.
CityGmlReadOptions at_lod(const std::string& lod) {
  CityGmlReadOptions o;
  o.lod = lod;
  return o;
}

fs::path shared(const std::string& name) {
  return fs::path(SKYBAND_SHARED_DATA) / "citygml" / name;
}
const char* kTokyo2 = "plateau_tokyo_53394517_bldg_6697_2_op.citygml2.gml";
const char* kTokyo3 = "plateau_tokyo_53394517_bldg_6697_2_op.citygml3.gml";
const char* kYokosuka = "plateau_yokosuka_52397519_bldg_6697_op.citygml2.gml";
const char* kLyon3 = "lyon_opera_CityGML3.0_LOD2.gml";

fs::path temp_path() {
  return fs::temp_directory_path() / ("skyband_citygml_reader_test_" + std::to_string(::getpid()));
}

fs::path write_file(const std::string& name, const std::string& text) {
  fs::create_directories(temp_path());
  const fs::path p = temp_path() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// ---- Hand-made CityGML ---------------------------------------------------------------------

std::string number(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// A closed ring as a gml:posList (first vertex repeated at the end, as GML requires).
std::string pos_list(const std::vector<Vec3>& ring) {
  std::string out = "<gml:posList srsDimension=\"3\">";
  for (std::size_t i = 0; i <= ring.size(); ++i) {
    const Vec3& p = ring[i % ring.size()];
    out += number(p.x()) + " " + number(p.y()) + " " + number(p.z()) + (i < ring.size() ? " " : "");
  }
  return out + "</gml:posList>";
}

// A polygon whose outer ring is written as one gml:pos per vertex (the first repeated at the end).
std::string pos_polygon(const std::string& id, const std::vector<Vec3>& ring) {
  std::string out = "<gml:Polygon gml:id=\"" + id + "\"><gml:exterior><gml:LinearRing>";
  for (std::size_t i = 0; i <= ring.size(); ++i) {
    const Vec3& p = ring[i % ring.size()];
    out += "<gml:pos>" + number(p.x()) + " " + number(p.y()) + " " + number(p.z()) + "</gml:pos>";
  }
  return out + "</gml:LinearRing></gml:exterior></gml:Polygon>";
}

std::string polygon(const std::string& id, const std::vector<Vec3>& outer, const std::vector<std::vector<Vec3>>& holes = {}) {
  std::string out =
      "<gml:Polygon gml:id=\"" + id + "\"><gml:exterior><gml:LinearRing>" + pos_list(outer) + "</gml:LinearRing></gml:exterior>";
  for (const auto& h : holes) out += "<gml:interior><gml:LinearRing>" + pos_list(h) + "</gml:LinearRing></gml:interior>";
  return out + "</gml:Polygon>";
}

std::string multi_surface(const std::vector<std::string>& polygons) {
  std::string out = "<gml:MultiSurface>";
  for (const auto& p : polygons) out += "<gml:surfaceMember>" + p + "</gml:surfaceMember>";
  return out + "</gml:MultiSurface>";
}

// `extra`: more namespace declarations on the root (an ADE's).
std::string document(const std::string& version, const std::string& srs, const std::string& members,
                     const std::string& extra = "") {
  const std::string ns = "http://www.opengis.net/citygml/";
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<core:CityModel xmlns:core=\"" + ns + version + "\" xmlns:bldg=\"" + ns +
         "building/" + version + "\" xmlns:luse=\"" + ns + "landuse/" + version + "\" xmlns:veg=\"" + ns + "vegetation/" +
         version + "\" xmlns:dem=\"" + ns + "relief/" + version +
         "\" xmlns:gml=\"http://www.opengis.net/gml\" xmlns:xlink=\"http://www.w3.org/1999/xlink\"" + extra +
         ">\n"
         "<gml:boundedBy><gml:Envelope srsName=\"" +
         srs +
         "\" srsDimension=\"3\"><gml:lowerCorner>0 0 0</gml:lowerCorner>"
         "<gml:upperCorner>1 1 1</gml:upperCorner></gml:Envelope></gml:boundedBy>\n" +
         members + "</core:CityModel>\n";
}

// The box [lo, lo + (dx, dy, dz)]: its six faces as rings (outward, counter-clockwise seen from outside).
struct Box {
  Vec3 lo;
  double dx, dy, dz;
  Vec3 at(double x, double y, double z) const { return lo + Vec3(x * dx, y * dy, z * dz); }
  std::vector<Vec3> ground() const { return {at(0, 0, 0), at(0, 1, 0), at(1, 1, 0), at(1, 0, 0)}; }
  std::vector<Vec3> roof() const { return {at(0, 0, 1), at(1, 0, 1), at(1, 1, 1), at(0, 1, 1)}; }
  std::vector<Vec3> south() const { return {at(0, 0, 0), at(1, 0, 0), at(1, 0, 1), at(0, 0, 1)}; }
  std::vector<Vec3> east() const { return {at(1, 0, 0), at(1, 1, 0), at(1, 1, 1), at(1, 0, 1)}; }
  std::vector<Vec3> north() const { return {at(1, 1, 0), at(0, 1, 0), at(0, 1, 1), at(1, 1, 1)}; }
  std::vector<Vec3> west() const { return {at(0, 1, 0), at(0, 0, 0), at(0, 0, 1), at(0, 1, 1)}; }
};

// <bldg:boundedBy> with one thematic surface (LoD 2 polygons).
std::string thematic_surface(const std::string& type, const std::string& id, const std::vector<std::string>& polygons) {
  return "<bldg:boundedBy><bldg:" + type + " gml:id=\"" + id + "\"><bldg:lod2MultiSurface>" + multi_surface(polygons) +
         "</bldg:lod2MultiSurface></bldg:" + type + "></bldg:boundedBy>";
}

// A box building: LoD 2 as thematic surfaces (the south wall with a 2 m × 1 m window hole) and a
// lod2Solid referencing them by xlink (as PLATEAU writes it), plus an LoD 1 solid of its own polygons.
std::string box_building(const std::string& id, const Box& b, bool lod1 = true, bool lod2 = true,
                         const std::string& tag = "Building") {
  std::string out = "<bldg:" + tag + " gml:id=\"" + id + "\">";
  if (lod1) {
    out += "<bldg:lod1Solid><gml:Solid><gml:exterior><gml:CompositeSurface>";
    for (const auto& [n, ring] : std::vector<std::pair<std::string, std::vector<Vec3>>>{
             {"g", b.ground()}, {"r", b.roof()}, {"s", b.south()}, {"e", b.east()}, {"n", b.north()}, {"w", b.west()}})
      out += "<gml:surfaceMember>" + polygon(id + "_l1_" + n, ring) + "</gml:surfaceMember>";
    out += "</gml:CompositeSurface></gml:exterior></gml:Solid></bldg:lod1Solid>";
  }
  if (lod2) {
    out += "<bldg:lod2Solid><gml:Solid><gml:exterior><gml:CompositeSurface>";
    for (const char* n : {"g", "r", "s", "e", "n", "w"}) out += "<gml:surfaceMember xlink:href=\"#" + id + "_" + n + "\"/>";
    out += "</gml:CompositeSurface></gml:exterior></gml:Solid></bldg:lod2Solid>";
    const std::vector<Vec3> hole{b.lo + Vec3(4, 0, 2), b.lo + Vec3(4, 0, 3), b.lo + Vec3(6, 0, 3), b.lo + Vec3(6, 0, 2)};
    out += thematic_surface("GroundSurface", id + "_gs", {polygon(id + "_g", b.ground())});
    out += thematic_surface("RoofSurface", id + "_rs", {polygon(id + "_r", b.roof())});
    out += thematic_surface("WallSurface", id + "_ws", {polygon(id + "_s", b.south(), {hole})});
    out += thematic_surface("WallSurface", id + "_ws2",
                            {polygon(id + "_e", b.east()), polygon(id + "_n", b.north()), polygon(id + "_w", b.west())});
  }
  return out + "</bldg:" + tag + ">";
}

std::string member(const std::string& object) {
  return "<core:cityObjectMember>" + object + "</core:cityObjectMember>\n";
}

const Box kBox{Vec3(500000.25, 5400000.5, 10.125), 10, 20, 5};
const char* kProjected = "urn:ogc:def:crs:EPSG::25832";  // ETRS89 / UTM zone 32N

double area_m2(const TriangleSoup& s, std::size_t t) {
  const auto& tri = s.triangles[t];
  return 0.5 * (s.vertices[tri[1]] - s.vertices[tri[0]]).cross(s.vertices[tri[2]] - s.vertices[tri[0]]).norm();
}

std::map<std::string, double> area_by_material(const TriangleSoup& s) {
  std::map<std::string, double> out;
  for (std::size_t t = 0; t < s.triangle_count(); ++t) out[s.material_names.at(s.triangle_material.at(t))] += area_m2(s, t);
  return out;
}

// ---- An independent walk of the real files (plain string scanning, no XML library) --------

struct XmlWalk {
  std::size_t polygons = 0, triangles = 0;  // triangles: Σ over rings of (distinct consecutive vertices − 2)
};

// Polygons inside every <bldg:ELEMENT>...</bldg:ELEMENT> block: each posList's vertices with
// consecutive repeats and the closing repeat removed give n − 2 triangles (no ring has holes in
// these files: the walk checks).
XmlWalk walk_blocks(const std::string& text, const std::string& element) {
  XmlWalk w;
  const std::string open = "<bldg:" + element + ">", close = "</bldg:" + element + ">";
  for (std::size_t b = text.find(open); b != std::string::npos; b = text.find(open, b + 1)) {
    const std::size_t e = text.find(close, b);
    const std::string block = text.substr(b, e - b);
    BOOST_REQUIRE(block.find("<gml:interior") == std::string::npos);
    for (std::size_t p = block.find("<gml:Polygon"); p != std::string::npos; p = block.find("<gml:Polygon", p + 1)) ++w.polygons;
    for (std::size_t p = block.find("<gml:posList"); p != std::string::npos; p = block.find("<gml:posList", p + 1)) {
      const std::size_t start = block.find('>', p) + 1, end = block.find('<', start);
      std::istringstream in(block.substr(start, end - start));
      std::vector<std::array<std::string, 3>> ring;
      std::array<std::string, 3> v;
      while (in >> v[0] >> v[1] >> v[2])
        if (ring.empty() || ring.back() != v) ring.push_back(v);
      if (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
      w.triangles += ring.size() - 2;
    }
  }
  return w;
}

// ---- UTM forward by the Krüger series (Karney 2011, J. Geodesy 85, eqs. 7, 9, 35), to n⁴ ----
// (truncation error ~n⁵·a ≈ 10⁻⁷ m), on GRS80, independent of PROJ.
Vec3 utm_forward(double lat_deg, double lon_deg, int zone) {
  const double a = 6378137.0, f = 1 / 298.257222101, k0 = 0.9996, pi = std::acos(-1.0);
  const double n = f / (2 - f), n2 = n * n, n3 = n2 * n, n4 = n3 * n;
  const double A = a / (1 + n) * (1 + n2 / 4 + n4 / 64);
  const double alpha[4] = {n / 2 - 2 * n2 / 3 + 5 * n3 / 16 + 41 * n4 / 180, 13 * n2 / 48 - 3 * n3 / 5 + 557 * n4 / 1440,
                           61 * n3 / 240 - 103 * n4 / 140, 49561 * n4 / 161280};
  const double phi = lat_deg * pi / 180, lambda = (lon_deg - (6 * zone - 183)) * pi / 180;
  const double e = 2 * std::sqrt(n) / (1 + n);
  const double t = std::sinh(std::atanh(std::sin(phi)) - e * std::atanh(e * std::sin(phi)));
  const double xi1 = std::atan2(t, std::cos(lambda)), eta1 = std::atanh(std::sin(lambda) / std::sqrt(1 + t * t));
  double xi = xi1, eta = eta1;
  for (int j = 1; j <= 4; ++j) {
    xi += alpha[j - 1] * std::sin(2 * j * xi1) * std::cosh(2 * j * eta1);
    eta += alpha[j - 1] * std::cos(2 * j * xi1) * std::sinh(2 * j * eta1);
  }
  return Vec3(500000 + k0 * A * eta, k0 * A * xi, 0);
}

// The first vertex (latitude, longitude, height) of the first posList after `after` in `text`.
Vec3 first_position(const std::string& text, const std::string& after) {
  const std::size_t p = text.find("<gml:posList", text.find(after));
  std::istringstream in(text.substr(text.find('>', p) + 1, 200));
  Vec3 v;
  in >> v[0] >> v[1] >> v[2];
  return v;
}

}  // namespace

// ---- Hand-made files -----------------------------------------------------------------------

BOOST_AUTO_TEST_CASE(box_areas_materials_and_objects_in_closed_form) {
  const fs::path file = write_file("box.gml", document("2.0", kProjected, member(box_building("box1", kBox))));
  CityGmlReport report;
  const TriangleSoup s = read_citygml(file, {}, &report);
  // LoD 2 (the highest): ground and roof 10 × 20, walls 2·(10·5 + 20·5) minus the 2 m² window hole.
  const auto areas = area_by_material(s);
  BOOST_TEST(areas.size() == 3u);
  BOOST_TEST(areas.at("GroundSurface") == 200.0, tt::tolerance(1e-9));
  BOOST_TEST(areas.at("RoofSurface") == 200.0, tt::tolerance(1e-9));
  BOOST_TEST(areas.at("WallSurface") == 298.0, tt::tolerance(1e-9));
  // 6 polygons once each although the lod2Solid references them again; 5 quads give 2 triangles
  // each, the wall with its hole 8 (4 + 4 vertices, one hole: n + 2h − 2 = 8).
  BOOST_TEST(report.surfaces == 6u);
  BOOST_TEST(report.surfaces_with_holes == 1u);
  BOOST_TEST(s.triangle_count() == 18u);
  BOOST_TEST(report.thematic_surfaces == 4u);
  BOOST_TEST(report.objects == 1u);
  BOOST_TEST((report.lods_used == std::map<std::string, std::size_t>{{"2", 1}}));
  BOOST_TEST(report.format == "CityGML 2.0");
  BOOST_TEST(report.crs == kProjected);
  BOOST_TEST(report.reprojection.empty());
  // Every triangle belongs to box1; 8 box corners + 4 hole corners, shared.
  BOOST_TEST(s.object_names == std::vector<std::string>{"box1"});
  BOOST_TEST(s.triangle_object == std::vector<std::uint32_t>(18, 0));
  BOOST_TEST(s.vertices.size() == 12u);
  // Coordinates verbatim: each vertex is exactly a corner written in the file.
  std::set<std::array<double, 3>> written;
  for (const auto& ring : {kBox.ground(), kBox.roof()})
    for (const Vec3& p : ring) written.insert({p.x(), p.y(), p.z()});
  for (const Vec3& p : s.vertices) {
    const bool hole = p.y() == kBox.lo.y() && (p.z() == kBox.lo.z() + 2 || p.z() == kBox.lo.z() + 3);
    BOOST_TEST((hole || written.count({p.x(), p.y(), p.z()}) == 1));
  }
}

// core:externalReference (a link to a cadastre or another data set; every building of the Bavarian
// LoD2 files carries one, with core:informationSystem and core:externalObject) holds no geometry:
// the building reads as it does without it, in CityGML 2.0 and 1.0.
BOOST_AUTO_TEST_CASE(external_references_are_skipped) {
  const std::string plain = box_building("box1", kBox);
  const std::string reference =
      "<core:externalReference><core:informationSystem>http://www.adv-online.de</core:informationSystem>"
      "<core:externalObject><core:name>DEBY_LOD2_4906970</core:name></core:externalObject></core:externalReference>";
  const std::string tag = "<bldg:Building gml:id=\"box1\">";
  std::string with = plain;
  with.replace(with.find(tag), tag.size(), tag + reference);
  for (const std::string version : {"2.0", "1.0"}) {
    const TriangleSoup expected =
        read_citygml(write_file("plain" + version + ".gml", document(version, kProjected, member(plain))));
    CityGmlReport report;
    const TriangleSoup s =
        read_citygml(write_file("reference" + version + ".gml", document(version, kProjected, member(with))), {}, &report);
    BOOST_TEST(s.triangle_count() == expected.triangle_count());
    BOOST_TEST((s.vertices == expected.vertices));
    BOOST_TEST(report.objects == 1u);
    BOOST_TEST(area_by_material(s) == area_by_material(expected));
  }
}

BOOST_AUTO_TEST_CASE(lod_choice_exact_lod_and_building_parts) {
  const fs::path file = write_file("box_lods.gml", document("2.0", kProjected, member(box_building("box1", kBox))));
  CityGmlReport report;
  const TriangleSoup lod1 = read_citygml(file, at_lod("1"), &report);
  BOOST_TEST(lod1.triangle_count() == 12u);  // the LoD 1 solid: 6 quads, no hole
  BOOST_TEST((area_by_material(lod1) == std::map<std::string, double>{{"Building", 700.0}}));
  BOOST_TEST(read_citygml(file, at_lod("2.0")).triangle_count() == 18u);  // "2.0" = "2"
  BOOST_TEST(test::error_of([&] { read_citygml(file, at_lod("3")); }).find("no triangles") != std::string::npos);
  BOOST_TEST(test::error_of([&] { read_citygml(file, at_lod("2.2")); }).find("no triangles") != std::string::npos);
  BOOST_TEST(test::error_of([&] { read_citygml(file, at_lod("two")); }).find("is not a LoD") != std::string::npos);

  // A Building with an LoD 1 solid and a BuildingPart at LoD 2: by default the part alone (the
  // parent's LoD 1 would duplicate it); at LoD 1 the parent alone (the part has no LoD 1).
  const Box part{kBox.lo + Vec3(30, 0, 0), 10, 20, 5};
  std::string parent = box_building("parent", kBox, true, false);
  parent.insert(parent.rfind("</bldg:Building>"), "<bldg:consistsOfBuildingPart>" +
                                                      box_building("part", part, false, true, "BuildingPart") +
                                                      "</bldg:consistsOfBuildingPart>");
  const fs::path parts = write_file("parts.gml", document("2.0", kProjected, member(parent)));
  const TriangleSoup by_default = read_citygml(parts, {}, &report);
  BOOST_TEST(by_default.object_names == std::vector<std::string>{"part"});
  BOOST_TEST(report.objects == 2u);
  BOOST_TEST(report.skipped_objects == 1u);
  BOOST_TEST(by_default.triangle_count() == 18u);
  const TriangleSoup at_lod1 = read_citygml(parts, at_lod("1"), &report);
  BOOST_TEST(at_lod1.object_names == std::vector<std::string>{"parent"});
  BOOST_TEST(report.skipped_objects == 1u);
}

BOOST_AUTO_TEST_CASE(terrain_classes_are_ground_and_citygml_1_0_reads) {
  const std::vector<Vec3> field{kBox.lo + Vec3(-50, -50, 0), kBox.lo + Vec3(50, -50, 0), kBox.lo + Vec3(50, 50, 0),
                                kBox.lo + Vec3(-50, 50, 0)};
  const std::string land = "<luse:LandUse gml:id=\"field\"><luse:lod1MultiSurface>" + multi_surface({polygon("f", field)}) +
                           "</luse:lod1MultiSurface></luse:LandUse>";
  for (const std::string version : {"1.0", "2.0"}) {
    CityGmlReport report;
    const TriangleSoup s = read_citygml(
        write_file("land" + version + ".gml", document(version, kProjected, member(box_building("b", kBox)) + member(land))), {},
        &report);
    BOOST_TEST(report.format == "CityGML " + version);
    const std::vector<bool> ground = ground_triangle_mask(s, default_ground_materials());
    double ground_m2 = 0;
    for (std::size_t t = 0; t < s.triangle_count(); ++t)
      if (ground[t]) ground_m2 += area_m2(s, t);
    BOOST_TEST(ground_m2 == 100.0 * 100.0, tt::tolerance(1e-9));  // the LandUse field, not the building
    BOOST_TEST(area_by_material(s).at("LandUse") == 1e4, tt::tolerance(1e-9));
    BOOST_TEST(s.object_names.size() == 2u);
  }
}

// Two trees from one template (a unit box, defined in the first, referenced by xlink in the
// second): each instance is M·x + reference point with M = diag(2, 2, 3), so each tree is a
// 2 × 2 × 3 box of area 2·4 + 4·6 = 32 m² whose corners sit exactly at reference + M·corner.
BOOST_AUTO_TEST_CASE(implicit_geometries_are_placed) {
  const Box unit{Vec3(-0.5, -0.5, 0), 1, 1, 1};
  const std::string tpl = "<gml:MultiSurface gml:id=\"tpl\">" + [&] {
    std::string m;
    int k = 0;
    for (const auto& ring : {unit.ground(), unit.roof(), unit.south(), unit.east(), unit.north(), unit.west()})
      m += "<gml:surfaceMember>" + polygon("tpl_" + std::to_string(k++), ring) + "</gml:surfaceMember>";
    return m;
  }() + "</gml:MultiSurface>";
  auto tree = [&](const std::string& id, const std::string& geometry, const Vec3& ref) {
    return "<veg:SolitaryVegetationObject gml:id=\"" + id +
           "\"><veg:lod2ImplicitRepresentation><core:ImplicitGeometry>"
           "<core:transformationMatrix>2 0 0 0 0 2 0 0 0 0 3 0 0 0 0 1</core:transformationMatrix>" +
           geometry + "<core:referencePoint><gml:Point><gml:pos>" + number(ref.x()) + " " + number(ref.y()) + " " +
           number(ref.z()) +
           "</gml:pos></gml:Point></core:referencePoint></core:ImplicitGeometry></veg:lod2ImplicitRepresentation>"
           "</veg:SolitaryVegetationObject>";
  };
  const Vec3 a = kBox.lo + Vec3(-20, 0, 0), b = kBox.lo + Vec3(-40, 5, 0.5);
  const fs::path file = write_file(
      "trees.gml", document("2.0", kProjected,
                            member(tree("tree1", "<core:relativeGMLGeometry>" + tpl + "</core:relativeGMLGeometry>", a)) +
                                member(tree("tree2", "<core:relativeGMLGeometry xlink:href=\"#tpl\"/>", b))));
  CityGmlReport report;
  const TriangleSoup s = read_citygml(file, {}, &report);
  BOOST_TEST(s.object_names == (std::vector<std::string>{"tree1", "tree2"}));
  BOOST_TEST(s.triangle_count() == 24u);
  std::map<std::string, double> per_object;
  for (std::size_t t = 0; t < s.triangle_count(); ++t) per_object[s.object_names[s.triangle_object[t]]] += area_m2(s, t);
  BOOST_TEST(per_object.at("tree1") == 32.0, tt::tolerance(1e-12));
  BOOST_TEST(per_object.at("tree2") == 32.0, tt::tolerance(1e-12));
  BOOST_TEST(s.material_names == std::vector<std::string>{"SolitaryVegetationObject"});
  const Vec3 corner = b + Vec3(2 * 0.5, 2 * 0.5, 3 * 1.0);  // template corner (0.5, 0.5, 1)
  BOOST_TEST(std::count(s.vertices.begin(), s.vertices.end(), corner) == 1);
  BOOST_TEST((report.lods_used == std::map<std::string, std::size_t>{{"2", 2}}));
  // In a geographic CRS the reference point is in degrees and the template in metres: not read, and said.
  const fs::path geo = write_file(
      "trees_geo.gml",
      document("2.0", "EPSG:6697",
               member(tree("t", "<core:relativeGMLGeometry>" + tpl + "</core:relativeGMLGeometry>", Vec3(35.68, 139.69, 40)))));
  const std::string e = test::error_of([&] { read_citygml(geo); });
  BOOST_TEST(e.find("no triangles (1 city objects, 1 skipped)") != std::string::npos, e);
}

BOOST_AUTO_TEST_CASE(read_mesh_dispatches_and_reports_the_crs) {
  const fs::path file = write_file("box.citygml", document("2.0", kProjected, member(box_building("box1", kBox))));
  MeshReadReport report;
  const TriangleSoup s = read_mesh(file, &report);
  BOOST_TEST(s.triangle_count() == 18u);
  BOOST_TEST(report.format == "CityGML 2.0");
  BOOST_TEST(report.crs == kProjected);
  BOOST_TEST(report.faces_read == 6u);
  BOOST_TEST(report.summary().find("1 of 1 city objects read") != std::string::npos);
  MeshReadOptions lod1;
  lod1.lod = "1";
  BOOST_TEST(read_mesh(file, nullptr, lod1).triangle_count() == 12u);
}

BOOST_AUTO_TEST_CASE(bad_input_is_one_input_error_naming_the_file) {
  const std::string good = document("2.0", kProjected, member(box_building("box1", kBox)));
  auto error_of = [](const std::string& name, const std::string& text) {
    const fs::path p = write_file(name, text);
    const std::string e = test::error_of([&] { read_citygml(p); });
    BOOST_TEST(e.find(p.string()) == 0u, name << ": " << e);
    BOOST_TEST(e.find('\n') == std::string::npos);
    return e;
  };
  BOOST_TEST(error_of("empty.gml", "").find("not XML") != std::string::npos);
  BOOST_TEST(error_of("binary.gml", std::string("\x01\x02\xff\x00garbage", 11)).find("not XML") != std::string::npos);
  // UTF-16 (with or without a byte-order mark, either byte order): named as such, not "not XML".
  const auto utf16 = [&](bool big_endian, bool bom) {
    std::string out = bom ? (big_endian ? std::string("\xFE\xFF") : std::string("\xFF\xFE")) : std::string();
    for (const char c : good) out += big_endian ? std::string{'\0', c} : std::string{c, '\0'};
    return out;
  };
  for (const bool big : {false, true})
    for (const bool bom : {false, true}) {
      const std::string e = error_of(std::string("utf16") + (big ? "be" : "le") + (bom ? "bom" : "") + ".gml", utf16(big, bom));
      BOOST_TEST(e.find("UTF-16") != std::string::npos, e);
      BOOST_TEST(e.find("iconv") != std::string::npos, e);
    }
  // Cut in the middle: Xerces' message with line:column.
  const std::string cut = error_of("cut.gml", good.substr(0, good.size() / 2));
  BOOST_TEST(cut.find("malformed XML") != std::string::npos, cut);
  BOOST_TEST(cut.find("cut short?") != std::string::npos, cut);
  const std::string mismatched =
      error_of("mismatched.gml", good.substr(0, good.find("</core:cityObjectMember>")) + "</wrong></core:CityModel>");
  BOOST_TEST(mismatched.find("malformed XML") != std::string::npos, mismatched);
  BOOST_TEST(mismatched.find("cut short") == std::string::npos, mismatched);  // it ends as a CityModel does
  std::string nan = good;
  nan.replace(nan.find("10.125"), 6, "nan");
  BOOST_TEST(error_of("nan.gml", nan).find("non-finite coordinate in <gml:posList> 'nan'") != std::string::npos);
  std::string overflow = good;
  overflow.replace(overflow.find("10.125"), 6, "1e999");
  BOOST_TEST(error_of("overflow.gml", overflow).find("'1e999' is out of the range of a double") != std::string::npos);
  // What libcitygml would cut silently (it keeps the text after the last interruption): refused.
  for (const auto& [label, insert, expect] :
       std::vector<std::array<std::string, 3>>{{"comment.gml", " <!-- a comment --> ", "comment"},
                                               {"charref.gml", "&#32;", "character or entity reference"},
                                               {"cdata.gml", "<![CDATA[ 1 ]]>", "CDATA"},
                                               {"extra.gml", " 7", "not x y z triples"}}) {
    std::string t = good;
    t.insert(t.find(" ", t.find("<gml:posList srsDimension=\"3\">") + 31), insert);
    BOOST_TEST(error_of(label, t).find(expect) != std::string::npos, label);
  }
  std::string flat = good;
  flat.replace(flat.find("<gml:posList srsDimension=\"3\">"), 30, "<gml:posList srsDimension=\"2\">");
  const std::string flat_error = error_of("2d.gml", flat);
  BOOST_TEST(flat_error.find(": srsDimension is not 3") != std::string::npos, flat_error);
  BOOST_TEST(flat_error.find("::") == std::string::npos, flat_error);  // no empty location
  BOOST_TEST(error_of("nothing.gml", document("2.0", kProjected, member("<bldg:Building gml:id=\"b\"/>"))).find("no triangles") !=
             std::string::npos);
  BOOST_TEST(error_of("plain.xml", "<?xml version=\"1.0\"?><root><a/></root>").find("not CityGML 1.0 or 2.0") !=
             std::string::npos);
  BOOST_TEST(error_of("dtd.gml",
                      "<?xml version=\"1.0\"?><!DOCTYPE x [<!ENTITY a \"aaaa\">]>" + good.substr(good.find("<core:CityModel")))
                 .find("DOCTYPE") != std::string::npos);
  BOOST_TEST(error_of("geocentric.gml", document("2.0", "EPSG:4978", member(box_building("b", kBox)))).find("geocentric") !=
             std::string::npos);
  std::string mixed = good;
  mixed.insert(mixed.find("<gml:posList ") + 13, "srsName=\"EPSG:28992\" ");
  BOOST_TEST(error_of("mixed.gml", mixed).find("mixed CRSs") != std::string::npos);
  // Degrees that are not degrees: a geographic srsName over projected numbers.
  BOOST_TEST(error_of("not_degrees.gml", document("2.0", "EPSG:4326", member(box_building("b", kBox)))).find("axis order") !=
             std::string::npos);
  // A posList over 1 MiB, which libcitygml 2.4 would cut silently.
  std::vector<Vec3> long_ring;
  for (int i = 0; i < 40000; ++i) long_ring.push_back(kBox.lo + Vec3(std::cos(i * 1e-4), std::sin(i * 1e-4), 0));
  const std::string long_text =
      document("2.0", kProjected,
               member("<bldg:Building gml:id=\"b\"><bldg:lod1MultiSurface>" + multi_surface({polygon("p", long_ring)}) +
                      "</bldg:lod1MultiSurface></bldg:Building>"));
  BOOST_TEST(error_of("long.gml", long_text).find("cuts texts over 1 MiB") != std::string::npos);
  BOOST_TEST(test::error_of([] { read_citygml(temp_path() / "missing.gml"); }).find("does not exist") != std::string::npos);
}

// gml:pos, the coordinates libcitygml reads with no check at all, are checked as posList's are
// (every number a finite double, a whole position, plain text), and so is an implicit geometry's
// transformationMatrix; GML 2's gml:coordinates, which libcitygml drops, is refused. Each error
// names the file, the line and the value.
BOOST_AUTO_TEST_CASE(pos_and_matrix_values_are_checked_and_named) {
  const std::string good = document("2.0", kProjected,
                                    member("<bldg:Building gml:id=\"b\"><bldg:lod1MultiSurface>\n" +
                                           multi_surface({pos_polygon("g", kBox.ground()), pos_polygon("r", kBox.roof())}) +
                                           "\n</bldg:lod1MultiSurface></bldg:Building>"));
  BOOST_TEST(read_citygml(write_file("pos.gml", good)).triangle_count() == 4u);
  const std::string first = "<gml:pos>" + number(kBox.lo.x());  // the first vertex's x, on line 5
  auto error_of = [&](const std::string& name, const std::string& from, const std::string& to) {
    std::string text = good;
    text.replace(text.find(from), from.size(), to);
    const fs::path p = write_file(name, text);
    const std::string e = test::error_of([&] { read_citygml(p); });
    BOOST_TEST(e.find(p.string() + ":5: ") == 0u, name << ": " << e);
    BOOST_TEST(e.find('\n') == std::string::npos);
    return e;
  };
  for (const auto& [value, says] : std::vector<std::pair<std::string, std::string>>{{"1e400", "is out of the range of a double"},
                                                                                    {"-1e999", "is out of the range of a double"},
                                                                                    {"1e-400", "is out of the range of a double"},
                                                                                    {"NaN", "non-finite coordinate"},
                                                                                    {"-INF", "non-finite coordinate"},
                                                                                    {"1.0abc", "is not a number"},
                                                                                    {"1,5", "is not a number"}}) {
    const std::string e = error_of("pos_bad.gml", first, "<gml:pos>" + value);
    BOOST_TEST(e.find("'" + value + "'") != std::string::npos, e);
    BOOST_TEST(e.find(says) != std::string::npos, e);
    BOOST_TEST(e.find("<gml:pos>") != std::string::npos, e);
  }
  const std::string first_pos = good.substr(good.find("<gml:pos>"), good.find("</gml:pos>") + 10 - good.find("<gml:pos>"));
  BOOST_TEST(error_of("pos_empty.gml", first_pos, "<gml:pos></gml:pos>").find("<gml:pos> is empty") != std::string::npos);
  BOOST_TEST(error_of("pos_blank.gml", first_pos, "<gml:pos> </gml:pos>").find("<gml:pos> is empty") != std::string::npos);
  BOOST_TEST(error_of("pos_closed.gml", first_pos, "<gml:pos/>").find("<gml:pos> is empty") != std::string::npos);
  BOOST_TEST(error_of("pos_short.gml", first_pos, "<gml:pos>1 2</gml:pos>").find("holds 2 numbers, not x y z") !=
             std::string::npos);
  BOOST_TEST(error_of("pos_long.gml", first_pos, "<gml:pos>1 2 3 4</gml:pos>").find("holds 4 numbers, not x y z") !=
             std::string::npos);
  BOOST_TEST(error_of("pos_list_empty.gml", first_pos, "<gml:posList/>").find("<gml:posList> is empty") != std::string::npos);
  BOOST_TEST(
      error_of("coordinates.gml", first_pos, "<gml:coordinates>1,2,3</gml:coordinates>").find("write it as a gml:posList") !=
      std::string::npos);
  // A leading '+' is valid xs:double (and read).
  std::string plus = good;
  plus.replace(plus.find(first), first.size(), "<gml:pos>+" + number(kBox.lo.x()));
  BOOST_TEST(read_citygml(write_file("pos_plus.gml", plus)).triangle_count() == 4u);

  // An implicit geometry's matrix: 16 finite numbers.
  const std::string tree =
      "<veg:SolitaryVegetationObject gml:id=\"t\"><veg:lod2ImplicitRepresentation><core:ImplicitGeometry>\n"
      "<core:transformationMatrix>1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1</core:transformationMatrix><core:relativeGMLGeometry>" +
      multi_surface({polygon("p", {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)})}) +
      "</core:relativeGMLGeometry><core:referencePoint><gml:Point><gml:pos>500000 5400000 0</gml:pos></gml:Point>"
      "</core:referencePoint></core:ImplicitGeometry></veg:lod2ImplicitRepresentation></veg:SolitaryVegetationObject>";
  const std::string trees = document("2.0", kProjected, member(tree));
  BOOST_TEST(read_citygml(write_file("tree.gml", trees)).triangle_count() == 1u);
  for (const auto& [matrix, says] :
       std::vector<std::pair<std::string, std::string>>{{"1 0 0 0 0 1 0 0 0 0 nan 0 0 0 0 1", "'nan'"},
                                                        {"1 0 0 0 0 1 0 0 0 0 1 0 0 0 0", "holds 15 numbers, not 16"},
                                                        {"1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1x", "'1x' is not a number"}}) {
    std::string text = trees;
    text.replace(text.find("1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"), 31, matrix);
    const fs::path p = write_file("tree_bad.gml", text);
    const std::string e = test::error_of([&] { read_citygml(p); });
    BOOST_TEST(e.find(p.string() + ":5: ") == 0u, e);
    BOOST_TEST(e.find(says) != std::string::npos, e);
  }
}

// A vertex far beyond any place on Earth is read, with a warning in the report naming the file
// and the value (as for the mesh formats).
BOOST_AUTO_TEST_CASE(far_vertices_are_read_with_a_warning) {
  std::string text = document("2.0", kProjected, member(box_building("b", kBox, true, false)));
  text.replace(text.find(number(kBox.lo.x())), number(kBox.lo.x()).size(), "1e300");
  const fs::path p = write_file("far.gml", text);
  MeshReadReport report;
  read_mesh(p, &report);
  BOOST_TEST_REQUIRE(report.warnings.size() == 1u);
  BOOST_TEST(report.warnings[0].find(p.string() + ": 1 vertex with a coordinate beyond") == 0u, report.warnings[0]);
  BOOST_TEST(report.warnings[0].find("1.0000000000000001e+300") != std::string::npos, report.warnings[0]);
  BOOST_TEST(report.summary().find("warning: ") != std::string::npos);
  read_mesh(write_file("near.gml", document("2.0", kProjected, member(box_building("b", kBox)))), &report);
  BOOST_TEST(report.warnings.empty());
}

// Application Domain Extensions: their elements are not read (libcitygml would fail on a
// property whose ADE object it skips, and read an ADE element named like a CityGML one, such as
// an ADE's own lod2MultiSurface, as CityGML). An ADE subclass of a roof under bldg:boundedBy, an
// ADE property of the building and an ADE feature of its own are left out; the rest of the
// building reads, lines keep their numbers, and the report names the ADE and its elements.
BOOST_AUTO_TEST_CASE(ade_elements_are_not_read_and_named) {
  const std::string ns = " xmlns:test=\"http://www.example.org/ade/test/1.0\"";
  std::string building = box_building("b", kBox, false, true);
  // The roof surface as an ADE class; the solid's xlink to its polygon then finds nothing.
  const std::size_t roof = building.find("<bldg:RoofSurface");
  building.replace(roof, 17, "<test:IndustrialRoofSurface");
  building.replace(building.find("</bldg:RoofSurface>"), 19, "</test:IndustrialRoofSurface>");
  building.insert(building.find("<bldg:lod2Solid>"), "<test:energy><test:Certificate><test:lod2MultiSurface>" +
                                                         multi_surface({polygon("adeq", kBox.roof())}) +
                                                         "</test:lod2MultiSurface></test:Certificate></test:energy>\n");
  const std::string other = "<test:Thing gml:id=\"thing\"><test:lod2MultiSurface>" +
                            multi_surface({polygon("adep", kBox.ground())}) + "</test:lod2MultiSurface></test:Thing>";
  const std::string text = document("2.0", kProjected, member(building) + member(other), ns);
  CityGmlReport report;
  const TriangleSoup s = read_citygml(write_file("ade.gml", text), {}, &report);
  const auto areas = area_by_material(s);
  BOOST_TEST(areas.count("RoofSurface") == 0u);
  BOOST_TEST(areas.at("GroundSurface") == 200.0, tt::tolerance(1e-9));
  BOOST_TEST(areas.at("WallSurface") == 298.0, tt::tolerance(1e-9));
  BOOST_TEST(s.object_names == std::vector<std::string>{"b"});
  std::string ade_note;
  for (const std::string& n : report.notes)
    if (n.find("Application Domain Extension") != std::string::npos) ade_note = n;
  BOOST_TEST(ade_note.find("http://www.example.org/ade/test/1.0") != std::string::npos, ade_note);
  BOOST_TEST(ade_note.find("1 x <test:IndustrialRoofSurface>, 1 x <test:Thing>, 1 x <test:energy>") != std::string::npos,
             ade_note);
  // Lines keep their numbers after the blanked ADE elements: a bad value after them is found on
  // its own line.
  std::string bad = text;
  bad.replace(bad.rfind("</core:CityModel>"), 17,
              member("<bldg:Building gml:id=\"c\"><bldg:lod1MultiSurface>\n" + multi_surface({pos_polygon("x", kBox.roof())}) +
                     "</bldg:lod1MultiSurface></bldg:Building>") +
                  "</core:CityModel>");
  bad.replace(bad.rfind("<gml:pos>" + number(kBox.lo.x())), 9 + number(kBox.lo.x()).size(), "<gml:pos>NaN");
  const fs::path p = write_file("ade_bad.gml", bad);
  const std::size_t line = 1 + std::count(bad.begin(), bad.begin() + bad.rfind("<gml:pos>NaN"), '\n');
  const std::string e = test::error_of([&] { read_citygml(p); });
  BOOST_TEST(e.find(p.string() + ":" + std::to_string(line) + ": non-finite coordinate") == 0u, e);
  // A CityGML element libcitygml does not know, alone in its property: one line naming the place.
  const fs::path unknown = write_file("unknown.gml", document("2.0", kProjected, member("<bldg:Shed gml:id=\"s\"/>")));
  const std::string u = test::error_of([&] { read_citygml(unknown); });
  BOOST_TEST(u.find(unknown.string() + ":4:") == 0u, u);
  BOOST_TEST(u.find("cannot read the content of <core:cityobjectmember>") != std::string::npos, u);
  // A file of ADE features alone: one line naming the file and the ADE.
  const fs::path only = write_file("ade_only.gml", document("2.0", kProjected, member(other), ns));
  const std::string o = test::error_of([&] { read_citygml(only); });
  BOOST_TEST(o.find(only.string() + ": no triangles") == 0u, o);
  BOOST_TEST(o.find("Application Domain Extensions are not supported") != std::string::npos, o);
  BOOST_TEST(o.find("http://www.example.org/ade/test/1.0 (1 x <test:Thing>)") != std::string::npos, o);
  BOOST_TEST(o.find('\n') == std::string::npos);
}

// Relief components, which libcitygml 2.4 types but names "Unknown", carry their class name: a
// dem:TINRelief inside a dem:ReliefFeature (PLATEAU's dem files) is "TINRelief", a ground material.
BOOST_AUTO_TEST_CASE(tin_relief_is_named_and_ground) {
  auto triangle = [](const std::vector<Vec3>& t) {
    return "<gml:Triangle><gml:exterior><gml:LinearRing>" + pos_list(t) + "</gml:LinearRing></gml:exterior></gml:Triangle>";
  };
  const Vec3 o = kBox.lo;
  const std::string relief =
      "<dem:ReliefFeature gml:id=\"relief\"><dem:lod>1</dem:lod><dem:reliefComponent><dem:TINRelief gml:id=\"tin\">"
      "<dem:lod>1</dem:lod><dem:tin><gml:TriangulatedSurface><gml:trianglePatches>" +
      triangle({o, o + Vec3(100, 0, 0), o + Vec3(100, 100, 0)}) + triangle({o, o + Vec3(100, 100, 0), o + Vec3(0, 100, 0)}) +
      "</gml:trianglePatches></gml:TriangulatedSurface></dem:tin></dem:TINRelief></dem:reliefComponent></dem:ReliefFeature>";
  CityGmlReport report;
  const TriangleSoup s = read_citygml(
      write_file("relief.gml", document("2.0", kProjected, member(relief) + member(box_building("b", kBox)))), {}, &report);
  const auto areas = area_by_material(s);
  BOOST_TEST(areas.at("TINRelief") == 1e4, tt::tolerance(1e-9));
  BOOST_TEST(areas.count("Unknown") == 0u);
  const std::vector<bool> ground = ground_triangle_mask(s, default_ground_materials());
  double ground_m2 = 0;
  for (std::size_t t = 0; t < s.triangle_count(); ++t)
    if (ground[t]) ground_m2 += area_m2(s, t);
  BOOST_TEST(ground_m2 == 1e4, tt::tolerance(1e-9));  // the relief, not the building
}

// Geographic models read together share a UTM zone: tiles on both sides of 138° E (zones 53 and
// 54) are both projected to the zone given, the first one's, checked against the Krüger series;
// a model two zones away keeps its own (and the caller reports the different CRS).
BOOST_AUTO_TEST_CASE(geographic_models_share_the_utm_zone_given) {
  auto tile = [&](const std::string& name, double lon) {
    const Box b{Vec3(35.0, lon, 5), 0.0004, 0.0004, 10};  // latitude, longitude, height (EPSG:6668)
    return write_file(name, document("2.0", "EPSG:6668", member(box_building("b", b))));
  };
  const fs::path west = tile("west.gml", 137.9994), east = tile("east.gml", 138.0002), far = tile("far.gml", 150.5);
  CityGmlReport w, e, f;
  const TriangleSoup ws = read_citygml(west, {}, &w);
  BOOST_TEST_REQUIRE(w.utm_zone.has_value());
  BOOST_TEST(w.utm_zone->number == 53);
  BOOST_TEST(w.crs == "EPSG:6690");
  CityGmlReadOptions shared;
  shared.utm_zone = w.utm_zone;
  const TriangleSoup es = read_citygml(east, shared, &e);
  BOOST_TEST(e.crs == "EPSG:6690");
  BOOST_TEST((e.utm_zone == w.utm_zone));
  BOOST_TEST(e.reprojection.find("the zone of the models read before it") != std::string::npos, e.reprojection);
  // The east tile's south-west corner, projected to zone 53 by the series, is a vertex within 1 µm.
  const Vec3 en = utm_forward(35.0, 138.0002, 53);
  double best = 1e30;
  for (const Vec3& v : es.vertices) best = std::min(best, std::hypot(v.x() - en.x(), v.y() - en.y()));
  BOOST_TEST(best < 1e-6);
  BOOST_TEST(read_citygml(east, {}, &e).vertices.size() == es.vertices.size());
  BOOST_TEST(e.crs == "EPSG:6691");  // alone: its own zone, 54
  read_citygml(far, shared, &f);
  BOOST_TEST(f.utm_zone->number == 56);
  BOOST_TEST(f.crs == "EPSG:6693");
  BOOST_TEST(ws.triangle_count() > 0u);
}

// ---- The shared real files -----------------------------------------------------------------

BOOST_AUTO_TEST_CASE(citygml_3_is_refused_in_one_line, *test::needs_shared_data()) {
  for (const char* name : {kTokyo3, kLyon3}) {
    const std::string e = test::error_of([&] { read_mesh(shared(name)); });
    BOOST_TEST(e.find(shared(name).string()) == 0u, e);
    BOOST_TEST(e.find("CityGML 3.0 is not supported") != std::string::npos, e);
    BOOST_TEST(e.find("citygml-tools") != std::string::npos, e);
    BOOST_TEST(e.find('\n') == std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(tokyo_counts_match_an_independent_walk, *test::needs_shared_data()) {
  const std::string text = read_text(shared(kTokyo2));
  const XmlWalk lod2 = walk_blocks(text, "lod2MultiSurface");  // the thematic surfaces' polygons
  const XmlWalk lod1 = walk_blocks(text, "lod1Solid");
  BOOST_TEST(lod2.polygons == 650u);  // the README: 279 roof + 370 wall + 1 ground
  CityGmlReport report;
  const TriangleSoup s = read_citygml(shared(kTokyo2), {}, &report);
  BOOST_TEST(report.surfaces == lod2.polygons);
  BOOST_TEST(s.triangle_count() == lod2.triangles);
  BOOST_TEST((report.lods_used == std::map<std::string, std::size_t>{{"2", 1}}));
  std::map<std::string, std::size_t> per_material;
  for (const std::uint32_t m : s.triangle_material) ++per_material[s.material_names[m]];
  BOOST_TEST(per_material.size() == 3u);
  BOOST_TEST(per_material.count("RoofSurface") == 1u);
  BOOST_TEST(per_material.count("WallSurface") == 1u);
  BOOST_TEST(per_material.count("GroundSurface") == 1u);
  const TriangleSoup l1 = read_citygml(shared(kTokyo2), at_lod("1"), &report);
  BOOST_TEST(report.surfaces == lod1.polygons);
  BOOST_TEST(l1.triangle_count() == lod1.triangles);
}

BOOST_AUTO_TEST_CASE(yokosuka_lods_per_object, *test::needs_shared_data()) {
  const std::string text = read_text(shared(kYokosuka));
  // Every object (12 Buildings, 2 BuildingParts) has an LoD 1 solid; 1 Building and the 2 parts
  // of another (which has no geometry itself) have LoD 2 surfaces too (counted in the file with
  // a Python ElementTree walk: 14 lod1Solid, 9 thematic surfaces in 3 objects).
  const XmlWalk lod1 = walk_blocks(text, "lod1Solid");
  CityGmlReport report;
  const TriangleSoup l1 = read_citygml(shared(kYokosuka), at_lod("1"), &report);
  BOOST_TEST(report.surfaces == lod1.polygons);
  BOOST_TEST(l1.triangle_count() == lod1.triangles);
  BOOST_TEST((report.lods_used == std::map<std::string, std::size_t>{{"1", 14}}));
  const TriangleSoup best = read_citygml(shared(kYokosuka), {}, &report);
  BOOST_TEST((report.lods_used == std::map<std::string, std::size_t>{{"1", 11}, {"2", 3}}));
  BOOST_TEST(report.objects == 15u);
  BOOST_TEST(report.objects_with_geometry == 14u);
  BOOST_TEST(best.object_names.size() == 14u);
  // bldg:lod0FootPrint is not read by libcitygml: the report says so.
  bool lod0_noted = false;
  for (const std::string& n : report.notes) lod0_noted = lod0_noted || n.find("bldg:lod0FootPrint") != std::string::npos;
  BOOST_TEST(lod0_noted);
}

BOOST_AUTO_TEST_CASE(geographic_plateau_is_projected_to_utm_54n, *test::needs_shared_data()) {
  const std::string text = read_text(shared(kTokyo2));
  MeshReadReport report;
  const TriangleSoup s = read_mesh(shared(kTokyo2), &report);
  // EPSG:6697 = JGD2011 (latitude, longitude) + JGD2011 height: JGD2011 / UTM zone 54N + the same heights.
  BOOST_TEST(report.crs == "EPSG:6691+6695");
  // A known point: the first vertex of the first thematic surface, projected by the Krüger
  // series on GRS80 (JGD2011's ellipsoid), must be a vertex of the soup within 1 µm (the series
  // to n⁴ is good to ~10⁻⁷ m, PROJ's to nanometres; measured 5·10⁻⁸ m), its height copied exactly.
  const Vec3 llh = first_position(text, "<bldg:lod2MultiSurface>");
  BOOST_TEST(llh.x() > 35.0);
  BOOST_TEST(llh.x() < 36.0);
  const Vec3 en = utm_forward(llh.x(), llh.y(), 54);
  double best = 1e30;
  const Vec3* nearest = nullptr;
  for (const Vec3& v : s.vertices)
    if (const double d = std::hypot(v.x() - en.x(), v.y() - en.y()); d < best) best = d, nearest = &v;
  BOOST_TEST_MESSAGE("Krüger series vs the reader: " << best << " m");
  BOOST_TEST(best < 1e-6);
  BOOST_TEST(nearest->z() == llh.z());
  // Heights stay heights: the model's z range is the file's.
  double z_min = 1e30, z_max = -1e30;
  for (const Vec3& v : s.vertices) z_min = std::min(z_min, v.z()), z_max = std::max(z_max, v.z());
  BOOST_TEST(z_min > 0.0);
  BOOST_TEST(z_max < 100.0);
  // Plausible building: the box spans tens of metres, not degrees.
  double x_min = 1e30, x_max = -1e30;
  for (const Vec3& v : s.vertices) x_min = std::min(x_min, v.x()), x_max = std::max(x_max, v.x());
  BOOST_TEST(x_max - x_min > 20.0);
  BOOST_TEST(x_max - x_min < 500.0);
}

BOOST_AUTO_TEST_CASE(cleanup) {
  fs::remove_all(temp_path());
  BOOST_TEST(!fs::exists(temp_path()));
}
