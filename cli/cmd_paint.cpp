// skyband paint — results on the model itself: the mesh written back as PLY with a value and a
// colour on each face, for 3D viewers.
//
//   skyband paint --mesh FILE [--mesh FILE ...] [--lod L] --values RESULTS.csv [--column svf]
//                 --out MODEL.ply [--quiet]
//
// RESULTS.csv is a points file with a `face` column — the triangle's index in the meshes'
// order, as `skyband points facades` writes it — after `svf` or `irradiance` has added its
// columns (any numeric column can be painted). The meshes must be given as for `points
// facades` (the same files, order and --lod), so that the indices name the same triangles; an
// index beyond the meshes' triangles is an error. Each face's value is the mean of its points'
// values; faces without points get the nodata value −9999 and light grey. Colours: viridis over
// the values' range rounded out to 0.05 (as `skyband map`'s legend) for fractions in [0, 1],
// over the exact range otherwise; the header comments name the column, the range, the nodata
// value and the command line.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cli/command_registry.h"
#include "cli/map_picture.h"
#include "cli/point_checks.h"
#include "cli/point_job_args.h"
#include "cli/provenance.h"
#include "geometry/core/input_error.h"
#include "io/csv_table.h"
#include "io/mesh_reader.h"
#include "io/ply_writer.h"

namespace skyband::cli {

namespace {

constexpr float kNoData = -9999.0f;

struct PaintArgs {
  std::vector<std::string> meshes;
  std::string values, column = "svf", out, lod;
  bool quiet = false;
};

std::string fixed(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

void run(const PaintArgs& a) {
  if (a.meshes.empty()) throw InputError("paint: at least one --mesh FILE is required (as given to points facades)");
  if (a.values.empty()) throw InputError("paint: --values RESULTS.csv is required (points with a face column and values)");
  if (a.out.empty()) throw InputError("paint: --out MODEL.ply is required");
  if (std::filesystem::path(a.out).extension() != ".ply")
    throw InputError("paint: --out " + a.out + ": the file name must end in .ply");
  std::vector<std::pair<std::string, std::string>> inputs{{"--values", a.values}};
  for (const std::string& m : a.meshes) inputs.emplace_back("--mesh", m);
  check_output_file("--out", a.out, inputs);

  const CsvTable table = read_csv_table(a.values, "values file");
  const int face_col = table.column("face"), value_col = table.column(a.column);
  if (face_col < 0) throw InputError(a.values + ": no 'face' column (skyband points facades writes one)");
  if (value_col < 0) throw InputError(a.values + ": no '" + a.column + "' column to paint (--column names it)");

  const TriangleSoup soup = load_meshes(a.meshes, a.lod, a.quiet);
  const std::size_t nt = soup.triangle_count();
  std::vector<double> sum(nt, 0.0);
  std::vector<std::size_t> count(nt, 0);
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const double f = table.number(r, face_col);
    if (!(f >= 0) || f != std::floor(f) || f >= double(nt))
      throw InputError(table.where(r) + ": face " + table.text(r, face_col) + " is not a triangle index of the meshes (" +
                       std::to_string(nt) + " triangles: give the meshes as to points facades)");
    const double v = table.number(r, value_col);
    sum[std::size_t(f)] += v;
    ++count[std::size_t(f)];
  }
  std::vector<float> values(nt, kNoData);
  std::size_t painted = 0;
  double lo = 1e300, hi = -1e300;
  for (std::size_t t = 0; t < nt; ++t)
    if (count[t] > 0) {
      values[t] = float(sum[t] / double(count[t]));
      lo = std::min(lo, double(values[t])), hi = std::max(hi, double(values[t]));
      ++painted;
    }
  if (painted == 0) throw InputError(a.values + ": no rows: nothing to paint");
  // Fractions use the map's rounded range; other quantities (W/m², hours) their exact range.
  double c_lo = lo, c_hi = hi;
  if (lo >= 0 && hi <= 1)
    map_range(values, kNoData, c_lo, c_hi);
  else if (!(c_hi > c_lo))
    c_hi = c_lo + 1;
  std::vector<std::array<std::uint8_t, 3>> rgb(nt, std::array<std::uint8_t, 3>{200, 200, 200});
  for (std::size_t t = 0; t < nt; ++t)
    if (count[t] > 0) {
      const Rgb8 c = viridis((values[t] - c_lo) / (c_hi - c_lo));
      rgb[t] = {c.r, c.g, c.b};
    }
  FaceValuesPly ply;
  ply.soup = &soup;
  ply.values = values;
  ply.rgb = rgb;
  ply.comments = {
      "skyband " SKYBAND_VERSION ": face values of column '" + a.column + "' of " + a.values,
      "value = mean over the face's points; nodata " + fixed(kNoData) + " (faces without points, light grey)",
      "colour = viridis over [" + fixed(c_lo) + ", " + fixed(c_hi) + "]; values range [" + fixed(lo) + ", " + fixed(hi) + "]"};
  std::string command = invocation();
  std::replace(command.begin(), command.end(), '\n', ' ');
  std::replace(command.begin(), command.end(), '\r', ' ');
  ply.comments.push_back("command: " + command);
  write_face_values_ply(a.out, ply);
  write_provenance(a.out, inputs);
  if (!a.quiet)
    std::fprintf(stderr, "paint: %zu of %zu faces painted from %zu points ('%s' from %s to %s); wrote %s\n", painted, nt,
                 table.rows.size(), a.column.c_str(), fixed(lo).c_str(), fixed(hi).c_str(), a.out.c_str());
}

CommandRegistration registration{
    "paint", [](CLI::App& app) {
      auto args = std::make_shared<PaintArgs>();
      CLI::App* cmd = app.add_subcommand(
          "paint",
          "Results on the model: the meshes written as PLY with each face's value (the mean of its points') and\n"
          "colour, from a points file with a face column (skyband points facades, then svf or irradiance).");
      cmd->add_option("--mesh", args->meshes, "Mesh or city model file, as given to points facades (repeatable)");
      cmd->add_option("--lod", args->lod, "City models read at this LoD, as for points facades");
      cmd->add_option("--values", args->values, "Points CSV with a face column and the values");
      cmd->add_option("--column", args->column, "The column to paint (default svf)");
      cmd->add_option("--out", args->out, "Output PLY (binary), written atomically");
      cmd->add_flag("--quiet", args->quiet, "No report on stderr");
      cmd->callback([args] { run(*args); });
      return cmd;
    }};

}  // namespace

}  // namespace skyband::cli
