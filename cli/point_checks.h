#pragma once
// Checks of a per-point job's files and points before and around the work (`skyband svf`,
// `skyband irradiance`): what users of such tools lose hours to when nothing says it.
//
// Before any work (InputError, exit code 2):
//   - an output file whose folder does not exist or is not writable, that is an existing
//     folder, or that is one of the input files (`--out` equal to `--points` would overwrite
//     the input);
//   - an output column that already exists in the points file.
// Around the work (warnings on stderr with counts and the first rows; the job still runs):
//   - points outside the scene's box by more than a margin (a quarter of the box's larger
//     horizontal side plus 10 m): they see the scene, if at all, from far away;
//   - points that look like longitude/latitude (|x| ≤ 180, |y| ≤ 90) against a model in
//     projected metres (a box beyond ±1000 m), or whose x and y are swapped (the swapped
//     point lies in the box, the given one does not): both get an open sky silently;
//   - points within 1 cm of a surface in front of them (along their normal): a facade point
//     just behind its wall (coordinates rounded, the normal reversed) sees almost no sky.
//     `--offset D` moves every point D metres along its normal.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "geometry/mesh/scene.h"
#include "io/points_csv.h"

namespace skyband::cli {

// `flag` names the option in messages ("--out"); `inputs` are the (flag, path) pairs of the
// files the job reads.
void check_output_file(const std::string& flag, const std::string& path,
                       const std::vector<std::pair<std::string, std::string>>& inputs);

// The output columns must not repeat an input column (names compared after trimming spaces).
void check_output_columns(const std::string& out, const PointsTable& table, const std::vector<std::string>& columns);

// Moves every point `offset` metres along its (unit) normal, in place.
void offset_points(PointsTable& table, double offset);

// What warn_about_points found: counts and the input lines of the first few rows of each kind.
struct PointWarnings {
  std::size_t outside = 0, geographic = 0, swapped = 0, behind_surface = 0;
  std::vector<std::size_t> outside_lines, geographic_lines, swapped_lines, behind_lines;  // ≤ 5 each
};

// The warnings' findings (pure: no output).
PointWarnings find_point_warnings(const Scene& scene, const PointsTable& table);

// Prints one line per kind found to stderr, prefixed with `command` ("svf").
void print_point_warnings(const std::string& command, const PointWarnings& w, const std::string& points_file);

}  // namespace skyband::cli
