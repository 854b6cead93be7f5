// skyband points — calculation points made for the user.
//
//   skyband points grid --mesh FILE [--mesh FILE ...] --spacing S [--height H]
//                       [--bounds XMIN,YMIN,XMAX,YMAX] [--ground-materials NAME,...] [--lod L]
//                       --out POINTS.csv
//
// A ground grid (geometry/ground_grid.h): nodes at the cell centres of an S-aligned raster over
// the model (or --bounds), each H metres above the ground surface over it; no point inside or
// under a building (the highest surface over the node must be ground, and the point passes an
// exact under-a-triangle test). Columns x,y,z,nx,ny,nz (the normal up), ix,iy (the raster cell:
// x = (ix + ½)·S) and ground (the material the point stands on, "floor" on a model without
// ground triangles, where the ground is the plane of its lowest z). Written atomically, with a
// provenance record beside it; the counts of nodes left out go to stderr.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>

#include "examples/command_registry.h"
#include "examples/point_checks.h"
#include "examples/provenance.h"
#include "geometry/ground_grid.h"
#include "geometry/input_error.h"
#include "io/mesh_reader.h"
#include "io/points_csv.h"
#include "lighting/climate_irradiation.h"

namespace skyband::cli {

namespace {

struct GridArgs {
  std::vector<std::string> meshes;
  std::string out, lod;
  double spacing = 0, height = 0;
  std::vector<double> bounds;
  std::vector<std::string> ground_materials = default_ground_materials();
  bool quiet = false;
};

std::string shortest(double v) {
  char b[32];
  const auto [end, ec] = std::to_chars(b, b + sizeof b, v);
  return std::string(b, end);
}

void run_grid(const GridArgs& a) {
  if (a.meshes.empty()) throw InputError("points grid: at least one --mesh FILE is required");
  if (a.out.empty()) throw InputError("points grid: --out FILE.csv is required");
  if (!std::isfinite(a.spacing) || !(a.spacing > 0)) throw InputError("points grid: --spacing S (metres, > 0) is required");
  std::vector<std::pair<std::string, std::string>> inputs;
  for (const std::string& m : a.meshes) inputs.emplace_back("--mesh", m);
  check_output_file("--out", a.out, inputs);
  GroundGridOptions opt;
  opt.spacing_m = a.spacing;
  opt.height_m = a.height;
  if (!a.bounds.empty()) {
    if (a.bounds.size() != 4) throw InputError("--bounds: give four numbers, XMIN,YMIN,XMAX,YMAX (metres)");
    opt.bounds = std::array<double, 4>{a.bounds[0], a.bounds[1], a.bounds[2], a.bounds[3]};
  }
  TriangleSoup soup;
  for (const std::string& file : a.meshes) {
    MeshReadReport report;
    MeshReadOptions options;
    if (!a.lod.empty()) options.lod = a.lod;
    soup.append(read_mesh(file, &report, options));
    if (!a.quiet) std::fprintf(stderr, "%s\n", report.summary().c_str());
  }
  const Scene scene(std::move(soup));
  const std::vector<bool> ground_mask = ground_triangle_mask(scene.soup(), a.ground_materials);
  const GroundGrid grid = make_ground_grid(scene, ground_mask, opt);

  PointsTable table;
  table.file = a.out;
  table.header = {"x", "y", "z", "nx", "ny", "nz", "ix", "iy", "ground"};
  const auto& soup_ref = scene.soup();
  for (const GroundGridPoint& p : grid.points) {
    std::string ground_name = "floor";
    if (p.ground_triangle >= 0) {
      const auto t = std::size_t(p.ground_triangle);
      const std::uint32_t m = t < soup_ref.triangle_material.size() ? soup_ref.triangle_material[t] : 0;
      ground_name = m < soup_ref.material_names.size() ? soup_ref.material_names[m] : "ground";
    }
    table.rows.push_back({shortest(p.position.x()), shortest(p.position.y()), shortest(p.position.z()), "0", "0", "1",
                          std::to_string(p.ix), std::to_string(p.iy), ground_name});
    table.points.push_back({p.position, Vec3(0, 0, 1)});
  }
  write_points_csv(a.out, table, {}, {});
  write_provenance(a.out, inputs);
  const std::size_t nodes = grid.columns * grid.rows;
  std::fprintf(stderr,
               "points grid: %zu × %zu nodes at %s m: %zu points %s m above the %s, %zu under or on buildings, %zu where "
               "the model has no ground, %zu dropped by the exact under-a-surface test; wrote %s\n",
               grid.columns, grid.rows, shortest(a.spacing).c_str(), grid.points.size(), shortest(a.height).c_str(),
               grid.floor_plane ? "model's lowest z (no ground material: --ground-materials names it)" : "ground",
               grid.under_building, grid.off_ground, grid.dropped_exact, a.out.c_str());
  if (grid.points.empty() && nodes > 0)
    std::fprintf(stderr, "points grid: warning: no point: is the terrain named by a ground material (--ground-materials)?\n");
}

CommandRegistration registration{"points", [](CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("points", "Make calculation points for svf and irradiance");
  cmd->require_subcommand(1);
  auto args = std::make_shared<GridArgs>();
  CLI::App* grid = cmd->add_subcommand(
      "grid",
      "A ground grid: cell centres of an S-aligned raster over the model, H above the ground surface over each,\n"
      "none inside or under a building. Columns x,y,z,nx,ny,nz,ix,iy,ground.");
  grid->add_option("--mesh", args->meshes, "Mesh or city model file (OBJ, OFF, PLY, STL, CityJSON); repeat for several")
      ->check(CLI::ExistingFile);
  grid->add_option("--spacing", args->spacing, "Grid spacing S in metres");
  grid->add_option("--height", args->height, "Height of the points above the ground in metres (default 0: on it)");
  grid->add_option("--bounds", args->bounds, "Area XMIN,YMIN,XMAX,YMAX in the model's coordinates (default: its box)")
      ->delimiter(',');
  grid->add_option("--ground-materials", args->ground_materials,
                   "Material names (any case) of the ground surfaces (default: ground, terrain, road, water, forest, grass,\n"
                   "landuse, ...; a model without any stands on the plane of its lowest z)")
      ->delimiter(',');
  grid->add_option("--lod", args->lod, "City models: read every object at this LoD (default: each object's highest)");
  grid->add_option("--out", args->out, "Output points CSV, written atomically");
  grid->add_flag("--quiet", args->quiet, "No mesh report on stderr");
  grid->callback([args] { run_grid(*args); });
  return cmd;
}};

}  // namespace

}  // namespace skyband::cli
