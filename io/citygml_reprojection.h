#pragma once
// Geographic city models into metres: the CRS a city model names is classified through PROJ
// (projected, geographic, geocentric), and geographic coordinates are projected to the UTM zone
// of the model's centre. The only file that includes PROJ (proj.h); used by the CityGML reader.
//
// Why UTM: an EPSG-registered metric CRS every GIS knows, on the model's own datum where EPSG
// has one (JGD2011 / UTM zone 54N for PLATEAU's EPSG:6697), so no datum shift is applied. Its
// point scale factor k (0.9996 on the central meridian, ≤ 1.001 at the zone's edge) scales
// horizontal distances and not heights; a building's angles as seen from a point change by
// ~(k − 1) relative, below 10⁻³, which the report states.
//
// Heights are never transformed: z is copied verbatim from the file (orthometric heights stay
// orthometric, ellipsoidal ellipsoidal); the report says which kind the source CRS defines.
//
// Target CRS, by the source's geodetic datum (its EPSG code):
//   JGD2011 (6668)  → JGD2011 / UTM zones 51N–56N, EPSG:6688–6693;
//   ETRS89 (4258)   → ETRS89 / UTM zones 28N–38N, EPSG:25828–25838;
//   anything else   → WGS 84 / UTM, EPSG:326zz (north) / 327zz (south), through the
//                     transformation PROJ picks (a datum shift, possibly a ballpark one: stated).
// The zone is floor((λ + 180°)/6) + 1 of the longitude at the centre of the model's box (the
// Norway/Svalbard exceptions are not applied), north or south by the centre's latitude. Models
// read together share a zone: given the zone of those read before (`shared`), a model whose own
// zone is that one or a neighbour, in the same hemisphere, is projected to it (tiles on both
// sides of a zone boundary then join; at most 9° from the central meridian, k ≤ 1.012); else
// to its own zone, whose different CRS the caller reports.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "io/crs_codes.h"

#include "geometry/core/vec3.h"

namespace skyband {

enum class CrsKind { projected, geographic, geocentric, unknown };

struct CrsInfo {
  CrsKind kind = CrsKind::unknown;
  int epsg = 0;                // the code found in the CRS string (0: none)
  std::string name;            // PROJ's name of it ("JGD2011 + JGD2011 (vertical) height"), "" if unknown
  int vertical_epsg = 0;       // compound CRSs: the vertical part's EPSG code (6695), else 0
  std::string heights;         // what the source's z is, in words
  bool latitude_first = true;  // geographic: axis order of the file (EPSG: latitude, longitude)
};

// Classifies a CRS string (srsName). A string naming an EPSG code PROJ knows is classified from
// PROJ's database; "CRS84" is geographic (longitude first); a code PROJ does not know is
// geographic if geographic_epsg_codes() (io/cityjson_reader.h) lists it, else unknown.
CrsInfo classify_crs(const std::string& crs);

struct UtmZone {
  int number = 0;  // 1–60
  bool north = true;
  bool operator==(const UtmZone&) const = default;
};

struct Reprojection {
  UtmZone zone;
  std::string target_crs;          // "EPSG:6691", or "EPSG:6691+6695" when the source had a vertical CRS
  std::string target_name;         // "JGD2011 / UTM zone 54N"
  std::string operation;           // PROJ's name of the operation used
  double scale_factor_centre = 1;  // UTM point scale factor at the model's centre
  std::string description;         // one line for the report
};

// Projects `points` in place: on input (latitude°, longitude°, h) — or (longitude, latitude, h)
// when !source.latitude_first — on output (easting m, northing m, h) with h unchanged. Throws
// InputError (prefixed with `file`) on a latitude outside [−90°, 90°], a longitude outside
// [−180°, 360°] or a point PROJ cannot transform.
Reprojection reproject_geographic_to_utm(const std::string& file, const CrsInfo& source, std::span<Vec3> points,
                                         std::optional<UtmZone> shared = std::nullopt);

}  // namespace skyband
