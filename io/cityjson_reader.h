#pragma once
// CityJSON input: CityJSON 1.0, 1.1 and 2.0 files (`.json`, `.city.json`) and CityJSONSeq
// (`.city.jsonl`, `.jsonl`: a CityJSON header line, then one CityJSONFeature per line) into a
// TriangleSoup with per-triangle material names. Specifications: https://www.cityjson.org/specs/
// (1.0.3, 1.1.3, 2.0.1) and https://www.cityjson.org/cityjsonseq/.
//
// Reading:
//  - A single CityJSON file is read into memory once (its bytes plus simdjson's 64 bytes of
//    padding) and parsed with simdjson (https://simdjson.org). One forward pass of its on-demand
//    API checks the whole text as JSON (every number, string and bracket) and on the way reads
//    "vertices" (25 bytes per vertex: each coordinate's bits and kind) and splits "CityObjects"
//    into each object's text, a view into the file's bytes. The on-demand index of the text (4
//    bytes per structural character, about 1.3× the file) is freed after that pass. CityJSON's
//    members come in any order ("CityObjects" often before "vertices" and "transform"), which a
//    forward-only pass cannot resolve, so that pass only locates them: the small members (type,
//    version, metadata, transform, geometry-templates) are parsed afterwards from their own
//    text, and each CityObject is parsed on its own into simdjson's DOM when it is read, one at
//    a time, in the order of the ids (the objects are read in that order, whatever the file's).
//    simdjson's DOM for the whole file would hold a tape of 2–3× the file besides the text and
//    the index; this way the peak is about 2.5–3× the file plus the soup: 185 MB for a 68 MB
//    3D BAG-like tile whose soup is 18 MB, 5.2 MB for the 1.46 MB Delft tile (1.2 MB soup;
//    bench_city_model_load, docs/performance.md). A single very large CityObject (a terrain TIN
//    as one object) adds its own DOM, a few times its size, while it is read.
//    CityJSONSeq is read line by line, each line the same way: memory holds one feature at a
//    time (plus the soup).
//  - Not JSON (InputError "not JSON (what at line L, column C)", "at column C" on a CityJSONSeq
//    line): a syntax error, a number beyond the range of a double (1e999), invalid UTF-8, an
//    unescaped control character in a string, nesting deeper than 1024 levels. Such errors come
//    before any other. An integer beyond 64 bits is a number like any other (the nearest double),
//    as JSON defines it. Of members with equal names the last one counts.
//  - Vertices: with a `transform` (required from 1.1 on, optional in 1.0) every vertex
//    coordinate must be a JSON integer i and the coordinate is
//        x = i · scale + translate,
//    evaluated as the specification writes it, in double: i (|i| ≤ 2⁵³, larger is an error, so
//    i converts to double exactly) times the double nearest the file's scale, correctly rounded, plus the double
//    nearest the file's translate, correctly rounded (floating-point contraction is disabled for
//    this function, so no fused multiply-add merges the two). This is the value cjio / numpy /
//    3D BAG tools compute. It is not always the double nearest the exact decimal i·scale +
//    translate: 0.001 and most translates are not doubles, and the product is rounded before the
//    sum, so the error is ≤ ½ ulp(i·ŝ) + |i|·½ ulp(scale) + ½ ulp(translate) + ½ ulp(x)
//    < 2.5 ulp(max(|i·scale|, |translate|, |x|)) (the scale term is < 1 ulp(i·scale)):
//    ≈ 4·10⁻¹¹ m at RD coordinates of 10⁵ m, relative to the terms, not to x, when they cancel. Without a transform
//    (CityJSON 1.0) vertices are JSON numbers taken as parsed (simdjson parses decimals correctly rounded).
//  - Only vertices that a read surface uses enter the soup (per file, or per feature in
//    CityJSONSeq), in order of first use; coordinates are never shifted.
//  - Geometry types: MultiSurface, CompositeSurface, Solid (every shell, inner shells too),
//    MultiSolid, CompositeSolid, and GeometryInstance (a `geometry-templates` geometry, its
//    template vertices multiplied by the row-major 4×4 `transformationMatrix`, then translated
//    by the reference point, as the specification says). MultiPoint and MultiLineString have no
//    area and are skipped with a note.
//  - Surfaces with inner rings (holes) are triangulated by triangulate_polygon_with_holes
//    (geometry/mesh/polygon_with_holes_triangulation.h): triangles inside holes are not produced.
//  - Degenerate input common in real data is repaired, counted and noted, never silently:
//    a ring with fewer than 3 distinct vertex indices is dropped (an outer ring takes its
//    surface with it), consecutive repeated indices and a repeated closing vertex are removed,
//    rings that cross (holes that cannot be cut out without new vertices) are filled.
//
// LoD choice, per CityObject: its geometries carry a `lod` (a string "2.2" from 1.1 on, a
// number 2 or 1.2 in 1.0; compared numerically component by component, so "2.2" > "1.3" >
// "1.2" > "1" and "1" = "1.0"). By default each object is read at the highest LoD it has (all
// its geometries of that LoD), with one exception: a parent object (one with `children`) whose
// highest LoD is lower than the LoD at which one of its children is read is skipped — 3D BAG
// Buildings carry only a LoD 0 footprint while their BuildingParts carry the 3D solids, and
// the footprint would duplicate the solids' ground surfaces (`keep_lower_lod_parents` keeps
// them). With `lod` set, each object is read at exactly that LoD (numerically equal), and
// objects with geometry but none of that LoD are skipped and counted. Objects without geometry
// (parents whose children carry it) are counted as objects only.
//
// Material names (one per triangle), the rule:
//  1. the semantic surface type, `semantics.surfaces[values[...]].type`, when the surface has
//     one (RoofSurface, WallSurface, GroundSurface, ClosureSurface, OuterCeilingSurface,
//     Window, Door, TrafficArea, WaterSurface, "+Extension" types verbatim, ...);
//  2. else the CityObject's `type` verbatim: Building, BuildingPart, Bridge, TINRelief, Road,
//     Railway, TransportSquare, WaterBody, PlantCover, SolitaryVegetationObject, LandUse,
//     GenericCityObject, ...
//  So terrain objects keep their class: "TINRelief", "Road", "WaterBody", "PlantCover",
//  "LandUse" match the ground names of default_ground_materials() (case-insensitively);
//  "TransportSquare", "Railway" do not (yet) and a caller wanting them as ground adds them.
//
// Coordinate reference system: metadata.referenceSystem is kept verbatim in the report
// (1.x "urn:ogc:def:crs:EPSG::7415", 2.0 "https://www.opengis.net/def/crs/EPSG/0/7415", and
// "EPSG:7415"). A model without one is read with a note (coordinates taken as metres in an
// unknown projected CRS). A geographic or geocentric CRS is refused (degrees are not metres,
// and geocentric z is not up): see geographic_epsg_codes().
//
// Errors (InputError, one line: file[:line], the JSON path or CityObject id, the value): not
// JSON, `type` not "CityJSON"/"CityJSONFeature", unsupported version, missing or malformed
// members (vertices, CityObjects, transform, boundaries nested to the wrong depth), a vertex
// index out of range or not a non-negative integer, a non-integer or out-of-range vertex where
// a transform requires integers, a non-finite coordinate or transform, a geographic CRS, a
// missing geometry template, and a model that gives no triangle at all.
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "geometry/mesh/triangle_soup.h"

namespace skyband {

struct CityModelReadOptions {
  std::optional<std::string> lod;       // e.g. "2.2"; unset: per object the highest it has
  bool keep_lower_lod_parents = false;  // see "LoD choice" above
};

struct CityModelReport {
  std::string file;
  std::string format;                     // "CityJSON 1.0", "CityJSON 2.0", "CityJSONSeq 2.0", ...
  std::string crs;                        // metadata.referenceSystem verbatim, "" if none
  std::size_t features = 0;               // CityJSONSeq: CityJSONFeature lines; CityJSON: 0
  std::size_t objects = 0;                // CityObjects in the file (all features)
  std::size_t objects_with_geometry = 0;  // objects that gave at least one surface
  std::size_t skipped_objects = 0;        // objects with geometry of which nothing was read
  std::size_t surfaces = 0;               // surfaces (polygons) triangulated
  std::size_t surfaces_with_holes = 0;    // of those: with at least one inner ring kept
  std::size_t triangles = 0;
  std::size_t vertices = 0;                      // soup vertices (used by read surfaces)
  std::map<std::string, std::size_t> lods_used;  // LoD as written → objects read at it
  std::vector<std::string> notes;                // what was skipped or repaired, and why
  std::string summary() const;                   // a few human-readable lines
};

// Reads a CityJSON or CityJSONSeq file (chosen by extension: `.jsonl` is CityJSONSeq). Throws
// InputError on unreadable, malformed or empty input (see above).
TriangleSoup read_cityjson(const std::filesystem::path& file, const CityModelReadOptions& options = {},
                           CityModelReport* report = nullptr);

// True for `.json` / `.jsonl` names (`.city.json`, `.city.jsonl` included), case-insensitively.
bool is_cityjson_path(const std::filesystem::path& file);

// EPSG codes refused as not metric with z up. Geographic 2D/3D: 4326 WGS 84, 4979 WGS 84 3D,
// 4258 / 4937 ETRS89, 4289 Amersfoort, 4269 NAD83, 4617 NAD83(CSRS), 4283 GDA94, 7844 GDA2020,
// 4612 JGD2000, 6668 JGD2011, 6697 JGD2011 + JGD2011 height (PLATEAU), 4490 CGCS2000, 4167
// NZGD2000, 4171 RGF93, 4230 ED50, 4277 OSGB36; geocentric: 4978 WGS 84, 4936 ETRS89; compound
// on WGS 84: 9518 (+ EGM2008 height), 9705 (+ MSL height). "OGC:CRS84" / "CRS84" is refused too.
// Not exhaustive: any other code is taken as projected metres.
const std::vector<int>& geographic_epsg_codes();

}  // namespace skyband
