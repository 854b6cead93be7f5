#include "cli/point_checks.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "geometry/core/input_error.h"
#include "io/csv_table.h"

namespace skyband::cli {

namespace fs = std::filesystem;

void check_output_file(const std::string& flag, const std::string& path,
                       const std::vector<std::pair<std::string, std::string>>& inputs) {
  const fs::path p(path);
  const std::string named = flag + " '" + path + "'";
  if (p.filename().empty()) throw InputError(named + ": names a folder, not a file");
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  std::error_code ec;  // the error_code forms: a name the system refuses (> 255 bytes) is the user's input
  const fs::file_status dir_status = fs::status(dir, ec);
  if (!fs::is_directory(dir_status))
    throw InputError(named + ": folder '" + dir.string() + "' " +
                     (ec && dir_status.type() != fs::file_type::not_found ? "cannot be used: " + ec.message()
                                                                          : std::string("does not exist")));
  if (::access(dir.c_str(), W_OK | X_OK) != 0) throw InputError(named + ": folder '" + dir.string() + "' is not writable");
  const fs::file_status status = fs::status(p, ec);
  if (fs::is_directory(status)) throw InputError(named + ": is a folder");
  if (!fs::exists(status)) return;
  for (const auto& [in_flag, in_path] : inputs) {
    std::error_code e2;
    if (!in_path.empty() && fs::equivalent(p, in_path, e2) && !e2)
      throw InputError(named + ": is the " + in_flag + " file; writing it would overwrite the input");
  }
}

void check_output_columns(const std::string& out, const PointsTable& table, const std::vector<std::string>& columns) {
  for (const std::string& c : columns)
    for (const std::string& h : table.header)
      if (trim_csv_cell(h) == trim_csv_cell(c))
        throw InputError("--out '" + out + "': output column '" + c + "' already exists in the points file '" +
                         table.file.string() + "' (rename or drop that column)");
}

void offset_points(PointsTable& table, double offset) {
  if (offset == 0) return;
  for (QueryPoint& q : table.points) q.position += offset * q.normal;
}

PointWarnings find_point_warnings(const Scene& scene, const PointsTable& table) {
  PointWarnings w;
  if (scene.soup().triangles.empty() || table.points.empty()) return w;
  const Aabb& box = scene.bounds();
  const double side = std::max(box.hi.x() - box.lo.x(), box.hi.y() - box.lo.y());
  const double margin = 0.25 * side + 10.0;  // metres
  const auto in_box_xy = [&](double x, double y, double m) {
    return x >= box.lo.x() - m && x <= box.hi.x() + m && y >= box.lo.y() - m && y <= box.hi.y() + m;
  };
  const bool projected_model =
      std::max({std::abs(box.lo.x()), std::abs(box.hi.x()), std::abs(box.lo.y()), std::abs(box.hi.y())}) > 1000.0;
  constexpr double kFrontDistance = 0.01;  // metres: "just behind a surface"
  const auto note = [](std::size_t& count, std::vector<std::size_t>& lines, std::size_t line) {
    ++count;
    if (lines.size() < 5) lines.push_back(line);
  };
  for (std::size_t i = 0; i < table.points.size(); ++i) {
    const QueryPoint& q = table.points[i];
    const std::size_t line = i < table.row_lines.size() ? table.row_lines[i] : i + 2;
    const double x = q.position.x(), y = q.position.y();
    const bool inside = in_box_xy(x, y, margin) && q.position.z() >= box.lo.z() - margin && q.position.z() <= box.hi.z() + margin;
    if (!inside) {
      if (projected_model && std::abs(x) <= 180 && std::abs(y) <= 90)
        note(w.geographic, w.geographic_lines, line);
      else if (in_box_xy(y, x, 0.0))
        note(w.swapped, w.swapped_lines, line);
      else
        note(w.outside, w.outside_lines, line);
      continue;
    }
    Ray ray;
    ray.origin = q.position;
    ray.direction = q.normal;
    // From where the job evaluates the point (its face's offset, 1 µm): the surface a point lies
    // on is not in front of it, however the rounding of its coordinates falls.
    ray.t_min = VisibilityOptions{}.surface_offset_m;
    ray.t_max = kFrontDistance;
    if (scene.intersect(ray)) note(w.behind_surface, w.behind_lines, line);
  }
  return w;
}

namespace {

std::string lines_text(const std::vector<std::size_t>& lines, std::size_t count) {
  std::string s;
  for (std::size_t l : lines) s += (s.empty() ? "" : ", ") + std::to_string(l);
  if (count > lines.size()) s += ", ...";
  return s;
}

}  // namespace

void print_point_warnings(const std::string& command, const PointWarnings& w, const std::string& points_file) {
  const auto say = [&](std::size_t n, const std::vector<std::size_t>& lines, const char* what) {
    if (n == 0) return;
    std::fprintf(stderr, "%s: warning: %zu point%s of %s (line%s %s): %s\n", command.c_str(), n, n == 1 ? "" : "s",
                 points_file.c_str(), lines.size() == 1 ? "" : "s", lines_text(lines, n).c_str(), what);
  };
  say(w.geographic, w.geographic_lines,
      "coordinates like longitude/latitude in degrees, but the model is in projected metres; reproject them to the "
      "model's CRS");
  say(w.swapped, w.swapped_lines, "inside the model only with x and y swapped; the x column should hold eastings");
  say(w.outside, w.outside_lines, "far outside the model's box (beyond it by more than a quarter of its size)");
  say(w.behind_surface, w.behind_lines,
      "a surface less than 1 cm in front along the normal (a point just behind its wall, or a reversed normal?); "
      "--offset D moves points D metres along their normals");
}

}  // namespace skyband::cli
