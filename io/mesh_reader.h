#pragma once
// Mesh input: OBJ, OFF, PLY (ascii, binary little/big endian) and STL (ascii, binary) into a
// TriangleSoup. A scene of several files is built by the caller with TriangleSoup::append.
//
// How a file is read (no face may be lost silently: a lost face is a hole that leaks sky light):
//  1. A validating pass of our own reads the whole file into a polygon soup: it counts the faces
//     the file declares, checks every coordinate is a finite number and every index is in range,
//     and throws InputError naming the file, the line (or element number in binary files) and
//     the offending value. Coordinates are parsed with std::from_chars (correctly rounded) and
//     kept verbatim: never shifted, scaled or rounded.
//     Every count the file declares is bounded by what the rest of the file can hold before
//     anything is reserved or looped over, so a lying header costs an error, not gigabytes.
//  2. OpenMesh 9 (IO::read_mesh into a PolyMesh with double points) is used where it can do the
//     job: only if it reproduces every face of the file, with bit-identical corner positions, in
//     file order. If it runs out of memory the file is rejected (InputError), never silently read
//     by step 3. It is not even tried where the validating pass knows it misreads the file
//     (PolygonSoup::not_for_openmesh; found by fuzzing): any OFF file (OpenMesh 9's OFF
//     reader takes layouts our pass accepts differently — counts on the header line, an extra
//     value after a face, a comment right after the header — and then reads "-1" as a face size of
//     ~4·10⁹, gigabytes, or uses an uninitialised face count) and a PLY file with an element
//     without properties (OpenMesh loops over its count, up to 4·10⁹ times). Measured limits of OpenMesh 9.0 that make us fall
//     back: its readers parse coordinates as 32-bit floats (678045.908 becomes 678045.9375), refuse OFF files with `#` comment
//     lines, drop faces that would make the mesh non-manifold or have repeated indices, and drop a face of a PLY with CR LF line
//     ends.
//  3. Otherwise the validating pass's polygon soup is used ("skyband polygon soup" + the reason).
//  Either way every polygon with more than 3 vertices is triangulated by triangulate_polygon
//  (geometry/mesh/polygon_triangulation.h: projected constrained Delaunay triangulation, correct for
//  non-convex and slightly non-planar polygons), and the report says which reader was used and
//  why, how many faces were read against the faces in the file, and the mesh's defects.
//
// Formats:
//  - OBJ: `v` (extra values such as w or colours ignored), `f` with `i`, `i/t`, `i//n`, `i/t/n`
//    and negative (relative) indices, `usemtl` (per-triangle material names), `o` and `g`
//    (per-triangle object names: the latest of either, a group line's names joined by spaces); `s`,
//    `vt`, `vn`, `vp`, `mtllib`, `l`, `p` are ignored; other keywords are ignored and noted.
//  - OFF: `OFF`, `NOFF`, `COFF`, `CNOFF`, `STOFF`... headers (counts may follow on the header
//    line), `#` comments anywhere, per-vertex normals/colours and per-face colours ignored.
//  - PLY: ascii / binary_little_endian / binary_big_endian; vertex x, y, z of any scalar type;
//    face list `vertex_indices` (or `vertex_index`) with any integer count and index types;
//    other properties and elements are skipped.
//  - STL: ascii and binary (binary when the size is 84 + 50·count, else ascii if it starts with
//    `solid`). STL has no connectivity: exactly equal positions are welded (the report says so).
//  - CityJSON (`.json`, `.city.json`) and CityJSONSeq (`.jsonl`): io/cityjson_reader.h (each
//    object at its highest LoD; material names = semantic surface types, else object types;
//    object names = CityObject ids, per triangle in TriangleSoup::triangle_object).
//  - CityGML 1.0 and 2.0 (`.gml`, `.xml`, `.citygml`): io/citygml_reader.h, through libcitygml
//    (the same LoD choice, materials and objects as CityJSON; geographic CRSs projected to UTM by
//    PROJ, MeshReadReport::crs the output's CRS; CityGML 3.0 refused).
//  Faces with fewer than 3 vertices are input errors. A file with no faces is an "empty mesh"
//  error. Unknown extensions are errors that list the supported ones.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/vec3.h"
#include "geometry/mesh/mesh_defects.h"
#include "geometry/mesh/triangle_soup.h"
#include "io/citygml_reprojection.h"

namespace skyband {

struct MeshReadReport {
  std::string file, format;          // format: "OBJ", "OFF", "PLY (ascii)", "STL (binary)", ...
  std::string reader;                // "OpenMesh 9" or "skyband polygon soup (<reason>)"
  std::size_t vertices_in_file = 0;  // after welding for STL
  std::size_t faces_in_file = 0;     // declared (OFF/PLY/binary STL) or counted (OBJ, ascii STL)
  std::size_t faces_read = 0;        // faces that became triangles (must equal faces_in_file)
  std::size_t triangles = 0;
  std::size_t polygons_triangulated = 0;  // faces with > 3 vertices
  std::size_t polygons_fanned = 0;        // of those: zero-area or self-crossing, fan-triangulated
  std::string crs;                        // city models: the CRS of the output ("" = none/unknown)
  std::optional<UtmZone> utm_zone;        // geographic city models: the UTM zone they were projected to
  MeshDefects defects;                    // after welding exactly equal positions
  std::vector<std::string> notes;         // e.g. "OpenMesh dropped 743 faces; read as polygon soup"
  std::vector<std::string> warnings;      // what is read but likely wrong (see kFarCoordinate_m), one line each
  std::string summary() const;            // a few human-readable lines (warnings included)
};

// Vertices farther than this from the origin along any axis are read, with a warning (a
// corrupt or sentinel value, or the wrong unit): no projected CRS has coordinates beyond
// ~4·10⁷ m (the Earth's circumference), and there the exact predicates' products of coordinate
// differences lose the range of a double long before 10³⁰⁸. Metres.
constexpr double kFarCoordinate_m = 1e8;

struct MeshReadOptions {
  // City models (CityJSON, CityJSONSeq, CityGML): read each object at exactly this LoD ("1.2", "2.2";
  // objects without it are skipped and counted); unset: each object at the highest it has
  // (io/cityjson_reader.h). Other formats have no LoD: InputError when set for them.
  std::optional<std::string> lod;
  // Geographic city models (CityGML), projected to UTM: the zone of the models read before, so
  // that models read together share a CRS where they can (io/citygml_reprojection.h).
  std::optional<UtmZone> utm_zone;
};

// Reads one mesh file. Throws InputError on unreadable, malformed or empty input.
TriangleSoup read_mesh(const std::filesystem::path& file, MeshReadReport* report = nullptr, const MeshReadOptions& options = {});

// The supported extensions, lower case with dot: ".obj", ".off", ".ply", ".stl", ".json", ".jsonl",
// ".gml", ".xml", ".citygml".
const std::vector<std::string>& supported_mesh_extensions();

namespace mesh_io {

// The validating pass's result: the file's polygons verbatim.
struct PolygonSoup {
  std::string format;                        // as in MeshReadReport::format
  std::vector<Vec3> vertices;                // metres, verbatim
  std::vector<std::uint32_t> polygon_start;  // polygon p = indices[start[p], start[p + 1])
  std::vector<std::uint32_t> indices;
  std::vector<std::uint32_t> polygon_material;  // OBJ usemtl: per polygon, into material_names
  std::vector<std::string> material_names;      // empty when the file has no usemtl
  std::vector<std::uint32_t> polygon_object;    // OBJ o / g: per polygon, into object_names
  std::vector<std::string> object_names;        // empty when the file has no o or g
  std::size_t faces_declared = 0;
  bool welded = false;           // STL: identical positions merged while reading
  bool float32_exact = true;     // every coordinate is exactly a 32-bit float
  std::string not_for_openmesh;  // why OpenMesh must not read the file ("" = it may try)
  std::vector<std::string> notes;

  std::size_t polygon_count() const { return polygon_start.empty() ? 0 : polygon_start.size() - 1; }
};

// Per-format validating readers (file name used in messages; bytes = the whole file).
PolygonSoup parse_obj(const std::string& name, const std::string& bytes);
PolygonSoup parse_off(const std::string& name, const std::string& bytes);
PolygonSoup parse_ply(const std::string& name, const std::string& bytes);
PolygonSoup parse_stl(const std::string& name, const std::string& bytes);

// Shared helpers of the text readers.
// Parses a whole token as a finite double (a leading '+' allowed); throws InputError naming
// name:line, `what` and the token otherwise.
double parse_coordinate(std::string_view token, const std::string& name, std::size_t line, const char* what);
// Parses a whole token as a (possibly signed) integer; throws InputError otherwise.
long long parse_integer(std::string_view token, const std::string& name, std::size_t line, const char* what);
// Splits text into lines (LF, CR LF and lone CR all end a line), calling f(line_number, text).
template <class F>
void for_each_line(std::string_view text, F&& f) {
  std::size_t line = 1, start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\n' || text[i] == '\r') {
      f(line++, text.substr(start, i - start));
      if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      start = i + 1;
    }
  }
  if (start < text.size()) f(line, text.substr(start));
}
// Text formats hold no NUL byte: InputError naming name:line and the column of the first one
// (`what` says which part of the file is text, e.g. "the OBJ text"). Checked before parsing, so
// no message can carry a NUL, which would cut it short (utf8_text.h).
// `first_line` is the file line on which `text` starts.
void reject_nul_bytes(const std::string& name, std::string_view text, const char* what, std::size_t first_line = 1);
// Whitespace tokenizer (space, tab, vertical tab, form feed; also CR/LF if present).
void split_tokens(std::string_view text, std::vector<std::string_view>& out);
void add_vertex(PolygonSoup& soup, const Vec3& p);  // tracks float32_exact

}  // namespace mesh_io
}  // namespace skyband
