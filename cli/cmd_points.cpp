// skyband points — calculation points made for the user.
//
//   skyband points grid --mesh FILE [--mesh FILE ...] --spacing S [--height H]
//                       [--bounds XMIN,YMIN,XMAX,YMAX] [--ground-materials NAME,...] [--lod L]
//                       --out POINTS.csv
//
// A ground grid (geometry/points/ground_grid.h): nodes at the cell centres of an S-aligned raster over
// the model (or --bounds), each H metres above the ground surface over it; no point inside or
// under a building (the highest surface over the node must be ground, and the point passes an
// exact under-a-triangle test). Columns x,y,z,nx,ny,nz (the normal up), ix,iy (the raster cell:
// x = (ix + ½)·S) and ground (the material the point stands on, "floor" on a model without
// ground triangles, where the ground is the plane of its lowest z). Written atomically, with a
// provenance record beside it; the counts of nodes left out go to stderr.
//
//   skyband points facades --mesh FILE [--mesh FILE ...] --spacing S [--offset D]
//                          [--surfaces wall,roof] [--lod L] [--threads K] --out POINTS.csv
//
// Facade (and roof) points (geometry/points/facade_points.h): the cell centres of an S grid in each
// wall triangle's plane, moved D metres (default 0.1) along the outward normal, none on party
// walls, behind a coincident or adjacent surface, or inside a building. Columns x,y,z,nx,ny,nz
// (the outward normal), object (the CityObject id, or "component K" for a model without
// objects), surface (wall or roof), material (the triangle's material: the semantic surface
// type where the model has one), face (the triangle's index in the meshes' order), iu,iv (the
// face's grid cell). Written atomically with provenance; the counts of what was left out go to
// stderr.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cli/command_registry.h"
#include "cli/number_text.h"
#include "cli/point_checks.h"
#include "cli/point_job_args.h"
#include "cli/provenance.h"
#include "geometry/core/input_error.h"
#include "geometry/points/facade_points.h"
#include "geometry/points/ground_grid.h"
#include "io/mesh_reader.h"
#include "io/points_csv.h"
#include "lighting/climate/climate_irradiation.h"

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

struct FacadeArgs {
  std::vector<std::string> meshes;
  std::string out, lod;
  double spacing = 0, offset = 0.1;
  std::vector<std::string> surfaces{"wall"};
  int threads = 0;
  bool quiet = false;
};

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
  const Scene scene(load_meshes(a.meshes, a.lod, a.quiet));
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
    table.rows.push_back({shortest_text(p.position.x()), shortest_text(p.position.y()), shortest_text(p.position.z()), "0", "0",
                          "1", std::to_string(p.ix), std::to_string(p.iy), ground_name});
    table.points.push_back({p.position, Vec3(0, 0, 1)});
  }
  write_points_csv(a.out, table, {}, {});
  write_provenance(a.out, inputs);
  const std::size_t nodes = grid.columns * grid.rows;
  std::fprintf(stderr,
               "points grid: %zu × %zu nodes at %s m: %zu points %s m above the %s, %zu under or on buildings, %zu where "
               "the model has no ground, %zu dropped by the exact under-a-surface test; wrote %s\n",
               grid.columns, grid.rows, shortest_text(a.spacing).c_str(), grid.points.size(), shortest_text(a.height).c_str(),
               grid.floor_plane ? "model's lowest z (no ground material: --ground-materials names it)" : "ground",
               grid.under_building, grid.off_ground, grid.dropped_exact, a.out.c_str());
  if (grid.points.empty() && nodes > 0)
    std::fprintf(stderr,
                 "points grid: warning: no point: is the terrain named by a ground material (--ground-materials; a file without "
                 "materials by its name)?\n");
}

void parse_surfaces(const std::vector<std::string>& names, FacadePointsOptions& opt) {
  opt.walls = opt.roofs = false;
  for (const std::string& n : names) {
    if (n == "wall" || n == "walls")
      opt.walls = true;
    else if (n == "roof" || n == "roofs")
      opt.roofs = true;
    else
      throw InputError("--surfaces " + n + ": unknown surface; give wall, roof or wall,roof");
  }
}

void run_facades(const FacadeArgs& a) {
  if (a.meshes.empty()) throw InputError("points facades: at least one --mesh FILE is required");
  if (a.out.empty()) throw InputError("points facades: --out FILE.csv is required");
  if (a.spacing == 0) throw InputError("points facades: --spacing S (metres, > 0) is required");
  FacadePointsOptions opt;
  opt.spacing_m = a.spacing;
  opt.offset_m = a.offset;
  if (a.threads < 0) throw InputError("--threads " + std::to_string(a.threads) + ": give 0 (all cores) or a positive count");
  opt.threads = a.threads;
  parse_surfaces(a.surfaces, opt);
  check_facade_options(opt);
  std::vector<std::pair<std::string, std::string>> inputs;
  for (const std::string& m : a.meshes) inputs.emplace_back("--mesh", m);
  check_output_file("--out", a.out, inputs);
  const Scene scene(load_meshes(a.meshes, a.lod, a.quiet));
  const FacadePoints fp = make_facade_points(scene, opt);

  const TriangleSoup& soup = scene.soup();
  PointsTable table;
  table.file = a.out;
  table.header = {"x", "y", "z", "nx", "ny", "nz", "object", "surface", "material", "face", "iu", "iv"};
  table.rows.reserve(fp.points.size());
  for (const FacadePoint& p : fp.points) {
    const std::uint32_t m = p.triangle < soup.triangle_material.size() ? soup.triangle_material[p.triangle] : 0;
    const std::string material = m < soup.material_names.size() ? soup.material_names[m] : "";
    table.rows.push_back({shortest_text(p.position.x()), shortest_text(p.position.y()), shortest_text(p.position.z()),
                          shortest_text(p.normal.x() + 0.0), shortest_text(p.normal.y() + 0.0), shortest_text(p.normal.z() + 0.0),
                          fp.group_names[p.group], p.surface == FacadeSurface::roof ? "roof" : "wall", material,
                          std::to_string(p.triangle), std::to_string(p.iu), std::to_string(p.iv)});
    table.points.push_back({p.position, p.normal});
  }
  write_points_csv(a.out, table, {}, {});
  write_provenance(a.out, inputs);
  std::fprintf(stderr,
               "points facades: %zu cell centres at %s m on %zu faces: %zu points %s m out; left out: %zu enclosed on both "
               "sides (party or interior walls), %zu covered by a surface within %s m in front, %zu under the terrain, "
               "%zu in front of the face but inside a building, %zu facing down, %zu undecided; %zu zero-area faces; outward by "
               "the %s; wrote %s\n",
               fp.centres, shortest_text(a.spacing).c_str(), fp.faces, fp.points.size(), shortest_text(a.offset).c_str(),
               fp.enclosed, fp.covered, shortest_text(a.offset + 0.01).c_str(), fp.underground, fp.inside, fp.facing_down,
               fp.undecided, fp.zero_area,
               fp.groups_are_objects ? "city objects" : "connected components (the model has no objects)", a.out.c_str());
  if (fp.from_winding > 0)
    std::fprintf(stderr,
                 "points facades: warning: %zu points on surfaces open on both sides (no enclosing building found): outward "
                 "taken from the winding (up for roofs)\n",
                 fp.from_winding);
  if (fp.points.empty())
    std::fprintf(stderr, "points facades: warning: no point: does the model have walls (or roofs with --surfaces roof)?\n");
}

CommandRegistration registration{
    "points", [](CLI::App& app) {
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

      auto fargs = std::make_shared<FacadeArgs>();
      CLI::App* facades = cmd->add_subcommand(
          "facades",
          "Facade points: cell centres of an S grid on every wall (and roof), D along the outward normal, none on\n"
          "party walls, behind another surface or inside a building. Columns x,y,z,nx,ny,nz,object,surface,material,face,iu,iv.");
      facades->add_option("--mesh", fargs->meshes, "Mesh or city model file (OBJ, OFF, PLY, STL, CityJSON); repeat for several")
          ->check(CLI::ExistingFile);
      facades->add_option("--spacing", fargs->spacing, "Grid spacing S in metres, in each face's plane");
      facades->add_option("--offset", fargs->offset, "Distance D of the points in front of their face in metres (default 0.1)");
      facades->add_option("--surfaces", fargs->surfaces, "Surfaces to cover: wall, roof or wall,roof (default wall)")
          ->delimiter(',');
      facades->add_option("--lod", fargs->lod, "City models: read every object at this LoD (default: each object's highest)");
      facades->add_option("--out", fargs->out, "Output points CSV, written atomically");
      facades->add_option("--threads", fargs->threads, "Worker threads (default 0: all cores; the output does not depend on it)");
      facades->add_flag("--quiet", fargs->quiet, "No mesh report on stderr");
      facades->callback([fargs] { run_facades(*fargs); });
      return cmd;
    }};

}  // namespace

}  // namespace skyband::cli
