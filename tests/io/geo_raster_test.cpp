#define BOOST_TEST_MODULE geo_raster
#include <boost/test/unit_test.hpp>

// Rasters through GDAL (io/geo_raster.h): GeoTIFF written and read back bit for bit, ESRI ASCII
// grids read with their nodata and CRS, and every refused input a one-line InputError.

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "geometry/core/input_error.h"
#include "input_error_of.h"
#include "io/geo_raster.h"

using namespace skyband;
namespace fs = std::filesystem;
namespace tt = boost::test_tools;

namespace {

fs::path temp_dir() {
  const fs::path p = fs::temp_directory_path() / ("skyband_geo_raster_test_" + std::to_string(::getpid()));
  fs::create_directories(p);
  return p;
}

fs::path write_text(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p) << text;
  return p;
}

using skyband::test::error_of;

const char* kWgs84Wkt =
    R"(GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]])";

}  // namespace

BOOST_AUTO_TEST_CASE(geotiff_round_trip_keeps_values_georeferencing_nodata_and_crs) {
  const std::vector<float> values{0.25f, 0.5f, -9999.0f, 1.0f, 0.125f, 0.75f};
  GeoTiffOutput out;
  out.columns = 3;
  out.rows = 2;
  out.geotransform = {85000, 2, 0, 447000, 0, -2};
  out.values = values;
  out.crs_wkt = crs_wkt_of("EPSG:28992", "test");
  out.metadata = {{"QUANTITY", "svf"}};
  out.band_description = "svf";
  const fs::path f = temp_dir() / "round.tif";
  write_geotiff(f, out);
  const GeoRaster r = read_geo_raster(f);
  BOOST_TEST(r.columns == 3u);
  BOOST_TEST(r.rows == 2u);
  BOOST_TEST((r.geotransform == out.geotransform));
  BOOST_TEST(r.crs_name == "EPSG:28992");
  BOOST_TEST(r.nodata_pixels == 1u);
  BOOST_TEST(std::isnan(r.values[2]));
  // Float32 values are exactly doubles: read back unchanged.
  for (std::size_t i : {0, 1, 3, 4, 5}) BOOST_TEST(r.values[i] == double(values[i]));
  // No temporary file is left beside it.
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(temp_dir()))
    if (e.path().filename().string().rfind("round.tif", 0) == 0) ++files;
  BOOST_TEST(files == 1u);
}

BOOST_AUTO_TEST_CASE(ascii_grid_with_nodata_and_lower_left_origin) {
  // ESRI ASCII grid: the header's lower-left corner and cell size give the geotransform
  // (x0 = xllcorner, y0 = yllcorner + nrows·cellsize, steps ±cellsize); row 0 is the northern one.
  const fs::path f = write_text("dsm.asc",
                                "ncols 3\nnrows 2\nxllcorner 1000\nyllcorner 2000\ncellsize 0.5\nNODATA_value -1\n"
                                "1 2 3\n4 -1 6.25\n");
  const GeoRaster r = read_geo_raster(f);
  BOOST_TEST(r.columns == 3u);
  BOOST_TEST(r.rows == 2u);
  BOOST_TEST((r.geotransform == std::array<double, 6>{1000, 0.5, 0, 2001, 0, -0.5}));
  BOOST_TEST(r.values[0] == 1.0);
  BOOST_TEST(r.values[5] == 6.25);
  BOOST_TEST(std::isnan(r.values[4]));
  BOOST_TEST(r.nodata_pixels == 1u);
  BOOST_TEST(r.crs_name == "");
}

BOOST_AUTO_TEST_CASE(heights_are_values_times_the_bands_scale_plus_its_offset) {
  // Heights stored in decimetres (GDAL scale 0.1, offset 2 m): read as metres.
  GeoTiffOutput out;
  out.columns = 2;
  out.rows = 1;
  const std::vector<float> raw{100.0f, 250.0f};
  out.values = raw;
  out.geotransform = {0, 1, 0, 0, 0, -1};
  const fs::path tif = temp_dir() / "raw.tif";
  write_geotiff(tif, out);
  // A VRT over it declaring the scale and offset (as gdal_translate -a_scale -a_offset writes).
  const fs::path p = write_text("scaled.vrt", R"(<VRTDataset rasterXSize="2" rasterYSize="1">
  <GeoTransform>0, 1, 0, 0, 0, -1</GeoTransform>
  <VRTRasterBand dataType="Float32" band="1">
    <Offset>2</Offset>
    <Scale>0.1</Scale>
    <SimpleSource><SourceFilename relativeToVRT="1">raw.tif</SourceFilename><SourceBand>1</SourceBand></SimpleSource>
  </VRTRasterBand>
</VRTDataset>
)");
  const GeoRaster r = read_geo_raster(p);
  BOOST_TEST(r.values[0] == 100.0f * 0.1 + 2.0, tt::tolerance(1e-12));
  BOOST_TEST(r.values[1] == 250.0f * 0.1 + 2.0, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(refused_rasters_name_the_file_and_the_reason) {
  const fs::path missing = temp_dir() / "missing.tif";
  BOOST_TEST(error_of([&] { read_geo_raster(missing); }).find("missing.tif: no such raster file") != std::string::npos);
  const fs::path garbage = write_text("garbage.tif", "this is not a raster\n");
  BOOST_TEST(error_of([&] { read_geo_raster(garbage); }).find("garbage.tif: not a raster GDAL can read") != std::string::npos);

  // A rotated geotransform.
  const std::vector<float> v{1, 2, 3, 4};
  GeoTiffOutput out;
  out.columns = out.rows = 2;
  out.values = v;
  out.geotransform = {0, 1, 0.1, 0, 0, -1};
  const fs::path rotated = temp_dir() / "rotated.tif";
  write_geotiff(rotated, out);
  BOOST_TEST(error_of([&] { read_geo_raster(rotated); }).find("rotated or sheared") != std::string::npos);

  // A NaN height that is not the nodata value, named by its column and row.
  const std::vector<float> nan_values{1, std::numeric_limits<float>::quiet_NaN(), 3, 4};
  out.values = nan_values;
  out.geotransform = {0, 1, 0, 0, 0, -1};
  const fs::path with_nan = temp_dir() / "nan.tif";
  write_geotiff(with_nan, out);
  BOOST_TEST(error_of([&] { read_geo_raster(with_nan); }).find("pixel (column 1, row 0) is NaN") != std::string::npos);

  // Geographic coordinates: degrees are not metres.
  const fs::path geo = write_text("geo.asc", "ncols 1\nnrows 1\nxllcorner 4\nyllcorner 52\ncellsize 0.001\n5\n");
  write_text("geo.prj", kWgs84Wkt);
  BOOST_TEST(error_of([&] { read_geo_raster(geo); }).find("geographic CRS") != std::string::npos);
  BOOST_TEST(error_of([&] { crs_wkt_of("EPSG:4326", "--crs"); }).find("--crs: EPSG:4326 is a geographic CRS") !=
             std::string::npos);
  BOOST_TEST(error_of([&] { crs_wkt_of("EPSG:nonsense", "--crs"); }).find("unknown coordinate reference system") !=
             std::string::npos);

  // ASCII grids: GDAL's driver reads an unparsable or missing value as 0, so the text is checked.
  const std::string head = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n";
  BOOST_TEST(error_of([&] {
               read_geo_raster(write_text("nan.asc", head + "1 2 3\n4 nan 6\n"));
             }).find("nan.asc:8: value 'nan' is not a finite number") != std::string::npos);
  BOOST_TEST(error_of([&] {
               read_geo_raster(write_text("junk.asc", head + "1 2 3\n4 1.0abc 6\n"));
             }).find("junk.asc:8: value '1.0abc'") != std::string::npos);
  BOOST_TEST(error_of([&] {
               read_geo_raster(write_text("short.asc", head + "1 2 3\n4 5\n"));
             }).find("short.asc: 5 values for ncols × nrows = 3 × 2 = 6 pixels") != std::string::npos);
  // Every pixel nodata; an implausible height that is not the nodata value (FLT_MAX-like fill).
  BOOST_TEST(error_of([&] {
               read_geo_raster(write_text("none.asc", head + "-9999 -9999 -9999\n-9999 -9999 -9999\n"));
             }).find("none.asc: every pixel is nodata") != std::string::npos);
  BOOST_TEST(error_of([&] {
               read_geo_raster(write_text("fill.asc", head + "1 2 3\n4 -3.4e38 6\n"));
             }).find("fill.asc: pixel (column 1, row 1) has height -3.4e+38 m, not a plausible height") != std::string::npos);

  // Too many pixels for the limit.
  BOOST_TEST(error_of([&] { read_geo_raster(rotated, 3); }).find("over the limit") != std::string::npos);

  // Writing into a folder that does not exist.
  out.values = v;
  BOOST_TEST(!error_of([&] { write_geotiff(temp_dir() / "no_such_folder" / "x.tif", out); }).empty());
  BOOST_TEST(!fs::exists(temp_dir() / "no_such_folder"));
}

// same_crs: the same horizontal CRS however it is spelled; a compound CRS is its horizontal part
// plus heights, so it matches the horizontal CRS alone, and another compound only with the same
// heights; a CRS GDAL does not know compares by its EPSG codes, else is unknown.
BOOST_AUTO_TEST_CASE(same_crs_compares_what_the_names_mean) {
  BOOST_TEST((same_crs("EPSG:28992", "urn:ogc:def:crs:EPSG::28992") == true));
  BOOST_TEST((same_crs("EPSG:28992", "http://www.opengis.net/def/crs/EPSG/0/28992") == true));
  BOOST_TEST((same_crs("EPSG:28992", crs_wkt_of("EPSG:28992", "test")) == true));
  BOOST_TEST((same_crs("EPSG:7415", "EPSG:28992") == true));  // RD New + NAP height; RD New
  BOOST_TEST((same_crs("EPSG:7415", "urn:ogc:def:crs,crs:EPSG::28992,crs:EPSG::5709") == true));
  BOOST_TEST((same_crs("EPSG:6691+6695", "EPSG:6691") == true));
  BOOST_TEST((same_crs("EPSG:28992", "EPSG:25833") == false));
  BOOST_TEST((same_crs("EPSG:25832", "EPSG:25833") == false));      // neighbouring UTM zones
  BOOST_TEST((same_crs("EPSG:7415", "EPSG:28992+5710") == false));  // NAP height and Ostend height
  BOOST_TEST((same_crs("EPSG:99999", "EPSG:99998") == false));      // unknown codes, but different ones
  BOOST_TEST((same_crs("urn:ogc:def:crs:EPSG::99999", "EPSG:99999") == true));
  BOOST_TEST(!same_crs("urn:adv:crs:ETRS89_UTM33*DE_DHHN92_NH", "EPSG:25833").has_value());
  BOOST_TEST((same_crs("urn:adv:crs:ETRS89_UTM33*DE_DHHN92_NH", "urn:adv:crs:ETRS89_UTM33*DE_DHHN92_NH") == true));
}
