#include "io/geo_raster.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>

#include "geometry/core/input_error.h"
#include "io/atomic_file.h"
#include "io/crs_codes.h"
#include "io/third_party_fp.h"

namespace skyband {

namespace {

void register_gdal() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

// GDAL's messages are collected instead of printed; the last one explains a failure.
class QuietGdal {
 public:
  QuietGdal() {
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietGdal() { CPLPopErrorHandler(); }
  QuietGdal(const QuietGdal&) = delete;
  QuietGdal& operator=(const QuietGdal&) = delete;
  static std::string last() {
    const char* m = CPLGetLastErrorMsg();
    return m && *m ? std::string(m) : std::string("GDAL gave no reason");
  }
};

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
using Dataset = std::unique_ptr<GDALDataset, DatasetCloser>;

// "EPSG:n" when the CRS carries an authority code or PROJ's database identifies it (GeoTIFF
// keys of a compound CRS come back without one), else its name.
std::string crs_label(const OGRSpatialReference& srs) {
  const char* auth = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (auth && code) return std::string(auth) + ":" + code;
  int count = 0;
  int* confidence = nullptr;
  OGRSpatialReferenceH* matches = srs.FindMatches(nullptr, &count, &confidence);
  std::string label;
  if (matches && count > 0 && confidence[0] >= 90) {
    const auto* best = OGRSpatialReference::FromHandle(matches[0]);
    const char* a = best->GetAuthorityName(nullptr);
    const char* c = best->GetAuthorityCode(nullptr);
    if (a && c) label = std::string(a) + ":" + c;
  }
  if (matches) OSRFreeSRSArray(matches);
  CPLFree(confidence);
  if (!label.empty()) return label;
  if (srs.IsCompound()) {  // "EPSG:28992+5709": horizontal + vertical, as GDAL and PROJ accept it
    const char* h = srs.GetAuthorityCode("PROJCS");
    const char* v = srs.GetAuthorityCode("VERT_CS");
    if (h && v) return std::string("EPSG:") + h + "+" + v;
  }
  const char* name = srs.GetName();
  return name ? std::string(name) : std::string();
}

std::string wkt_of(const OGRSpatialReference& srs) {
  char* wkt = nullptr;
  const char* options[] = {"FORMAT=WKT2_2019", nullptr};
  srs.exportToWkt(&wkt, options);
  std::string out = wkt ? wkt : "";
  CPLFree(wkt);
  return out;
}

}  // namespace

constexpr double kMaxPlausibleHeight_m = 1e5;

// GDAL's ASCII grid driver reads an unparsable value ("nan", "1.0abc") and a missing one (a
// truncated file) as 0: the text is checked here first. Header lines start with a keyword.
static void check_ascii_grid(const std::string& name, std::size_t columns, std::size_t rows) {
  std::ifstream in(name, std::ios::binary);
  std::string line;
  std::size_t line_no = 0, count = 0;
  bool header = true;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream tokens(line);
    std::string t;
    bool first = true;
    while (tokens >> t) {
      if (header && first && (std::isalpha(static_cast<unsigned char>(t[0])) != 0)) break;  // a header line
      header = false, first = false;
      char* end = nullptr;
      const double v = std::strtod(t.c_str(), &end);
      if (end != t.c_str() + t.size() || !std::isfinite(v))
        throw InputError(name + ":" + std::to_string(line_no) + ": value '" + t.substr(0, 40) + "' is not a finite number");
      ++count;
    }
  }
  if (count != columns * rows)
    throw InputError(name + ": " + std::to_string(count) + " values for ncols × nrows = " + std::to_string(columns) + " × " +
                     std::to_string(rows) + " = " + std::to_string(columns * rows) + " pixels (a truncated or malformed grid)");
}

static std::string format_height(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

GeoRaster read_geo_raster(const std::filesystem::path& file, std::size_t max_pixels) {
  const ThirdPartyFpGuard fp;  // GDAL's and PROJ's own floating point
  register_gdal();
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw InputError(name + ": no such raster file");
  QuietGdal quiet;
  Dataset ds(GDALDataset::Open(name.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) throw InputError(name + ": not a raster GDAL can read (" + QuietGdal::last() + ")");
  if (ds->GetRasterCount() < 1) throw InputError(name + ": the raster has no band");
  GeoRaster r;
  r.columns = std::size_t(ds->GetRasterXSize());
  r.rows = std::size_t(ds->GetRasterYSize());
  if (r.columns == 0 || r.rows == 0) throw InputError(name + ": the raster has no pixels");
  if (r.columns > max_pixels / r.rows)
    throw InputError(name + ": " + std::to_string(r.columns) + " × " + std::to_string(r.rows) + " pixels, over the limit of " +
                     std::to_string(max_pixels) + " (crop or resample it)");
  if (GDALDriver* driver = ds->GetDriver(); driver && std::string(driver->GetDescription()) == "AAIGrid")
    check_ascii_grid(name, r.columns, r.rows);
  double gt[6];
  if (ds->GetGeoTransform(gt) != CE_None)
    throw InputError(name + ": the raster has no georeferencing (geotransform): pixel size and position unknown");
  for (int k = 0; k < 6; ++k) r.geotransform[std::size_t(k)] = gt[k];
  if (gt[2] != 0 || gt[4] != 0)
    throw InputError(name + ": rotated or sheared raster (geotransform terms " + std::to_string(gt[2]) + ", " +
                     std::to_string(gt[4]) + "): warp it north-up first (gdalwarp)");
  for (double v : gt)
    if (!std::isfinite(v)) throw InputError(name + ": geotransform not finite");
  if (gt[1] == 0 || gt[5] == 0) throw InputError(name + ": zero pixel size in the geotransform");
  if (const OGRSpatialReference* srs = ds->GetSpatialRef()) {
    if (srs->IsGeographic())
      throw InputError(name + ": geographic CRS " + crs_label(*srs) +
                       " (degrees, not metres): reproject the raster first (gdalwarp -t_srs EPSG:...)");
    if (srs->IsGeocentric())
      throw InputError(name + ": geocentric CRS " + crs_label(*srs) +
                       " (earth-centred x, y, z): reproject the raster to a projected CRS first (gdalwarp -t_srs EPSG:...)");
    r.crs_wkt = wkt_of(*srs);
    r.crs_name = crs_label(*srs);
  }
  GDALRasterBand* band = ds->GetRasterBand(1);
  if (GDALDataTypeIsComplex(band->GetRasterDataType()))
    throw InputError(name + ": band 1 holds complex numbers (" + GDALGetDataTypeName(band->GetRasterDataType()) +
                     "), not heights");
  // Stored values are heights after GDAL's scale and offset (height = value · scale + offset).
  int has_scale = 0, has_offset = 0;
  const double scale = band->GetScale(&has_scale), offset = band->GetOffset(&has_offset);
  if ((has_scale && !(std::isfinite(scale) && scale != 0)) || (has_offset && !std::isfinite(offset)))
    throw InputError(name + ": band 1 has scale " + std::to_string(scale) + " and offset " + std::to_string(offset) +
                     ": heights cannot be recovered");
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  if (has_nodata) r.nodata = nodata;
  r.values.resize(r.columns * r.rows);
  if (band->RasterIO(GF_Read, 0, 0, int(r.columns), int(r.rows), r.values.data(), int(r.columns), int(r.rows), GDT_Float64, 0,
                     0) != CE_None)
    throw InputError(name + ": reading band 1 failed (" + QuietGdal::last() + ")");
  for (std::size_t i = 0; i < r.values.size(); ++i) {
    double& v = r.values[i];
    if (has_nodata && (v == nodata || (std::isnan(v) && std::isnan(nodata)))) {
      v = std::nan("");
      ++r.nodata_pixels;
    } else if (!std::isfinite(v)) {
      throw InputError(name + ": pixel (column " + std::to_string(i % r.columns) + ", row " + std::to_string(i / r.columns) +
                       ") is " + (std::isnan(v) ? "NaN" : "infinite") + " and not the nodata value" +
                       (has_nodata ? " (" + std::to_string(nodata) + ")" : std::string(" (the band has none)")));
    } else {
      if (has_scale) v *= scale;
      if (has_offset) v += offset;
      // No surface on earth lies 100 km above or below sea level: an undeclared nodata value
      // (−9999 is plausible; −3.4e38, FLT_MAX are not).
      if (!(std::abs(v) <= kMaxPlausibleHeight_m))
        throw InputError(name + ": pixel (column " + std::to_string(i % r.columns) + ", row " + std::to_string(i / r.columns) +
                         ") has height " + format_height(v) + " m, not a plausible height; declare the raster's nodata " +
                         "value if it is one (gdal_edit.py -a_nodata VALUE)");
    }
  }
  if (r.nodata_pixels == r.values.size()) throw InputError(name + ": every pixel is nodata: no height to map");
  return r;
}

std::string crs_wkt_of(const std::string& crs, const std::string& what) {
  const ThirdPartyFpGuard fp;  // GDAL's and PROJ's own floating point
  register_gdal();
  QuietGdal quiet;
  OGRSpatialReference srs;
  if (srs.SetFromUserInput(crs.c_str()) != OGRERR_NONE)
    throw InputError(what + ": unknown coordinate reference system '" + crs + "' (" + QuietGdal::last() + ")");
  if (srs.IsGeographic()) throw InputError(what + ": " + crs + " is a geographic CRS (degrees, not metres)");
  // A raster is 2D: of a compound CRS (EPSG:7415 = RD New + NAP height) its horizontal part,
  // which keeps its EPSG code in the GeoTIFF keys (GIS software identifies it).
  if (srs.IsCompound()) srs.StripVertical();
  return wkt_of(srs);
}

std::optional<bool> same_crs(const std::string& a, const std::string& b) {
  if (a == b) return true;
  const ThirdPartyFpGuard fp;  // GDAL's and PROJ's own floating point
  register_gdal();
  QuietGdal quiet;
  OGRSpatialReference sa, sb;
  if (sa.SetFromUserInput(a.c_str()) != OGRERR_NONE || sb.SetFromUserInput(b.c_str()) != OGRERR_NONE) {
    const std::vector<int> ca = crs_epsg_codes(a), cb = crs_epsg_codes(b);
    if (ca.empty() || cb.empty()) return std::nullopt;
    return ca == cb;
  }
  const char* options[] = {"IGNORE_DATA_AXIS_TO_SRS_AXIS_MAPPING=YES", nullptr};
  if (sa.IsSame(&sb, options)) return true;
  const bool both_vertical = sa.IsCompound() && sb.IsCompound();
  if (sa.IsCompound()) sa.StripVertical();
  if (sb.IsCompound()) sb.StripVertical();
  return !both_vertical && sa.IsSame(&sb, options);
}

void write_geotiff(const std::filesystem::path& file, const GeoTiffOutput& out) {
  const ThirdPartyFpGuard fp;  // GDAL's and PROJ's own floating point
  register_gdal();
  if (out.values.size() != out.columns * out.rows || out.columns == 0 || out.rows == 0)
    throw InputError(file.string() + ": " + std::to_string(out.values.size()) + " values for a " + std::to_string(out.columns) +
                     " × " + std::to_string(out.rows) + " raster");
  write_atomically(file, [&](const std::filesystem::path& temp) {
    QuietGdal quiet;
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    if (!driver) throw InputError(file.string() + ": GDAL has no GeoTIFF driver");
    CPLStringList options;
    options.SetNameValue("COMPRESS", "DEFLATE");
    options.SetNameValue("PREDICTOR", "3");  // floating-point predictor
    if (out.columns >= 256 && out.rows >= 256) options.SetNameValue("TILED", "YES");
    const std::string tname = temp.string();
    Dataset ds(driver->Create(tname.c_str(), int(out.columns), int(out.rows), 1, GDT_Float32, options.List()));
    if (!ds) throw InputError(file.string() + ": cannot create the GeoTIFF (" + QuietGdal::last() + ")");
    double gt[6];
    for (int k = 0; k < 6; ++k) gt[k] = out.geotransform[std::size_t(k)];
    bool ok = ds->SetGeoTransform(gt) == CE_None;
    if (!out.crs_wkt.empty()) ok = ds->SetProjection(out.crs_wkt.c_str()) == CE_None && ok;
    for (const auto& [key, value] : out.metadata) ok = ds->SetMetadataItem(key.c_str(), value.c_str()) == CE_None && ok;
    GDALRasterBand* band = ds->GetRasterBand(1);
    ok = band->SetNoDataValue(out.nodata) == CE_None && ok;
    if (!out.band_description.empty()) band->SetDescription(out.band_description.c_str());
    ok = band->RasterIO(GF_Write, 0, 0, int(out.columns), int(out.rows), const_cast<float*>(out.values.data()), int(out.columns),
                        int(out.rows), GDT_Float32, 0, 0) == CE_None &&
         ok;
    if (!ok) throw InputError(file.string() + ": writing the GeoTIFF failed (" + QuietGdal::last() + ")");
    ds.reset();  // flushes and closes; GDAL reports a failed flush through its error state
    if (CPLGetLastErrorType() >= CE_Failure)
      throw InputError(file.string() + ": writing the GeoTIFF failed (" + QuietGdal::last() + "; disk full?)");
  });
}

}  // namespace skyband
