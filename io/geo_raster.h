#pragma once
// Georeferenced rasters through GDAL: digital surface models in (any format GDAL reads:
// GeoTIFF, ASCII grid, ...), sky-view-factor maps out (GeoTIFF).
//
// Georeferencing is GDAL's affine geotransform: the outer corner of pixel (column c, row r) is
//   x = gt[0] + c·gt[1] + r·gt[2],   y = gt[3] + c·gt[4] + r·gt[5]   (metres in the raster's CRS).
// Only axis-aligned rasters are read (gt[2] = gt[4] = 0; north-up rasters have gt[5] < 0):
// rotated or sheared ones are refused. Heights are band 1, as doubles; pixels equal to the band's
// nodata value become NaN. A geographic CRS (degrees are not metres) is refused.
//
// Errors (InputError, one line naming the file): not readable by GDAL, no band, a rotated
// geotransform, zero or non-finite pixel sizes, a geographic CRS, a NaN or infinite height that is
// not the nodata value (naming its column and row), a raster over `max_pixels`.
#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace skyband {

struct GeoRaster {
  std::size_t columns = 0, rows = 0;
  std::array<double, 6> geotransform{0, 1, 0, 0, 0, -1};
  std::vector<double> values;    // row-major, row 0 first; NaN = nodata
  std::optional<double> nodata;  // the band's nodata value, as in the file
  std::string crs_wkt;           // "" = the file has none
  std::string crs_name;          // "EPSG:28992" when the CRS has an EPSG code, else its name, "" if none
  std::size_t nodata_pixels = 0;
};

// Reads band 1 of a raster file (see above).
GeoRaster read_geo_raster(const std::filesystem::path& file, std::size_t max_pixels = 100'000'000);

// A CRS given by the user or a model file ("EPSG:7415", "urn:ogc:def:crs:EPSG::7415",
// "https://www.opengis.net/def/crs/EPSG/0/7415", WKT) as WKT for a GeoTIFF — of a compound CRS
// its horizontal part (EPSG:7415 → EPSG:28992); InputError (naming `what`) when GDAL/PROJ does
// not know it or it is geographic.
std::string crs_wkt_of(const std::string& crs, const std::string& what);

// Whether two CRSs (each as crs_wkt_of takes it, or WKT) are the same coordinate system: their
// horizontal parts equivalent by GDAL (axis-order conventions aside) and, when both have a
// vertical part, the whole CRSs too — a CRS without a vertical part says nothing about heights,
// so EPSG:28992 and EPSG:7415 (= EPSG:28992 + NAP height) are the same. Equal strings are the
// same. When GDAL does not know one of them: the same if both name the same EPSG codes
// (io/crs_codes.h), different if both name EPSG codes and these differ, else nullopt (unknown).
std::optional<bool> same_crs(const std::string& a, const std::string& b);

struct GeoTiffOutput {
  std::size_t columns = 0, rows = 0;
  std::array<double, 6> geotransform{0, 1, 0, 0, 0, -1};
  std::span<const float> values;  // row-major, row 0 first
  float nodata = -9999.0f;
  std::string crs_wkt;  // "" = none written
  // Dataset metadata items (TIFF tags GDAL keeps: the quantity, its units, the command line).
  std::vector<std::pair<std::string, std::string>> metadata;
  std::string band_description;  // e.g. "svf"
};

// Writes a single-band Float32 GeoTIFF (deflate-compressed, tiled when large) atomically.
// InputError when GDAL cannot write it.
void write_geotiff(const std::filesystem::path& file, const GeoTiffOutput& out);

}  // namespace skyband
