#pragma once
// CityGML input: CityGML 1.0 and 2.0 files (`.gml`, `.xml`, `.citygml`) into a TriangleSoup
// with per-triangle material names and city objects, read through libcitygml 2.4 (Xerces-C SAX).
// Specification: OGC 12-019 (CityGML 2.0), OGC 08-007r1 (1.0).
//
// Before libcitygml sees the file, a scan of our own checks its bytes:
//  - the version, from the namespaces: `http://www.opengis.net/citygml/2.0` or `/1.0` on the
//    root element. CityGML 3.0 (`http://www.opengis.net/citygml/3.0` anywhere in the file) is
//    refused, never half-read: libcitygml 2.4 does not know its elements (3.0 puts surfaces
//    under `boundary`, LoDs in `lod2MultiSurface` of a different namespace) and would return a
//    model with most geometry silently missing. Convert with citygml-tools (`citygml-tools
//    to-cityjson`, or `upgrade`/`downgrade` to 2.0) first;
//  - no text node (a gml:posList) longer than 1 000 000 bytes: libcitygml keeps only the last
//    chunk of a text node that Xerces delivers in pieces (measured: texts over 1 MiB lose their
//    start, the ring is cut mid-number, silently), so such a file is refused with its line;
//  - well-formedness, by a Xerces-C SAX pass of its own: libcitygml on malformed XML logs
//    Xerces' message without its line and leaks what it had built, so it only sees
//    well-formed XML, and the error names file:line:column;
//  - Application Domain Extensions: every element of a namespace that is not CityGML's (core
//    and modules, `http://www.opengis.net/citygml/...`), GML's or xAL's is blanked out with its
//    content (spaces, line ends kept, so every line keeps its number), and so is the property
//    left empty by that (the core:cityObjectMember or bldg:boundedBy that held an ADE feature):
//    libcitygml 2.4 reads elements by local name whatever their namespace (an ADE's own
//    lod2Solid would be read as CityGML), skips the ones it does not know, and then fails on
//    the property left without an object ("unbound CityGMLElementParser"). So an ADE subclass
//    of a CityGML class (a roof surface of an energy ADE) is not read either. The report names
//    each ADE namespace and its elements; a file of nothing else ends in the "no triangles"
//    error, naming them;
//  - every gml:posList, gml:pos and core:transformationMatrix (what libcitygml reads as
//    numbers) is plain text up to its end tag — libcitygml keeps only the piece after a comment,
//    CDATA section, character reference or child element inside it — of finite doubles
//    (io/mesh_reader.h's parse_coordinate: no NaN, infinity, overflow beyond ±1.8·10³⁰⁸ or
//    garbage; libcitygml reads a gml:pos with no check, 1e400 as 1.8·10³⁰⁸, an empty one as
//    (0, 0, 0)), and whole: x y z triples in a posList (libcitygml drops 1 or 2 trailing
//    numbers), exactly x y z in a pos, 16 numbers in a matrix, none empty. GML 2's
//    gml:coordinates and gml:coord, which libcitygml does not read (their ring is dropped), are
//    refused. Each error names the line and the value;
//  - the srsName attributes (all of them must name the same EPSG codes).
//
// Reading (libcitygml with tesselation and "optimize" off, so rings arrive as written):
//  - City objects are libcitygml's CityObjects except thematic surfaces: the boundary surfaces
//    (WallSurface, RoofSurface, GroundSurface, ClosureSurface, FloorSurface, OuterCeilingSurface,
//    OuterFloorSurface, InteriorWallSurface, CeilingSurface), openings (Window, Door), the
//    traffic areas of transportation objects and the boundary surfaces of water bodies are the
//    semantic surfaces of the object above them, as in CityJSON. An object's triangles carry
//    its gml:id (TriangleSoup::triangle_object).
//  - LoD choice, per object, as in io/cityjson_reader.h: an object's LoDs are those of its own
//    geometries and of its thematic surfaces' geometries (CityGML's lod0..lod4 element names);
//    by default it is read at the highest LoD it has (all its geometries of that LoD); a parent
//    (Building) whose highest LoD is below the LoD at which one of its child objects
//    (BuildingPart) is read is skipped; with `lod` set ("2", "2.0"), each object is read at
//    exactly that LoD, and objects with geometry but none of that LoD are skipped and counted.
//  - A polygon referenced twice (a lod2Solid's xlink:href to the polygons of its boundary
//    surfaces, as PLATEAU writes it) is read once, with the thematic surface's type.
//  - Polygons with holes: rings as written (closing vertex and consecutive repeats removed,
//    counted), triangulated by triangulate_polygon_with_holes (the CityJSON reader's method);
//    vertices with bit-identical coordinates are shared. Coordinates are never shifted.
//  - Implicit geometries (templates of vegetation and city furniture, shared by xlink): each
//    instance placed as M·x + reference point (M the row-major 4×4 transformationMatrix, as the
//    CityJSON reader places geometry instances), at its LoD like any other geometry; not in a
//    geographic CRS (a template in metres on a reference point in degrees), with a note.
//  - Not read, and counted in the notes: curves and points, the elements libcitygml skips
//    (bldg:lod0FootPrint and lod0RoofEdge), by element name, and ADE elements (above).
//
// Material names (one per triangle): the thematic surface's type (RoofSurface, WallSurface,
// GroundSurface, ..., Window, Door; traffic areas "TrafficArea" — libcitygml does not tell
// auxiliary ones apart; water boundary surfaces "WaterBody"), else the object's type (Building,
// BuildingPart, TINRelief, LandUse, Road, WaterBody, PlantCover, GenericCityObject, ...; the
// relief components and CityObjectGroup, which libcitygml 2.4 names "Unknown", by their class:
// TINRelief, RasterRelief, MassPointRelief, BreaklineRelief). So the terrain classes match
// default_ground_materials() (lighting/climate/climate_irradiation.h): a PLATEAU dem file's
// dem:ReliefFeature / dem:TINRelief is ground.
//
// Coordinate reference system (the srsName, kept in the report): projected CRSs are read as
// metres verbatim. Geographic CRSs (PLATEAU's EPSG:6697, 4326, 6668, ...: latitude, longitude,
// height) are projected to the UTM zone of the model's centre by PROJ
// (io/citygml_reprojection.h: JGD2011 / UTM zone 54N, EPSG:6691, for Tokyo), or to the zone
// given in the options (that of models read before, where it is this one's or a neighbour);
// heights are kept as in the file, and the report says in which CRS the output is and what the
// heights are.
// Geocentric CRSs are refused (z is not up). A file without srsName is read as metres with a note.
//
// Errors (InputError, one line naming the file, and the line where the XML gives one): missing
// or unreadable file, not XML or malformed XML (Xerces' message and line:column), not CityGML
// 1.0/2.0, CityGML 3.0, an over-long text node, a coordinate that is not a finite double, a
// coordinate list or position that is empty, interrupted or not whole, GML 2 coordinates, a
// srsDimension other than 3, mixed or geocentric CRSs, a requested LoD that is not a LoD, and a
// model that gives no triangle.
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "geometry/mesh/triangle_soup.h"
#include "io/citygml_reprojection.h"

namespace skyband {

struct CityGmlReadOptions {
  std::optional<std::string> lod;  // "2" (or "2.0"); unset: per object the highest it has
  // Geographic CRSs: the UTM zone of models read before, shared when this model's own zone is
  // that one or a neighbour (io/citygml_reprojection.h); unset: the zone of the model's centre.
  std::optional<UtmZone> utm_zone;
};

struct CityGmlReport {
  std::string file;
  std::string format;                     // "CityGML 2.0", "CityGML 1.0"
  std::string crs_in_file;                // the srsName verbatim, "" if none
  std::string crs;                        // the CRS of the output: crs_in_file, or the UTM CRS reprojected to
  std::string reprojection;               // "" when not reprojected, else what was done (one line)
  std::optional<UtmZone> utm_zone;        // when reprojected: the zone used
  std::size_t objects = 0;                // city objects (thematic surfaces not counted)
  std::size_t objects_with_geometry = 0;  // objects that gave at least one surface
  std::size_t skipped_objects = 0;        // objects with geometry of which nothing was read
  std::size_t thematic_surfaces = 0;      // thematic surface features read (WallSurface, ...)
  std::size_t surfaces = 0;               // polygons triangulated
  std::size_t surfaces_with_holes = 0;    // of those: with at least one inner ring kept
  std::size_t triangles = 0;
  std::size_t vertices = 0;                      // soup vertices (bit-identical positions shared)
  std::map<std::string, std::size_t> lods_used;  // LoD → objects read at it
  std::vector<std::string> notes;                // what was skipped or repaired, and why
  std::string summary() const;                   // a few human-readable lines
};

// Reads a CityGML 1.0/2.0 file. Throws InputError on unreadable, malformed, unsupported or empty
// input (see above).
TriangleSoup read_citygml(const std::filesystem::path& file, const CityGmlReadOptions& options = {},
                          CityGmlReport* report = nullptr);

// True for `.gml`, `.xml` and `.citygml` names, case-insensitively.
bool is_citygml_path(const std::filesystem::path& file);

}  // namespace skyband
