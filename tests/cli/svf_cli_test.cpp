#define BOOST_TEST_MODULE svf_cli
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/support/cli_runner.h"
#include "shared_data.h"

namespace tt = boost::test_tools;
namespace fs = std::filesystem;
using skyband::test::run_skyband;

namespace {

std::string q(const fs::path& p) {
  return skyband::test::shell_quote(p);
}
void write_cube(const fs::path& file) {
  skyband::test::write_cube_obj(file);
}
using skyband::test::slurp;

}  // namespace

// End to end: rows in input order, pass-through columns kept, svf/sky_exposure appended.
// Closed forms: on the cube's top face SVF = 1 and exposure 1; inside 0; open ground far away
// (500 m, the cube subtends < 3e-4 of the sky there: reference-notes §5 rectangle formula) ≈ 1;
// an open wall facing away from the cube: 0.5.
BOOST_AUTO_TEST_CASE(end_to_end_values_and_pass_through) {
  const fs::path d = skyband::test::test_folder("svf_cli_e2e");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "id,x,y,z,nx,ny,nz,note\n"
                                  "a,5,5,10,0,0,1,\"top, centre\"\n"
                                  "b,5,5,5,0,0,1,inside\n"
                                  "c,500,500,0,0,0,1,far\n"
                                  "d,-20,5,3,-1,0,0,wall facing west\n";
  const auto r = run_skyband("svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --out " + q(d / "out.csv") +
                             " --threads 2");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  std::istringstream out(slurp(d / "out.csv"));
  std::string line;
  std::getline(out, line);
  BOOST_TEST(line == "id,x,y,z,nx,ny,nz,note,svf,sky_exposure");
  std::vector<std::pair<double, double>> v;
  std::vector<std::string> ids;
  while (std::getline(out, line)) {
    ids.push_back(line.substr(0, 1));
    const auto last = line.rfind(','), prev = line.rfind(',', last - 1);
    v.emplace_back(std::stod(line.substr(prev + 1, last - prev - 1)), std::stod(line.substr(last + 1)));
  }
  BOOST_TEST_REQUIRE(v.size() == 4u);
  BOOST_TEST((ids == std::vector<std::string>{"a", "b", "c", "d"}));
  BOOST_TEST(v[0].first == 1.0, tt::tolerance(1e-12));
  BOOST_TEST(v[0].second == 1.0, tt::tolerance(1e-6));
  BOOST_TEST(v[1].first == 0.0);
  BOOST_TEST(v[1].second == 0.0);
  BOOST_TEST(v[2].first > 0.9997);
  BOOST_TEST(v[3].first == 0.5, tt::tolerance(1e-9));
  BOOST_TEST(v[3].second == 0.5, tt::tolerance(1e-6));
  BOOST_TEST(slurp(d / "out.csv").find("\"top, centre\"") != std::string::npos);
}

// --method bands with --bands N (the paper's fixed bands) or --tolerance T, and the default exact
// horizon, all agree with the closed form within their errors.
BOOST_AUTO_TEST_CASE(bands_and_tolerance_options) {
  const fs::path d = skyband::test::test_folder("svf_cli_opts");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "x,y,z\n15,5,0\n";
  for (const std::string opt : {"--method bands --bands 256", "--method bands --tolerance 1e-5", "", "--method auto"}) {
    const auto r = run_skyband("svf --quiet --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --out " +
                               q(d / "o.csv") + " " + opt);
    BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
    const std::string text = slurp(d / "o.csv");
    const auto nl = text.find('\n');
    const std::string row = text.substr(nl + 1);
    const double svf = std::stod(row.substr(row.find(',', row.find(',', row.find(',') + 1) + 1) + 1));
    // Closed form (reference-notes §5, element to a perpendicular rectangle): the point (15, 5, 0)
    // sees only the cube's face x = 10, two rectangles w = 5 (along y) × h = 10 at c = 5 with the
    // foot of the perpendicular at their common corner: X = h/w = 2, Y = c/w = 1,
    // F = 2·(1/2π)[atan(1/Y) − Y/√(X²+Y²)·atan(1/√(X²+Y²))] = 0.190136, SVF = 1 − F.
    const double X = 2, Y = 1, rho = std::sqrt(X * X + Y * Y);
    const double expected = 1 - 2 * (std::atan(1 / Y) - Y / rho * std::atan(1 / rho)) / (2 * M_PI);
    // 256 fixed bands: O(1/N²) here (no cube edge is parallel to the axis), measured 5e-7. The
    // exact horizon (the default): rounding only, and the 1 µm surface offset (dSVF/dz ~ 1e-2/m).
    const bool exact = opt.find("bands") == std::string::npos;
    BOOST_TEST(svf == expected, tt::tolerance(exact ? 1e-7 : 1e-5));
  }
}

// Bad input: one line naming the file/line/flag and the value, exit code 2, no output file left.
BOOST_AUTO_TEST_CASE(bad_input_errors) {
  const fs::path d = skyband::test::test_folder("svf_cli_errors");
  write_cube(d / "cube.obj");
  std::ofstream(d / "ok.csv") << "x,y,z\n1,2,3\n";
  std::ofstream(d / "badnum.csv") << "x,y,z\n1,2,3\n4,five,6\n";
  std::ofstream(d / "zero_normal.csv") << "x,y,z,nx,ny,nz\n1,2,3,0,0,0\n";
  std::ofstream(d / "nan.obj") << "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(d / "badindex.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
  const std::string out = " --out " + q(d / "out.csv");
  skyband::test::check_bad_input(
      {
          {"svf --mesh " + q(d / "missing.obj") + " --points " + q(d / "ok.csv") + out, "missing.obj"},
          {"svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "absent.csv") + out, "absent.csv"},
          {"svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "badnum.csv") + out, "five"},
          {"svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "zero_normal.csv") + out, "zero_normal.csv"},
          {"svf --mesh " + q(d / "nan.obj") + " --points " + q(d / "ok.csv") + out, "nan.obj"},
          {"svf --mesh " + q(d / "badindex.obj") + " --points " + q(d / "ok.csv") + out, "7"},
          {"svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "ok.csv") + out + " --bands 0", "--bands"},
          {"svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "ok.csv") + out + " --tolerance -1", "--tolerance"},
          {"svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "ok.csv") + out + " --threads -3", "--threads"},
          {"svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "ok.csv") + out + " --method best", "--method"},
          {"svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "ok.csv") + " --out " + q(d / "no_such_dir" / "o.csv"),
           "no_such_dir"},
      },
      d / "out.csv");
}

// The default method reports which points it computed exactly: the cube on no ground is a column
// scene, so a point beside it goes by the exact horizon, one inside it by the exact union of the
// occluders' projections.
BOOST_AUTO_TEST_CASE(method_summary_on_stderr) {
  const fs::path d = skyband::test::test_folder("svf_cli_method");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "x,y,z\n15,5,0\n5,5,5\n";
  const auto r = run_skyband("svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --out " + q(d / "o.csv"));
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(
      r.err.find("1 point exact by the horizon of closed buildings, 1 point exact by the union of the occluders' projections") !=
          std::string::npos,
      r.err);
  const std::string text = slurp(d / "o.csv");
  BOOST_TEST(text.substr(text.rfind('\n', text.size() - 2) + 1) == "5,5,5,0,0\n");  // inside: nothing seen
}

// The built-in demo prints its table.
BOOST_AUTO_TEST_CASE(demo_runs) {
  const auto r = run_skyband("svf --demo");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.out.find("street centre") != std::string::npos);
  BOOST_TEST(r.out.find("roof of the tower") != std::string::npos);
}

// --horizon: the rows of every point's profile in input order; beside the 10 m cube at (15, 5, 0)
// the cube's east face at x = 10, 5 m away and 10 m high, makes the horizon
// atan((10 − 1e-6)/5) = 63.434947° due west (azimuth 270°, clockwise from north; the point is
// evaluated 1 µm above the ground), and nothing stands east (90°): 0°. Inside the cube the profile is 90° all round. A bad step
// (outside [0.01°, 360°]: a finer one would write over 36,000 rows per point) is an error before
// any work.
BOOST_AUTO_TEST_CASE(horizon_profiles) {
  const fs::path d = skyband::test::test_folder("svf_cli_horizon");
  write_cube(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "x,y,z\n15,5,0\n5,5,5\n";
  const auto r = run_skyband("svf --quiet --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --out " +
                             q(d / "o.csv") + " --horizon " + q(d / "h.csv") + " --horizon-step 90");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(slurp(d / "h.csv") ==
             "point,azimuth_deg,elevation_deg\n"
             "0,0,0.000000\n0,90,0.000000\n0,180,0.000000\n0,270,63.434947\n"
             "1,0,90.000000\n1,90,90.000000\n1,180,90.000000\n1,270,90.000000\n");
  for (const char* step : {"0", "-1", "400", "nan", "1e-6", "0.009"}) {
    const auto bad = run_skyband("svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --out " +
                                 q(d / "o2.csv") + " --horizon " + q(d / "h2.csv") + " --horizon-step " + step);
    BOOST_TEST(bad.exit_code == 2, bad.err);
    BOOST_TEST(bad.err.find("--horizon-step") != std::string::npos, bad.err);
    BOOST_TEST(!fs::exists(d / "h2.csv"));
    BOOST_TEST(!fs::exists(d / "o2.csv"));
  }
}

namespace {

const fs::path kFuzzFound = fs::path(SKYBAND_SHARED_DATA) / "fuzz-found";

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::size_t count_of(const std::string& s, char c) {
  return static_cast<std::size_t>(std::count(s.begin(), s.end(), c));
}

}  // namespace

// The mesh files fuzzing found (../shared/data/fuzz-found/README.md) through the CLI: files that
// can cost seconds and gigabytes in a naive reader (OFF through OpenMesh, PLY headers declaring
// 4·10⁹ empty entries). Each ends at once (< 2 s expected, 10 s asserted against a hang),
// with exit 0 and the output, or exit 2 and one line naming the file.
// Expected exits: the files' faces are valid (see tests/io/mesh_reader_test.cpp), except
// ply_empty_element.ply, which has neither vertices nor faces.
BOOST_AUTO_TEST_CASE(fuzz_found_meshes_end_at_once, *skyband::test::needs_shared_data()) {
  const fs::path d = skyband::test::test_folder("svf_cli_fuzz_found");
  std::ofstream(d / "pts.csv") << "x,y,z\n0.2,0.2,5\n";
  const std::vector<std::pair<std::string, int>> cases{
      {"off_comment_after_header.off", 0}, {"off_face_extra_value_minus1.off", 0},  {"off_face_loop_oom.off", 0},
      {"ply_empty_element.ply", 2},        {"ply_empty_element_huge_count.ply", 0}, {"ply_three_empty_elements.ply", 0},
  };
  for (const auto& [file, exit_code] : cases) {
    BOOST_TEST_CONTEXT(file) {
      const fs::path out = d / (file + ".csv");
      const auto t0 = std::chrono::steady_clock::now();
      const auto r =
          run_skyband("svf --quiet --mesh " + q(kFuzzFound / file) + " --points " + q(d / "pts.csv") + " --out " + q(out));
      BOOST_TEST(seconds_since(t0) < 10.0);
      BOOST_TEST(r.exit_code == exit_code, r.err);
      if (exit_code == 0) {
        BOOST_TEST(slurp(out).starts_with("x,y,z,svf,sky_exposure\n0.2,0.2,5,"), slurp(out));
      } else {
        BOOST_TEST(r.err.starts_with("skyband: error: " + (kFuzzFound / file).string() + ": "), r.err);
        BOOST_TEST(r.err.find("neither a vertex nor a face element") != std::string::npos, r.err);
        BOOST_TEST(count_of(r.err, '\n') == 1u, r.err);
        BOOST_TEST(!fs::exists(out));
      }
    }
  }
}

// The points files fuzzing found: a pass-through first header cell that begins with U+FEFF
// (after the file's own byte-order mark, or after a blank line) is written quoted, so it keeps
// its name when the output is read back (expected bytes: tests/io/points_csv_test.cpp).
BOOST_AUTO_TEST_CASE(fuzz_found_points_keep_their_first_column_name, *skyband::test::needs_shared_data()) {
  const fs::path d = skyband::test::test_folder("svf_cli_fuzz_found_points");
  write_cube(d / "cube.obj");
  for (const char* file : {"points_roundtrip_double_bom.csv", "points_roundtrip_bom_after_blank_line.csv"}) {
    const fs::path out = d / (std::string(file) + ".out.csv");
    const auto r =
        run_skyband("svf --quiet --mesh " + q(d / "cube.obj") + " --points " + q(kFuzzFound / file) + " --out " + q(out));
    BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
    BOOST_TEST(slurp(out).starts_with("\"\xEF\xBB\xBFid\",x,y,z,svf,sky_exposure\na,0,0,1,"), file);
  }
}

// Whatever a message quotes, the CLI prints one line: a line break inside a quoted cell and a NUL
// byte are escaped, and the text after the NUL is there (what() is a C string: the reader escapes
// the value before it goes into the message).
BOOST_AUTO_TEST_CASE(messages_are_one_whole_line) {
  const fs::path d = skyband::test::test_folder("svf_cli_message_lines");
  write_cube(d / "cube.obj");
  std::ofstream(d / "lf.csv") << "x,y,z\n1,\"2\n5\",3\n";
  std::ofstream(d / "nul.csv", std::ios::binary) << std::string("x,y,z\n1,2\0x,3\n", 14);
  const std::string base = "svf --quiet --mesh " + q(d / "cube.obj") + " --out " + q(d / "out.csv") + " --points ";
  const auto lf = run_skyband(base + q(d / "lf.csv"));
  BOOST_TEST(lf.exit_code == 2);
  BOOST_TEST(lf.err == "skyband: error: " + (d / "lf.csv").string() + ":2: column 'y': value '2\\n5' is not a number\n");
  const auto nul = run_skyband(base + q(d / "nul.csv"));
  BOOST_TEST(nul.exit_code == 2);
  BOOST_TEST(nul.err == "skyband: error: " + (d / "nul.csv").string() + ":2: column 'y': value '2\\x00x' is not a number\n");
  BOOST_TEST(!fs::exists(d / "out.csv"));
}

// Output files and columns are checked before any work: --out equal to --points (the input
// stays as it was), an output column the input already has, --horizon into a missing folder.
BOOST_AUTO_TEST_CASE(outputs_are_checked_before_the_work) {
  const fs::path d = skyband::test::test_folder("svf_cli_outputs");
  write_cube(d / "cube.obj");
  const std::string points = "x,y,z,svf\n1,2,30,0.3\n";
  std::ofstream(d / "with_svf.csv") << points;
  std::ofstream(d / "ok.csv") << "x,y,z\n1,2,30\n";
  const std::string mesh = "svf --mesh " + q(d / "cube.obj");
  auto r = run_skyband(mesh + " --points " + q(d / "ok.csv") + " --out " + q(d / "ok.csv"));
  BOOST_TEST(r.exit_code == 2, r.err);
  BOOST_TEST(r.err.find("is the --points file; writing it would overwrite the input") != std::string::npos, r.err);
  BOOST_TEST(slurp(d / "ok.csv") == "x,y,z\n1,2,30\n");
  r = run_skyband(mesh + " --points " + q(d / "with_svf.csv") + " --out " + q(d / "o.csv"));
  BOOST_TEST(r.exit_code == 2, r.err);
  BOOST_TEST(r.err.find("output column 'svf' already exists in the points file") != std::string::npos, r.err);
  BOOST_TEST(!fs::exists(d / "o.csv"));
  r = run_skyband(mesh + " --points " + q(d / "ok.csv") + " --out " + q(d / "o.csv") + " --horizon " +
                  q(d / "missing" / "h.csv"));
  BOOST_TEST(r.exit_code == 2, r.err);
  BOOST_TEST(r.err.find("--horizon '") != std::string::npos, r.err);
  BOOST_TEST(!fs::exists(d / "o.csv"));
  r = run_skyband(mesh + " --points " + q(d / "ok.csv") + " --out " + q(d / "o.csv") + " --offset nan");
  BOOST_TEST(r.exit_code == 2, r.err);
}

// Point sanity: against a cube in projected metres (RD New-like coordinates), points given in
// degrees, with x and y swapped, far away, and 0.1 mm behind a wall they face each get a warning
// naming their lines; the job still runs. --offset 0.1 moves the point behind the east wall to
// 0.1 m in front of it, where the wall's half-space hides the whole cube: SVF 0.5 exactly (an
// open vertical face), and the warning is gone.
BOOST_AUTO_TEST_CASE(point_sanity_warnings_and_offset) {
  const fs::path d = skyband::test::test_folder("svf_cli_point_sanity");
  {
    std::ofstream f(d / "cube_rd.obj");
    for (int i = 0; i < 8; ++i)
      f << "v " << (i & 1 ? 85010 : 85000) << ' ' << (i & 2 ? 446010 : 446000) << ' ' << (i & 4 ? 10 : 0) << '\n';
    f << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  }
  std::ofstream(d / "pts.csv") << "x,y,z,nx,ny,nz\n"
                                  "4.36,52.01,1,0,0,1\n"         // line 2: degrees
                                  "446005,85005,1,0,0,1\n"       // line 3: swapped
                                  "95000,446000,1,0,0,1\n"       // line 4: far away
                                  "85009.9999,446005,5,1,0,0\n"  // line 5: behind the east wall
                                  "85005,446005,10.5,0,0,1\n";   // line 6: above the roof, fine
  const std::string cmd = "svf --mesh " + q(d / "cube_rd.obj") + " --points " + q(d / "pts.csv") + " --out " + q(d / "o.csv");
  auto r = run_skyband(cmd + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("1 point of " + (d / "pts.csv").string() + " (line 2): coordinates like longitude/latitude") !=
                 std::string::npos,
             r.err);
  BOOST_TEST(r.err.find("(line 3): inside the model only with x and y swapped") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("(line 4): far outside the model's box") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("(line 5): a surface less than 1 cm in front along the normal") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("line 6") == std::string::npos, r.err);
  r = run_skyband(cmd + " --quiet --offset 0.1");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("1 cm in front") == std::string::npos, r.err);
  std::istringstream out(slurp(d / "o.csv"));
  std::string line;
  for (int i = 0; i < 5; ++i) std::getline(out, line);  // header + lines 2..5
  const auto last = line.rfind(','), prev = line.rfind(',', last - 1);
  BOOST_TEST(std::stod(line.substr(prev + 1, last - prev - 1)) == 0.5, tt::tolerance(1e-12));
  BOOST_TEST(line.starts_with("85009.9999,446005,5,"), line);  // the input's cells pass through unchanged
}

// --lod reads a city model at one LoD: the 3D BAG sample's BuildingParts give 460 triangles at
// their highest LoD (2.2) and 312 at LoD 1.2 — the reader's counts, which cityjson_reader_test
// (bag_v1_explicit_lod_selects_exactly_that_lod) checks against an independent walk of the JSON;
// here the flag must reach the reader. A LoD no object has, and --lod on a format without
// LoDs, are errors.
BOOST_AUTO_TEST_CASE(lod_selects_the_city_model_level, *skyband::test::needs_shared_data()) {
  const fs::path d = skyband::test::test_folder("svf_cli_lod");
  const fs::path bag = fs::path(SKYBAND_SHARED_DATA) / "cityjson" / "3dbag_v1_sample_denhaag.city.json";
  std::ofstream(d / "p.csv") << "x,y,z\n0,0,0\n";
  const std::string cmd = "svf --mesh " + q(bag) + " --points " + q(d / "p.csv") + " --out " + q(d / "o.csv");
  auto r = run_skyband(cmd);
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("460 triangles") != std::string::npos, r.err);
  r = run_skyband(cmd + " --lod 1.2");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("each object at LoD 1.2") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("312 triangles") != std::string::npos, r.err);
  r = run_skyband(cmd + " --lod 3");
  BOOST_TEST(r.exit_code == 2, r.err);
  BOOST_TEST(r.err.find("requested LoD 3") != std::string::npos, r.err);
  skyband::test::write_cube_obj(d / "cube.obj");
  r = run_skyband("svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "p.csv") + " --out " + q(d / "o.csv") + " --lod 2");
  BOOST_TEST(r.exit_code == 2, r.err);
  BOOST_TEST(r.err.find("applies to city models") != std::string::npos, r.err);
}

// Beside the CSV, <out>.provenance.json records the version, the command line as typed and each
// input file with its size in bytes (the file sizes checked against the filesystem).
BOOST_AUTO_TEST_CASE(provenance_beside_the_output) {
  const fs::path d = skyband::test::test_folder("svf_cli_provenance");
  write_cube(d / "cube.obj");
  std::ofstream(d / "p.csv") << "x,y,z\n5,5,10\n";
  const std::string cmd = "svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "p.csv") + " --out " + q(d / "o.csv");
  const auto r = run_skyband(cmd + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  const std::string text = slurp(d / "o.csv.provenance.json");
  const nlohmann::json j = nlohmann::json::parse(text);
  BOOST_TEST(j.at("output").get<std::string>() == (d / "o.csv").string());
  BOOST_TEST(j.at("command_line").get<std::string>().find("svf --mesh") != std::string::npos);
  BOOST_TEST(!j.at("skyband_version").get<std::string>().empty());
  BOOST_TEST_REQUIRE(j.at("inputs").size() == 2u);
  BOOST_TEST(j["inputs"][0]["flag"].get<std::string>() == "--points");
  BOOST_TEST(j["inputs"][0]["bytes"].get<std::uintmax_t>() == fs::file_size(d / "p.csv"));
  BOOST_TEST(j["inputs"][1]["path"].get<std::string>() == (d / "cube.obj").string());
  BOOST_TEST(j["inputs"][1]["bytes"].get<std::uintmax_t>() == fs::file_size(d / "cube.obj"));
  BOOST_TEST(j.at("written_utc").get<std::string>().ends_with("Z"));
}

// Command-line errors have the form of every other error — one line "skyband: error: ...",
// exit code 2 — with a suggestion for a flag or command within a few edits of a known one.
BOOST_AUTO_TEST_CASE(parse_errors_suggest_the_flag) {
  auto r = run_skyband("svf --pionts p.csv");
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(r.err.starts_with("skyband: error: "), r.err);
  BOOST_TEST(r.err.find("(did you mean --points?)") != std::string::npos, r.err);
  BOOST_TEST(std::count(r.err.begin(), r.err.end(), '\n') == 1, r.err);
  r = run_skyband("svff");
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(r.err.find("(did you mean 'svf'?)") != std::string::npos, r.err);
  r = run_skyband("svf --threads abc");
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(r.err.find("see skyband svf --help") != std::string::npos, r.err);
  r = run_skyband("svf --help");
  BOOST_TEST(r.exit_code == 0);
}

// A point exactly on its wall, facing out of it, is not "behind a surface": no warning.
BOOST_AUTO_TEST_CASE(points_on_their_wall_get_no_warning) {
  const fs::path d = skyband::test::test_folder("svf_cli_on_wall");
  write_cube(d / "cube.obj");
  std::ofstream(d / "p.csv") << "x,y,z,nx,ny,nz\n10,5,5,1,0,0\n5,0,3,0,-1,0\n";
  const auto r =
      run_skyband("svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "p.csv") + " --out " + q(d / "o.csv") + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("warning") == std::string::npos, r.err);
}
