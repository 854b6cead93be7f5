#include "io/citygml_reprojection.h"

#include <proj.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "geometry/core/input_error.h"
#include "io/cityjson_reader.h"
#include "io/third_party_fp.h"

namespace skyband {
namespace {

struct ContextDeleter {
  void operator()(PJ_CONTEXT* c) const { proj_context_destroy(c); }
};
struct PjDeleter {
  void operator()(PJ* p) const { proj_destroy(p); }
};
using Context = std::unique_ptr<PJ_CONTEXT, ContextDeleter>;
using Pj = std::unique_ptr<PJ, PjDeleter>;

// A PROJ context that logs nothing to stderr (errors are read back from it).
Context quiet_context() {
  Context c(proj_context_create());
  proj_log_level(c.get(), PJ_LOG_NONE);
  return c;
}

int id_code(const PJ* p) {
  const char* code = p ? proj_get_id_code(p, 0) : nullptr;
  return code ? std::atoi(code) : 0;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool is_geographic(PJ_TYPE t) {
  return t == PJ_TYPE_GEOGRAPHIC_2D_CRS || t == PJ_TYPE_GEOGRAPHIC_3D_CRS || t == PJ_TYPE_GEOGRAPHIC_CRS;
}

// The horizontal part of a CRS (itself unless compound; a bound CRS's base).
Pj horizontal_part(PJ_CONTEXT* c, const PJ* crs) {
  if (proj_get_type(crs) == PJ_TYPE_COMPOUND_CRS) return Pj(proj_crs_get_sub_crs(c, crs, 0));
  if (proj_get_type(crs) == PJ_TYPE_BOUND_CRS) return Pj(proj_get_source_crs(c, crs));
  return Pj(proj_clone(c, crs));
}

// Axis order of a geographic CRS: true when its first axis points north (latitude first).
bool first_axis_north(PJ_CONTEXT* c, const PJ* geographic) {
  Pj cs(proj_crs_get_coordinate_system(c, geographic));
  const char* direction = nullptr;
  if (!cs || !proj_cs_get_axis_info(c, cs.get(), 0, nullptr, nullptr, &direction, nullptr, nullptr, nullptr, nullptr))
    return true;
  return direction && lower(direction) == "north";
}

void describe_heights(PJ_CONTEXT* c, const PJ* crs, CrsInfo& info) {
  if (proj_get_type(crs) == PJ_TYPE_COMPOUND_CRS) {
    Pj vertical(proj_crs_get_sub_crs(c, crs, 1));
    info.vertical_epsg = id_code(vertical.get());
    info.heights = std::string("heights of the vertical CRS ") + (vertical ? proj_get_name(vertical.get()) : "?") +
                   (info.vertical_epsg ? " (EPSG:" + std::to_string(info.vertical_epsg) + ", orthometric)" : std::string());
  } else if (proj_get_type(crs) == PJ_TYPE_GEOGRAPHIC_3D_CRS) {
    info.heights = "ellipsoidal heights of " + info.name;
  } else {
    info.heights = "heights of a vertical reference the CRS does not name";
  }
}

// UTM target of a geodetic datum: EPSG code and name.
int utm_epsg(int geodetic_epsg, int zone, bool north) {
  if (north && geodetic_epsg == 6668 && zone >= 51 && zone <= 56) return 6688 + (zone - 51);  // JGD2011
  if (north && geodetic_epsg == 4258 && zone >= 28 && zone <= 38) return 25800 + zone;        // ETRS89
  return (north ? 32600 : 32700) + zone;                                                      // WGS 84
}

}  // namespace

CrsInfo classify_crs(const std::string& crs) {
  const ThirdPartyFpGuard fp;  // PROJ's own floating point
  CrsInfo info;
  const std::string l = lower(crs);
  if (l.find("crs84") != std::string::npos || l.find("crs:84") != std::string::npos) {
    info.kind = CrsKind::geographic;
    info.epsg = 4326;  // WGS 84 with longitude first
    info.name = "OGC CRS84 (WGS 84, longitude, latitude)";
    info.latitude_first = false;
    info.heights = "heights of a vertical reference the CRS does not name";
    return info;
  }
  const std::vector<int> codes = crs_epsg_codes(crs);
  if (codes.empty()) return info;
  info.epsg = codes.front();
  Context c = quiet_context();
  std::string definition = "EPSG:" + std::to_string(codes[0]);
  for (std::size_t i = 1; i < codes.size(); ++i) {  // a compound URN: "EPSG:6668+6695"
    definition += '+';
    definition += std::to_string(codes[i]);
  }
  Pj p(proj_create(c.get(), definition.c_str()));
  if (!p) {
    const auto& geographic = geographic_epsg_codes();
    if (std::find(geographic.begin(), geographic.end(), info.epsg) != geographic.end()) info.kind = CrsKind::geographic;
    return info;
  }
  info.name = proj_get_name(p.get()) ? proj_get_name(p.get()) : "";
  const PJ_TYPE type = proj_get_type(p.get());
  if (type == PJ_TYPE_GEOCENTRIC_CRS) {
    info.kind = CrsKind::geocentric;
    return info;
  }
  Pj horizontal = horizontal_part(c.get(), p.get());
  const PJ_TYPE htype = horizontal ? proj_get_type(horizontal.get()) : PJ_TYPE_UNKNOWN;
  if (is_geographic(htype)) {
    info.kind = CrsKind::geographic;
    info.latitude_first = first_axis_north(c.get(), horizontal.get());
    describe_heights(c.get(), p.get(), info);
  } else if (htype == PJ_TYPE_PROJECTED_CRS) {
    info.kind = CrsKind::projected;
  } else if (htype == PJ_TYPE_GEOCENTRIC_CRS) {
    info.kind = CrsKind::geocentric;
  }
  return info;
}

Reprojection reproject_geographic_to_utm(const std::string& file, const CrsInfo& source, std::span<Vec3> points,
                                         std::optional<UtmZone> shared) {
  if (points.empty()) return {};  // nothing to project (the reader reports the empty model)
  // Latitude and longitude of every point, checked, and the box's centre.
  double lat_min = std::numeric_limits<double>::infinity(), lat_max = -lat_min, lon_min = lat_min, lon_max = -lat_min;
  for (const Vec3& p : points) {
    const double lat = source.latitude_first ? p.x() : p.y(), lon = source.latitude_first ? p.y() : p.x();
    if (!(lat >= -90 && lat <= 90) || !(lon >= -180 && lon <= 360)) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "(%.17g, %.17g)", p.x(), p.y());
      throw InputError(file + ": coordinate " + buf + " is not a (" +
                       (source.latitude_first ? "latitude, longitude" : "longitude, latitude") +
                       ") pair in degrees, as the CRS " + source.name + " says; is the axis order or the srsName wrong?");
    }
    lat_min = std::min(lat_min, lat), lat_max = std::max(lat_max, lat);
    lon_min = std::min(lon_min, lon), lon_max = std::max(lon_max, lon);
  }
  const double lat_centre = 0.5 * (lat_min + lat_max);
  double lon_centre = 0.5 * (lon_min + lon_max);
  if (lon_centre > 180) lon_centre -= 360;
  const int own_zone = std::clamp(static_cast<int>(std::floor((lon_centre + 180) / 6)) + 1, 1, 60);
  const bool north = lat_centre >= 0;
  const int apart = shared ? std::abs(shared->number - own_zone) : 0;
  const bool use_shared = shared && shared->north == north && (apart <= 1 || apart == 59);  // 59: zones 60 and 1
  const int zone = use_shared ? shared->number : own_zone;

  const ThirdPartyFpGuard fp;  // PROJ's own floating point, from here on
  Context c = quiet_context();
  Pj src(proj_create(c.get(), ("EPSG:" + std::to_string(source.epsg)).c_str()));
  Pj horizontal = src ? horizontal_part(c.get(), src.get()) : Pj();
  Pj geodetic = horizontal ? Pj(proj_crs_get_geodetic_crs(c.get(), horizontal.get())) : Pj();
  const int datum_epsg = id_code(geodetic.get());
  const int target_epsg = utm_epsg(datum_epsg, zone, north);
  Pj target(proj_create(c.get(), ("EPSG:" + std::to_string(target_epsg)).c_str()));
  if (!horizontal || !target)
    throw InputError(file + ": PROJ cannot set up a projection from " + source.name + " (EPSG:" + std::to_string(source.epsg) +
                     ") to EPSG:" + std::to_string(target_epsg) + " (is proj-data installed?)");
  Pj raw(proj_create_crs_to_crs_from_pj(c.get(), horizontal.get(), target.get(), nullptr, nullptr));
  // Normalised: input (longitude, latitude), output (easting, northing) whatever the CRSs' axis orders.
  Pj op = raw ? Pj(proj_normalize_for_visualization(c.get(), raw.get())) : Pj();
  if (!op)
    throw InputError(file + ": PROJ finds no transformation from EPSG:" + std::to_string(source.epsg) +
                     " to EPSG:" + std::to_string(target_epsg));

  for (Vec3& p : points) {
    const double lat = source.latitude_first ? p.x() : p.y(), lon = source.latitude_first ? p.y() : p.x();
    const PJ_COORD out = proj_trans(op.get(), PJ_FWD, proj_coord(lon, lat, 0, 0));
    if (!std::isfinite(out.xy.x) || !std::isfinite(out.xy.y))
      throw InputError(file + ": PROJ cannot project latitude " + std::to_string(lat) + ", longitude " + std::to_string(lon) +
                       " to EPSG:" + std::to_string(target_epsg));
    p = Vec3(out.xy.x, out.xy.y, p.z());  // z verbatim
  }

  Reprojection r;
  r.zone = {zone, north};
  r.target_crs = "EPSG:" + std::to_string(target_epsg) + (source.vertical_epsg ? "+" + std::to_string(source.vertical_epsg) : "");
  r.target_name = proj_get_name(target.get()) ? proj_get_name(target.get()) : "";
  r.operation = proj_get_name(op.get()) ? proj_get_name(op.get()) : "";
  // Point scale factor of transverse Mercator at easting E: k ≈ k0·(1 + (E − E0)²/(2R²)),
  // R = 6371 km; the neglected terms are < 10⁻⁶ within a zone.
  const PJ_COORD centre = proj_trans(op.get(), PJ_FWD, proj_coord(lon_centre, lat_centre, 0, 0));
  const double de_m = centre.xy.x - 500000.0;
  r.scale_factor_centre = 0.9996 * (1 + de_m * de_m / (2 * 6371000.0 * 6371000.0));
  char k[32];
  std::snprintf(k, sizeof k, "%.6f", r.scale_factor_centre);
  r.description = "reprojected by PROJ " + std::string(proj_info().release) + " from " + source.name +
                  " (EPSG:" + std::to_string(source.epsg) +
                  (source.latitude_first ? ", latitude, longitude" : ", longitude, latitude") + ") to " + r.target_crs + " (" +
                  r.target_name + (use_shared && zone != own_zone ? ", the zone of the models read before it" : "") +
                  ", x = easting, y = northing; operation: " + r.operation + "); z kept as in the file: " + source.heights +
                  "; UTM scale factor at the model's centre " + k + " (horizontal distances only)";
  return r;
}

}  // namespace skyband
