#include "io/mesh_reader.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mutex>
#include <new>
#include <sstream>

#include "geometry/core/input_error.h"
#include "geometry/mesh/polygon_triangulation.h"
#include "io/citygml_reader.h"
#include "io/cityjson_reader.h"
#include "io/utf8_text.h"

namespace skyband {
namespace mesh_io {

void split_tokens(std::string_view text, std::vector<std::string_view>& out) {
  out.clear();
  auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f' || c == '\r' || c == '\n'; };
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && is_space(text[i])) ++i;
    const std::size_t start = i;
    while (i < text.size() && !is_space(text[i])) ++i;
    if (i > start) out.push_back(text.substr(start, i - start));
  }
}

double parse_coordinate(std::string_view token, const std::string& name, std::size_t line, const char* what) {
  std::string_view t = token;
  if (t.size() > 1 && t[0] == '+' && (std::isdigit(static_cast<unsigned char>(t[1])) || t[1] == '.')) t.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value, std::chars_format::general);
  const std::string where = name + ":" + std::to_string(line) + ": ";
  if (ec == std::errc::result_out_of_range)
    throw InputError(where + what + " '" + printable_text(token) + "' is out of the range of a double");
  if (ec != std::errc() || end != t.data() + t.size())
    throw InputError(where + what + " '" + printable_text(token) + "' is not a number");
  if (!std::isfinite(value)) throw InputError(where + "non-finite " + what + " '" + printable_text(token) + "'");
  return value;
}

long long parse_integer(std::string_view token, const std::string& name, std::size_t line, const char* what) {
  std::string_view t = token;
  if (t.size() > 1 && t[0] == '+') t.remove_prefix(1);
  long long value = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (ec != std::errc() || end != t.data() + t.size())
    throw InputError(name + ":" + std::to_string(line) + ": " + what + " '" + printable_text(token) + "' is not an integer");
  return value;
}

void reject_nul_bytes(const std::string& name, std::string_view text, const char* what, std::size_t first_line) {
  const std::size_t nul = text.find('\0');
  if (nul == std::string_view::npos) return;
  std::size_t line = first_line, line_start = 0;
  for (std::size_t i = 0; i < nul; ++i)  // LF, CR LF and lone CR each end a line, as in for_each_line
    if (text[i] == '\n' || (text[i] == '\r' && (i + 1 >= text.size() || text[i + 1] != '\n'))) ++line, line_start = i + 1;
  throw InputError(name + ":" + std::to_string(line) + ": NUL byte at column " + std::to_string(nul - line_start + 1) + " of " +
                   what + " (binary data in a text file?)");
}

void add_vertex(PolygonSoup& soup, const Vec3& p) {
  for (int i = 0; i < 3; ++i)
    if (static_cast<double>(static_cast<float>(p[i])) != p[i]) soup.float32_exact = false;
  soup.vertices.push_back(p);
}

}  // namespace mesh_io

namespace {

using mesh_io::PolygonSoup;

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using OpenMeshPolyMesh = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string read_whole_file(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InputError("mesh file '" + file.string() + "' does not exist");
  if (std::filesystem::is_directory(file, ec)) throw InputError("mesh file '" + file.string() + "' is a directory, not a file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("cannot open mesh file '" + file.string() + "': " + std::strerror(errno));
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError("cannot read mesh file '" + file.string() + "'");
  return bytes;
}

bool same_position(const Vec3& a, const OpenMesh::Vec3d& b) {
  return a.x() == b[0] && a.y() == b[1] && a.z() == b[2];
}

std::string describe(const Vec3& p) {
  std::ostringstream s;
  s.precision(17);
  s << '(' << p.x() << ", " << p.y() << ", " << p.z() << ')';
  return s.str();
}

// Tries OpenMesh. Returns true and fills `out` (vertices + polygons in file order) only when
// OpenMesh reproduced every polygon of the validating pass with bit-identical corner positions
// (compared as cyclic sequences); otherwise returns false with the reason.
bool read_with_openmesh(const std::filesystem::path& file, const PolygonSoup& soup, PolygonSoup& out, std::string& reason) {
  if (!soup.float32_exact) {
    for (const Vec3& p : soup.vertices)
      for (int i = 0; i < 3; ++i)
        if (static_cast<double>(static_cast<float>(p[i])) != p[i]) {
          std::ostringstream s;
          s.precision(17);
          s << "OpenMesh 9 reads coordinates as 32-bit floats and would round " << p[i] << " to "
            << static_cast<double>(static_cast<float>(p[i]));
          reason = s.str();
          return false;
        }
  }
  static std::once_flag quiet;
  std::call_once(quiet, [] {  // OpenMesh prints one warning line per complex vertex/edge
    omerr().disable();
    omout().disable();
    omlog().disable();
  });
  OpenMeshPolyMesh mesh;
  OpenMesh::IO::Options options;
  bool ok = false;
  try {
    ok = OpenMesh::IO::read_mesh(mesh, file.string(), options);
  } catch (const std::bad_alloc&) {
    // Never fall back silently: our pass has bounded every count by the file's size, so OpenMesh
    // running out of memory means it read the file differently from our check.
    throw InputError(file.string() +
                     ": OpenMesh 9 ran out of memory reading this file (it reads its layout "
                     "differently from skyband's check); the file is malformed");
  } catch (const std::exception& e) {
    reason = std::string("OpenMesh 9 threw: ") + e.what();
    return false;
  }
  if (!ok) {
    reason = "OpenMesh 9 could not read the file";
    return false;
  }
  if (mesh.n_faces() != soup.polygon_count()) {
    const long long lost = static_cast<long long>(soup.polygon_count()) - static_cast<long long>(mesh.n_faces());
    reason = lost > 0 ? "OpenMesh 9 dropped " + std::to_string(lost) + " of " + std::to_string(soup.polygon_count()) + " faces"
                      : "OpenMesh 9 read " + std::to_string(mesh.n_faces()) + " faces, the file has " +
                            std::to_string(soup.polygon_count());
    return false;
  }
  out.vertices.clear();
  out.vertices.reserve(mesh.n_vertices());
  for (const auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    out.vertices.emplace_back(p[0], p[1], p[2]);
  }
  out.polygon_start.assign(1, 0);
  out.indices.clear();
  std::vector<std::uint32_t> ring;
  for (std::size_t f = 0; f < mesh.n_faces(); ++f) {
    ring.clear();
    for (const auto v : mesh.fv_range(OpenMesh::FaceHandle(static_cast<int>(f))))
      ring.push_back(static_cast<std::uint32_t>(v.idx()));
    const std::uint32_t b = soup.polygon_start[f], e = soup.polygon_start[f + 1];
    const std::size_t n = e - b;
    bool match = ring.size() == n;
    if (match) {
      match = false;
      for (std::size_t shift = 0; shift < n && !match; ++shift) {
        bool all = true;
        for (std::size_t k = 0; k < n && all; ++k)
          all = same_position(soup.vertices[soup.indices[b + k]],
                              mesh.point(OpenMesh::VertexHandle(static_cast<int>(ring[(k + shift) % n]))));
        match = all;
      }
    }
    if (!match) {
      reason = "OpenMesh 9 changed face " + std::to_string(f + 1) + " (corner " + describe(soup.vertices[soup.indices[b]]) + ")";
      return false;
    }
    // Keep the file's starting corner so that the face is the file's, not a rotation of it.
    std::size_t shift = 0;
    for (; shift < n; ++shift)
      if (same_position(soup.vertices[soup.indices[b]], mesh.point(OpenMesh::VertexHandle(static_cast<int>(ring[shift]))))) break;
    for (std::size_t k = 0; k < n; ++k) out.indices.push_back(ring[(k + shift) % n]);
    out.polygon_start.push_back(static_cast<std::uint32_t>(out.indices.size()));
  }
  out.polygon_material = soup.polygon_material;
  out.material_names = soup.material_names;
  out.polygon_object = soup.polygon_object;
  out.object_names = soup.object_names;
  return true;
}

// A warning when a triangle's corner lies beyond kFarCoordinate_m on some axis: the farthest one and the count.
void warn_about_far_vertices(const TriangleSoup& soup, MeshReadReport& r) {
  std::vector<char> far(soup.vertices.size(), 0);
  std::size_t count = 0, worst = 0;
  double worst_m = 0;
  for (const auto& t : soup.triangles)
    for (const std::uint32_t v : t) {
      const double m = soup.vertices[v].cwiseAbs().maxCoeff();
      if (!(m > kFarCoordinate_m) || far[v]) continue;
      far[v] = 1;
      ++count;
      if (m > worst_m) worst_m = m, worst = v;
    }
  if (count == 0) return;
  const Vec3& p = soup.vertices[worst];
  char line[256];
  std::snprintf(line, sizeof line, "%zu %s with a coordinate beyond +-%.0e m, the farthest at (%.17g, %.17g, %.17g)", count,
                count == 1 ? "vertex" : "vertices", kFarCoordinate_m, p.x(), p.y(), p.z());
  r.warnings.push_back(r.file + ": " + line +
                       ": no place on Earth is that far in a projected CRS (a corrupt or sentinel value, or the wrong unit?)");
}

}  // namespace

const std::vector<std::string>& supported_mesh_extensions() {
  static const std::vector<std::string> extensions{".obj", ".off", ".ply", ".stl", ".json", ".jsonl", ".gml", ".xml", ".citygml"};
  return extensions;
}

std::string MeshReadReport::summary() const {
  std::ostringstream s;
  s << file << ": " << format << ", read by " << reader << "\n";
  s << "  " << vertices_in_file << " vertices, " << faces_read << " of " << faces_in_file << " faces read, " << triangles
    << " triangles";
  if (polygons_triangulated) s << " (" << polygons_triangulated << " polygons triangulated";
  if (polygons_triangulated && polygons_fanned) s << ", " << polygons_fanned << " of them fanned";
  if (polygons_triangulated) s << ")";
  s << "\n  defects after welding identical positions: " << defects.summary();
  for (const auto& n : notes) s << "\n  note: " << n;
  for (const auto& w : warnings) s << "\n  warning: " << w;
  return s.str();
}

// CityJSON through its own reader (io/cityjson_reader.h), reported in the mesh readers' terms.
TriangleSoup read_city_model(const std::filesystem::path& file, MeshReadReport* report, const MeshReadOptions& options) {
  CityModelReport c;
  CityModelReadOptions city;
  city.lod = options.lod;
  TriangleSoup soup = read_cityjson(file, city, &c);
  if (report) {
    MeshReadReport r;
    r.file = c.file;
    r.format = c.format;
    r.reader = options.lod ? "skyband CityJSON reader (each object at LoD " + *options.lod + ")"
                           : std::string("skyband CityJSON reader (each object at its highest LoD)");
    r.vertices_in_file = c.vertices;
    r.crs = c.crs;
    r.faces_in_file = r.faces_read = c.surfaces;
    r.triangles = c.triangles;
    r.polygons_triangulated = c.surfaces;
    r.notes.push_back(std::to_string(c.objects_with_geometry) + " of " + std::to_string(c.objects) + " city objects read (" +
                      std::to_string(c.skipped_objects) + " skipped), " + std::to_string(c.surfaces_with_holes) +
                      " surfaces with holes");
    std::string lods;
    for (const auto& [lod, n] : c.lods_used)
      lods += (lods.empty() ? "" : ", ") + std::string("LoD ") + lod + ": " + std::to_string(n);
    if (!lods.empty()) r.notes.push_back(lods);
    if (!c.crs.empty()) r.notes.push_back("referenceSystem " + c.crs);  // without one the reader's own note says so
    r.notes.insert(r.notes.end(), c.notes.begin(), c.notes.end());
    r.defects = analyse_defects(soup);
    warn_about_far_vertices(soup, r);
    *report = std::move(r);
  }
  return soup;
}

// CityGML through io/citygml_reader.h (libcitygml), reported in the mesh readers' terms.
TriangleSoup read_citygml_model(const std::filesystem::path& file, MeshReadReport* report, const MeshReadOptions& options) {
  CityGmlReport c;
  CityGmlReadOptions city;
  city.lod = options.lod;
  city.utm_zone = options.utm_zone;
  TriangleSoup soup = read_citygml(file, city, &c);
  if (report) {
    MeshReadReport r;
    r.file = c.file;
    r.format = c.format;
    r.reader = options.lod ? "libcitygml 2.4 + skyband CityGML reader (each object at LoD " + *options.lod + ")"
                           : std::string("libcitygml 2.4 + skyband CityGML reader (each object at its highest LoD)");
    r.vertices_in_file = c.vertices;
    r.crs = c.crs;
    r.utm_zone = c.utm_zone;
    r.faces_in_file = r.faces_read = c.surfaces;
    r.triangles = c.triangles;
    r.polygons_triangulated = c.surfaces;
    r.notes.push_back(std::to_string(c.objects_with_geometry) + " of " + std::to_string(c.objects) + " city objects read (" +
                      std::to_string(c.skipped_objects) + " skipped), " + std::to_string(c.thematic_surfaces) +
                      " thematic surfaces, " + std::to_string(c.surfaces_with_holes) + " polygons with holes");
    std::string lods;
    for (const auto& [lod, n] : c.lods_used)
      lods += (lods.empty() ? "" : ", ") + std::string("LoD ") + lod + ": " + std::to_string(n);
    if (!lods.empty()) r.notes.push_back(lods);
    if (!c.crs_in_file.empty())
      r.notes.push_back("srsName " + c.crs_in_file + (c.crs != c.crs_in_file ? "; output in " + c.crs : std::string()));
    r.notes.insert(r.notes.end(), c.notes.begin(), c.notes.end());
    r.defects = analyse_defects(soup);
    warn_about_far_vertices(soup, r);
    *report = std::move(r);
  }
  return soup;
}

TriangleSoup read_mesh(const std::filesystem::path& file, MeshReadReport* report, const MeshReadOptions& options) {
  const std::string name = file.string();
  if (is_cityjson_path(file)) return read_city_model(file, report, options);
  if (is_citygml_path(file)) return read_citygml_model(file, report, options);
  if (options.lod)
    throw InputError(name + ": --lod " + *options.lod +
                     " applies to city models (CityJSON, CityJSONSeq, CityGML); this file has no LoDs");
  const std::string extension = lower(file.extension().string());
  const auto& supported = supported_mesh_extensions();
  if (std::find(supported.begin(), supported.end(), extension) == supported.end()) {
    std::string list;
    for (const auto& e : supported) list += (list.empty() ? "" : ", ") + e;
    throw InputError(name + ": unknown mesh file extension '" + file.extension().string() + "' (supported: " + list + ")");
  }
  const std::string bytes = read_whole_file(file);

  if (extension == ".obj" || extension == ".off") refuse_wide_text(name, bytes, extension == ".obj" ? "OBJ" : "OFF");
  PolygonSoup soup;
  if (extension == ".obj")
    soup = mesh_io::parse_obj(name, bytes);
  else if (extension == ".off")
    soup = mesh_io::parse_off(name, bytes);
  else if (extension == ".ply")
    soup = mesh_io::parse_ply(name, bytes);
  else
    soup = mesh_io::parse_stl(name, bytes);

  if (soup.polygon_count() == 0)
    throw InputError(name + ": empty mesh: no faces (" + std::to_string(soup.vertices.size()) + " vertices)");

  MeshReadReport r;
  r.file = name;
  r.format = soup.format;
  r.vertices_in_file = soup.vertices.size();
  r.faces_in_file = soup.faces_declared;
  r.notes = soup.notes;

  PolygonSoup from_openmesh;
  std::string reason;
  const PolygonSoup* used = &soup;
  if (!soup.not_for_openmesh.empty()) {
    // The validating pass knows layouts OpenMesh 9 mishandles (OFF always; a PLY element without
    // properties): OpenMesh is not even tried.
    r.reader = "skyband polygon soup (" + soup.not_for_openmesh + ")";
  } else if (read_with_openmesh(file, soup, from_openmesh, reason)) {
    used = &from_openmesh;
    r.reader = "OpenMesh 9";
    if (from_openmesh.vertices.size() != soup.vertices.size())
      r.notes.push_back("OpenMesh 9 duplicated " + std::to_string(from_openmesh.vertices.size() - soup.vertices.size()) +
                        " vertices at non-manifold places (same positions; occlusion unchanged)");
  } else {
    r.reader = "skyband polygon soup (" + reason + ")";
  }

  TriangleSoup out;
  out.vertices = used->vertices;
  out.triangles.reserve(used->indices.size());
  const bool materials = !used->material_names.empty();
  if (materials) {
    out.material_names = used->material_names;
    out.triangle_material.reserve(used->indices.size());
  }
  const bool objects = !used->object_names.empty();
  if (objects) out.object_names = used->object_names;
  for (std::size_t p = 0; p < used->polygon_count(); ++p) {
    const std::span<const std::uint32_t> ring(used->indices.data() + used->polygon_start[p],
                                              used->polygon_start[p + 1] - used->polygon_start[p]);
    const PolygonTriangulation t = triangulate_polygon_with_method(out.vertices, ring);
    if (ring.size() > 3) ++r.polygons_triangulated;
    if (t.method == PolygonTriangulationMethod::kFanZeroArea || t.method == PolygonTriangulationMethod::kFanSelfIntersecting)
      ++r.polygons_fanned;
    if (!t.triangles.empty()) ++r.faces_read;
    for (const auto& tri : t.triangles) {
      out.triangles.push_back(tri);
      if (materials) out.triangle_material.push_back(used->polygon_material[p]);
      if (objects) out.triangle_object.push_back(used->polygon_object[p]);
    }
  }
  r.triangles = out.triangles.size();
  if (r.polygons_fanned)
    r.notes.push_back(std::to_string(r.polygons_fanned) +
                      " polygons with zero area or a self-crossing outline were fan-triangulated (kept, not dropped)");
  if (r.faces_read != r.faces_in_file)
    r.notes.push_back("only " + std::to_string(r.faces_read) + " of " + std::to_string(r.faces_in_file) +
                      " faces gave triangles");
  r.defects = analyse_defects(out);
  warn_about_far_vertices(out, r);
  if (used != &soup) {
    // The "as stored" counts describe the file, not the vertices OpenMesh duplicated at
    // non-manifold places.
    TriangleSoup file_vertices;
    file_vertices.vertices = soup.vertices;
    const MeshDefects stored = analyse_defects(file_vertices);
    r.defects.duplicate_vertex_positions = stored.duplicate_vertex_positions;
    r.defects.vertices_in_duplicate_positions = stored.vertices_in_duplicate_positions;
    std::vector<char> referenced(soup.vertices.size(), 0);
    for (const std::uint32_t i : soup.indices) referenced[i] = 1;
    r.defects.unreferenced_vertices = static_cast<std::size_t>(std::count(referenced.begin(), referenced.end(), 0));
  }
  if (report) *report = std::move(r);
  return out;
}

}  // namespace skyband
