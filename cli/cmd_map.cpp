// skyband map — a raster of sky view factors (or sky exposure) over a city, as a GeoTIFF.
//
//   skyband map --mesh FILE [--mesh FILE ...] --spacing S [--height H] [--bounds XMIN,YMIN,XMAX,YMAX]
//               [--ground-materials NAME,...] [--lod L] [--quantity svf|sky_exposure] [--crs CRS]
//               [--threads K] [--quiet] --out MAP.tif [--png MAP.png]
//   skyband map --dsm DSM.tif [--quantity ...] [--crs CRS] [--threads K] [--quiet] --out MAP.tif [--png MAP.png]
//
// From a city model (--mesh): the pixels are the cells of the ground grid of `skyband points
// grid` (geometry/points/ground_grid.h: an S-aligned raster, a point H above the ground at each cell
// centre, none inside or under a building); pixels without a point are nodata.
// From a digital surface model (--dsm, any raster GDAL reads, heights in metres): the pixels are
// the DSM's, each a flat column of its height (geometry/mesh/height_field.h), the point on top of each
// pixel — what UMEP and SAGA estimate by shadow casting, computed exactly; the DSM's nodata
// pixels have no column and no value. The world beyond the raster's edge is empty.
// Every value is exact (the exact horizon where the scene allows it, the exact union elsewhere).
//
// Output: a single-band Float32 GeoTIFF (nodata −9999) in the model's CRS (the city model's
// referenceSystem or the DSM's own; --crs names it for an input that names none, and is refused
// when it differs from the input's: it labels, it does not reproject), written atomically, with the quantity, its units
// and the command line in its metadata and a provenance record beside it; with --png a
// false-colour picture with a legend (cli/map_picture.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <optional>

#include "cli/command_registry.h"
#include "cli/map_picture.h"
#include "cli/point_checks.h"
#include "cli/point_job_args.h"
#include "cli/provenance.h"
#include "geometry/core/input_error.h"
#include "geometry/mesh/height_field.h"
#include "geometry/points/ground_grid.h"
#include "geometry/visibility/sky_factors.h"
#include "io/geo_raster.h"
#include "io/mesh_reader.h"
#include "io/png_writer.h"
#include "io/utf8_text.h"
#include "lighting/climate/climate_irradiation.h"

namespace skyband::cli {

namespace {

constexpr float kNoData = -9999.0f;
constexpr std::size_t kMaxDsmPixels = 4'000'000;

struct MapArgs {
  std::vector<std::string> meshes;
  std::string dsm, out, png, lod, quantity = "svf", crs;
  double spacing = 0, height = 0;
  std::vector<double> bounds;
  std::vector<std::string> ground_materials = default_ground_materials();
  int threads = 0;
  bool quiet = false;
};

// The raster being made: its grid, CRS and one calculation point per pixel with a value.
struct MapGrid {
  std::size_t columns = 0, rows = 0;
  std::array<double, 6> geotransform{};
  std::string crs_wkt, crs_name;
  std::vector<QueryPoint> points;
  std::vector<std::size_t> pixel;  // points[i] is pixel pixel[i] (row-major index)
  VisibilityOptions visibility;
};

std::string shortest(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

void check_args(const MapArgs& a) {
  if (a.meshes.empty() == a.dsm.empty())
    throw InputError("map: give either --mesh FILE (a city model) or --dsm FILE (a surface raster), not both");
  if (a.out.empty()) throw InputError("map: --out MAP.tif is required");
  if (a.quantity != "svf" && a.quantity != "sky_exposure")
    throw InputError("map: --quantity " + a.quantity + ": choose svf or sky_exposure");
  if (!a.dsm.empty() && (a.spacing != 0 || a.height != 0 || !a.bounds.empty() || !a.lod.empty()))
    throw InputError("map: --spacing, --height, --bounds and --lod apply to --mesh; a DSM's pixels are the map's");
  if (!a.meshes.empty() && (!std::isfinite(a.spacing) || !(a.spacing > 0)))
    throw InputError("map: --spacing S (metres, > 0) is required with --mesh");
  if (a.threads < 0) throw InputError("map: --threads " + std::to_string(a.threads) + ": give 0 (all cores) or more");
  if (!a.crs.empty()) crs_wkt_of(a.crs, "--crs");  // known to GDAL, and projected: before any input is read
  std::vector<std::pair<std::string, std::string>> inputs;
  for (const std::string& m : a.meshes) inputs.emplace_back("--mesh", m);
  if (!a.dsm.empty()) inputs.emplace_back("--dsm", a.dsm);
  check_output_file("--out", a.out, inputs);
  if (!a.png.empty()) {
    check_output_file("--png", a.png, inputs);
    if (std::filesystem::absolute(a.png) == std::filesystem::absolute(a.out))
      throw InputError("map: --png and --out name the same file");
  }
}

std::vector<std::pair<std::string, std::string>> input_files(const MapArgs& a) {
  std::vector<std::pair<std::string, std::string>> inputs;
  for (const std::string& m : a.meshes) inputs.emplace_back("--mesh", m);
  if (!a.dsm.empty()) inputs.emplace_back("--dsm", a.dsm);
  return inputs;
}

// --crs names the CRS of the output and never reprojects: with an input that names a CRS, it must
// be that CRS (a map labelled with another one is a silent wrong answer in any GIS), else
// InputError saying what to do. An input that names none takes it; one whose CRS GDAL does not
// know takes it with a warning.
// `input_crs` as same_crs takes it (a name or WKT), `label` as the message shows it.
void check_crs_option(const std::string& crs, const std::string& input_crs, const std::string& label,
                      const std::string& input_file, bool dsm) {
  if (crs.empty() || input_crs.empty()) return;
  const std::optional<bool> same = same_crs(crs, input_crs);
  if (same == false)
    throw InputError("map: --crs " + printable_text(crs) + " is not the CRS of " + input_file + " (" + label +
                     "): --crs labels the map, it does not reproject; drop --crs (the map is then in the input's CRS) or " +
                     (dsm ? "reproject the DSM first (gdalwarp -t_srs " + printable_text(crs) + ")"
                          : std::string("reproject the model first")));
  if (!same)
    std::fprintf(stderr, "map: warning: %s names the CRS %s, which GDAL does not know: the map is labelled --crs %s as given\n",
                 input_file.c_str(), label.c_str(), printable_text(crs).c_str());
}

MapGrid grid_from_model(const MapArgs& a, std::unique_ptr<Scene>& scene) {
  GroundGridOptions opt;
  opt.spacing_m = a.spacing;
  opt.height_m = a.height;
  if (!a.bounds.empty()) {
    if (a.bounds.size() != 4) throw InputError("--bounds: give four numbers, XMIN,YMIN,XMAX,YMAX (metres)");
    opt.bounds = std::array<double, 4>{a.bounds[0], a.bounds[1], a.bounds[2], a.bounds[3]};
  }
  std::vector<MeshReadReport> reports;
  scene = std::make_unique<Scene>(load_meshes(a.meshes, a.lod, a.quiet, &reports));
  // The files share one CRS (load_meshes refuses others): the first that names one names it.
  const auto named = std::find_if(reports.begin(), reports.end(), [](const MeshReadReport& r) { return !r.crs.empty(); });
  const std::string model_crs = named == reports.end() ? "" : named->crs;
  if (named != reports.end()) check_crs_option(a.crs, model_crs, printable_text(model_crs), named->file, false);
  const GroundGrid grid = make_ground_grid(*scene, ground_triangle_mask(scene->soup(), a.ground_materials), opt);
  MapGrid m;
  m.columns = grid.columns;
  m.rows = grid.rows;
  // North up: row 0 is the northernmost row of cells (iy = iy0 + rows − 1).
  const double s = a.spacing;
  m.geotransform = {double(grid.ix0) * s, s, 0, double(grid.iy0 + std::int64_t(grid.rows)) * s, 0, -s};
  for (const GroundGridPoint& p : grid.points) {
    const std::size_t c = std::size_t(p.ix - grid.ix0), r = grid.rows - 1 - std::size_t(p.iy - grid.iy0);
    m.points.push_back({p.position, Vec3(0, 0, 1)});
    m.pixel.push_back(r * m.columns + c);
  }
  const std::string crs = a.crs.empty() ? model_crs : a.crs;
  if (!crs.empty()) {
    m.crs_wkt = crs_wkt_of(crs, a.crs.empty() ? "the model's referenceSystem" : "--crs");
    m.crs_name = crs;
  }
  if (!a.quiet)
    std::fprintf(stderr, "map: %zu × %zu pixels of %s m, %zu with a point (%zu under or on buildings, %zu off the ground)\n",
                 m.columns, m.rows, shortest(s).c_str(), m.points.size(), grid.under_building, grid.off_ground);
  return m;
}

MapGrid grid_from_dsm(const MapArgs& a, std::unique_ptr<Scene>& scene) {
  // The pixel columns cost ~4.5 kB a pixel (~7 triangles with their BVH and classification, on
  // a rough DSM): 4 million pixels (2000²) fill ~18 GB. Larger rasters are refused up front.
  const GeoRaster dsm = read_geo_raster(a.dsm, kMaxDsmPixels);
  check_crs_option(a.crs, dsm.crs_wkt, dsm.crs_name.empty() ? "a CRS without a name" : printable_text(dsm.crs_name), a.dsm, true);
  HeightField f;
  f.columns = dsm.columns;
  f.rows = dsm.rows;
  f.x0 = dsm.geotransform[0];
  f.dx = dsm.geotransform[1];
  f.y0 = dsm.geotransform[3];
  f.dy = dsm.geotransform[5];
  f.heights = dsm.values;
  try {
    scene = std::make_unique<Scene>(height_field_mesh(f, height_field_floor(f)));
  } catch (const InputError& e) {  // the field's own checks, after the reader's: named by the file
    throw InputError(a.dsm + ": " + e.what());
  }
  MapGrid m;
  m.columns = dsm.columns;
  m.rows = dsm.rows;
  m.geotransform = dsm.geotransform;
  m.visibility.prefer_horizon = true;
  for (std::size_t r = 0; r < f.rows; ++r)
    for (std::size_t c = 0; c < f.columns; ++c) {
      const double h = f.height(c, r);
      if (std::isnan(h)) continue;
      m.points.push_back({Vec3(f.centre_x(c), f.centre_y(r), h), Vec3(0, 0, 1)});
      m.pixel.push_back(r * m.columns + c);
    }
  if (!a.crs.empty()) {
    m.crs_wkt = crs_wkt_of(a.crs, "--crs");
    m.crs_name = a.crs;
  } else {
    m.crs_wkt = dsm.crs_wkt;
    m.crs_name = dsm.crs_name;
  }
  if (!a.quiet)
    std::fprintf(stderr, "map: DSM %s: %zu × %zu pixels of %s × %s m, %zu nodata; %zu triangles as pixel columns\n",
                 a.dsm.c_str(), dsm.columns, dsm.rows, shortest(std::abs(f.dx)).c_str(), shortest(std::abs(f.dy)).c_str(),
                 dsm.nodata_pixels, scene->soup().triangle_count());
  return m;
}

void run(const MapArgs& a) {
  check_args(a);
  std::unique_ptr<Scene> scene;
  const MapGrid m = a.dsm.empty() ? grid_from_model(a, scene) : grid_from_dsm(a, scene);
  if (m.points.empty())
    throw InputError(
        "map: no pixel has a calculation point (for a city model: is the terrain named by a ground material, "
        "--ground-materials?)");
  if (m.crs_wkt.empty())
    std::fprintf(stderr, "map: warning: the %s names no CRS: the GeoTIFF has none (give --crs EPSG:n)\n",
                 a.dsm.empty() ? "city model" : "DSM");

  const auto t0 = std::chrono::steady_clock::now();
  Progress progress("map", !a.quiet);
  const SkyFactorsRun run = compute_sky_factors(*scene, m.points, m.visibility, SkyFactorsMethod::automatic, a.threads,
                                                [&](std::size_t d, std::size_t t) { progress(d, t); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::vector<float> values(m.columns * m.rows, kNoData);
  const bool svf = a.quantity == "svf";
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const double v = svf ? run.factors[i].svf : run.factors[i].sky_exposure;
    if (!std::isfinite(v)) throw InputError("map: internal error: a non-finite value at pixel " + std::to_string(m.pixel[i]));
    values[m.pixel[i]] = float(v);
  }
  GeoTiffOutput out;
  out.columns = m.columns;
  out.rows = m.rows;
  out.geotransform = m.geotransform;
  out.values = values;
  out.nodata = kNoData;
  out.crs_wkt = m.crs_wkt;
  out.band_description = a.quantity;
  out.metadata = {{"QUANTITY", a.quantity},
                  {"UNITS", svf ? "1 (cosine-weighted fraction of the open sky of a horizontal surface)"
                                : "1 (visible sky solid angle / 2 pi sr)"},
                  {"SOURCE", a.dsm.empty() ? "city model ground grid" : "DSM pixel columns"},
                  {"METHOD", method_summary(run.by_horizon, run.by_exact, run.by_bands)},
                  {"SOFTWARE", "skyband " SKYBAND_VERSION},
                  {"COMMAND", invocation()}};
  if (!m.crs_name.empty()) out.metadata.emplace_back("MODEL_CRS", m.crs_name);  // as named (compound CRSs included)
  write_geotiff(a.out, out);
  write_provenance(a.out, input_files(a));
  if (!a.png.empty()) {
    MapPictureInput pic;
    pic.columns = m.columns;
    pic.rows = m.rows;
    pic.values = values;
    pic.nodata = kNoData;
    pic.quantity = svf ? "SKY VIEW FACTOR" : "SKY EXPOSURE";
    pic.units = svf ? "FRACTION OF THE OPEN SKY" : "SOLID ANGLE / 2 PI SR";
    pic.pixel_m = std::abs(m.geotransform[1]);
    const Picture p = map_picture(pic);
    write_png_rgb8(a.png, p.width, p.height, p.rgb);
    write_provenance(a.png, input_files(a));
  }
  if (!a.quiet) {
    double sum = 0;
    for (std::size_t i = 0; i < m.points.size(); ++i) sum += values[m.pixel[i]];
    std::fprintf(stderr, "map: %zu pixels in %.2f s (%.0f pixels/s), mean %s %.4f; %s; wrote %s%s%s\n", m.points.size(), seconds,
                 seconds > 0 ? double(m.points.size()) / seconds : 0.0, a.quantity.c_str(), sum / double(m.points.size()),
                 method_summary(run.by_horizon, run.by_exact, run.by_bands).c_str(), a.out.c_str(), a.png.empty() ? "" : " and ",
                 a.png.c_str());
  }
}

CommandRegistration registration{
    "map", [](CLI::App& app) {
      auto args = std::make_shared<MapArgs>();
      CLI::App* cmd = app.add_subcommand(
          "map",
          "A GeoTIFF raster of exact sky view factors (or sky exposure) over a city model's ground, or over every\n"
          "pixel of a digital surface model (each pixel a flat column of its height), with an optional\n"
          "false-colour PNG and legend.");
      cmd->add_option("--mesh", args->meshes, "City model or mesh file (repeatable): the map covers its ground");
      cmd->add_option("--dsm", args->dsm, "Digital surface model raster (GeoTIFF or any GDAL raster; heights in metres)");
      cmd->add_option("--spacing", args->spacing, "With --mesh: pixel size S in metres (pixel edges at multiples of S)");
      cmd->add_option("--height", args->height, "With --mesh: points H metres above the ground (default 0)");
      cmd->add_option("--bounds", args->bounds, "With --mesh: area XMIN,YMIN,XMAX,YMAX (default: the model's box)")
          ->delimiter(',');
      cmd->add_option("--ground-materials", args->ground_materials,
                      "With --mesh: material / semantic names that are ground (default: the usual terrain classes)")
          ->delimiter(',');
      cmd->add_option("--lod", args->lod, "With --mesh: read city models at this LoD (default: each object's highest)");
      cmd->add_option("--quantity", args->quantity, "svf (default) or sky_exposure");
      cmd->add_option("--crs", args->crs,
                      "CRS of the output (EPSG:n, WKT, ...) for an input that names none; it labels, it does not\n"
                      "reproject, so it must be the input's own CRS when the input names one (default: that one)");
      cmd->add_option("--out", args->out, "Output GeoTIFF (Float32, nodata -9999), written atomically");
      cmd->add_option("--png", args->png, "Also a false-colour PNG with a legend");
      cmd->add_option("--threads", args->threads, "Worker threads (0 = all cores)");
      cmd->add_flag("--quiet", args->quiet, "No progress or summary on stderr");
      cmd->callback([args] { run(*args); });
      return cmd;
    }};

}  // namespace

}  // namespace skyband::cli
