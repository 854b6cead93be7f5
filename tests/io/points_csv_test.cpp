#define BOOST_TEST_MODULE points_csv
#include <boost/test/unit_test.hpp>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "geometry/core/input_error.h"
#include "io/points_csv.h"
#include "shared_data.h"

using namespace skyband;
namespace fs = std::filesystem;

namespace {

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("skyband_points_csv_test_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

fs::path write(const TempDir& d, const std::string& name, const std::string& text) {
  const fs::path p = d.path / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string error_of(const fs::path& p) {
  try {
    read_points_csv(p);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

}  // namespace

BOOST_AUTO_TEST_CASE(reads_points_with_default_normals_and_passes_columns_through) {
  TempDir d;
  // BOM, CR LF, a quoted field with a comma and an escaped quote, blank trailing lines.
  const fs::path f = write(d, "p.csv",
                           "\xEF\xBB\xBFid,x,y,z,label\r\n"
                           "a1,678040.189,5403913.006,414.907,\"wall, \"\"north\"\"\"\r\n"
                           "a2,1,2,3,plain\r\n\r\n\r\n");
  const PointsTable t = read_points_csv(f);
  BOOST_TEST(t.header == (std::vector<std::string>{"id", "x", "y", "z", "label"}));
  BOOST_REQUIRE_EQUAL(t.points.size(), 2u);
  // Verbatim doubles: the compiler's correctly rounded literals are the reference.
  BOOST_TEST(t.points[0].position.x() == 678040.189);
  BOOST_TEST(t.points[0].position.y() == 5403913.006);
  BOOST_TEST(t.points[0].position.z() == 414.907);
  BOOST_TEST(t.points[0].normal == Vec3(0, 0, 1));
  BOOST_TEST(t.rows[0][4] == "wall, \"north\"");
  BOOST_TEST(t.row_lines[1] == 3u);
}

BOOST_AUTO_TEST_CASE(normals_are_normalised) {
  TempDir d;
  const fs::path f = write(d, "n.csv", "x,y,z,nx,ny,nz\n0,0,0,3,0,4\n1,1,1, 0 ,-2, 0\n");
  const PointsTable t = read_points_csv(f);
  // (3, 0, 4)/5 exactly representable up to rounding of 3/5 and 4/5 (1 ulp).
  BOOST_TEST(std::abs(t.points[0].normal.x() - 0.6) <= 1e-16);
  BOOST_TEST(std::abs(t.points[0].normal.z() - 0.8) <= 1e-16);
  BOOST_TEST(t.points[1].normal == Vec3(0, -1, 0));
}

BOOST_AUTO_TEST_CASE(header_only_is_an_empty_table) {
  TempDir d;
  const PointsTable t = read_points_csv(write(d, "e.csv", "x,y,z\n"));
  BOOST_TEST(t.points.empty());
  BOOST_TEST(t.rows.empty());
}

BOOST_AUTO_TEST_CASE(errors_name_file_line_column_and_value) {
  TempDir d;
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases{
      {"id,x,y\n1,2,3\n", {"missing.csv:1:", "'z'", "missing"}},
      {"x,y,z\n1,2,3\n1,abc,3\n", {"missing.csv:3:", "column 'y'", "'abc'", "not a number"}},
      {"x,y,z\n1,2,inf\n", {"missing.csv:2:", "column 'z'", "non-finite", "'inf'"}},
      {"x,y,z\n1,2\n", {"missing.csv:2:", "2 cells", "3 columns"}},
      {"x,y,z\n1,2,3,4\n", {"missing.csv:2:", "4 cells"}},
      {"x,y,z,nx\n1,2,3,4\n", {"missing.csv:1:", "nx, ny, nz"}},
      {"x,y,z,nx,ny,nz\n1,2,3,0,0,0\n", {"missing.csv:2:", "normal (0, 0, 0)", "zero"}},
      {"x,y,z,x\n1,2,3,4\n", {"missing.csv:1:", "'x' appears twice"}},
      {"x,y,z\n1,2,\"3\n", {"missing.csv:2:", "never closed"}},
      {"x,y,z\n1,2,1e999\n", {"missing.csv:2:", "'1e999'", "out of the range"}},
      {"", {"missing.csv", "empty"}},
      // Spreadsheet exports with another separator: named, not "column 'x' is missing".
      {"x;y;z\n1,5;2;3\n", {"missing.csv:1:", "'x;y;z' is one column", "';'", "','"}},
      {"x\ty\tz\n1\t2\t3\n", {"missing.csv:1:", "is one column", "tabs"}},
  };
  for (const auto& [text, parts] : cases) {
    BOOST_TEST_CONTEXT(text) {
      const std::string message = error_of(write(d, "missing.csv", text));
      BOOST_TEST(!message.empty());
      for (const auto& p : parts) BOOST_TEST(contains(message, p), "'" << message << "' lacks '" << p << "'");
    }
  }
  BOOST_TEST(contains(error_of(d.path / "nope.csv"), "does not exist"));
}

BOOST_AUTO_TEST_CASE(write_round_trips_rows_and_numbers) {
  TempDir d;
  const fs::path in = write(d, "in.csv", "id,x,y,z,note\r\nA,1,2,3,\"a, b\"\r\nB,4,5,6,\r\n");
  const PointsTable t = read_points_csv(in);
  const double third = 1.0 / 3.0, tiny = 5e-324, big = 678040.18900000001;
  const fs::path out = d.path / "out.csv";
  write_points_csv(out, t, {"svf", "other"}, {{third, tiny}, {big, -0.0}});
  BOOST_TEST(slurp(out) == "id,x,y,z,note,svf,other\nA,1,2,3,\"a, b\",0.3333333333333333,678040.189\nB,4,5,6,,5e-324,-0\n");
  // Reading the output back gives the same numbers bit for bit (shortest round-trip form).
  const PointsTable back = read_points_csv(out);
  BOOST_TEST(back.rows[0][5] == "0.3333333333333333");
  BOOST_TEST(std::stod(back.rows[0][5]) == third);
  BOOST_TEST(back.rows[0][4] == "a, b");
  // No temporary file is left next to the output.
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(d.path)) ++files;
  BOOST_TEST(files == 2u);
}

BOOST_AUTO_TEST_CASE(write_rejects_bad_arguments_without_touching_the_target) {
  TempDir d;
  const PointsTable t = read_points_csv(write(d, "in.csv", "x,y,z\n1,2,3\n"));
  const fs::path out = d.path / "out.csv";
  BOOST_CHECK_THROW(write_points_csv(out, t, {"svf"}, {{0.5, 0.25}}), std::invalid_argument);
  BOOST_CHECK_THROW(write_points_csv(out, t, {"x"}, {{0.5}}), InputError);
  BOOST_TEST(!fs::exists(out));
  BOOST_CHECK_THROW(write_points_csv(d.path / "no_folder" / "out.csv", t, {"svf"}, {{0.5}}), InputError);
}

// The fuzzing findings (../shared/data/fuzz-found/README.md): a first header cell that itself
// begins with U+FEFF — after the file's own byte-order mark, or after a blank line — must not be
// written at byte 0, where it would be eaten as a byte-order mark on read-back. The expected header comes from the
// files' bytes: "EF BB BF EF BB BF id,x,y,z" (one mark stripped at byte 0, the second is data) and
// "CR LF EF BB BF id,x,y,z" (the mark is not at byte 0: data; the blank line is skipped).
BOOST_AUTO_TEST_CASE(fuzz_found_bom_headers_round_trip_exactly, *skyband::test::needs_shared_data()) {
  TempDir d;
  const fs::path found = fs::path(SKYBAND_SHARED_DATA) / "fuzz-found";
  for (const char* name : {"points_roundtrip_double_bom.csv", "points_roundtrip_bom_after_blank_line.csv"}) {
    BOOST_TEST_CONTEXT(name) {
      const PointsTable in = read_points_csv(found / name);
      BOOST_TEST(in.header == (std::vector<std::string>{"\xEF\xBB\xBFid", "x", "y", "z"}));
      BOOST_REQUIRE_EQUAL(in.rows.size(), 1u);
      const fs::path out = d.path / "out.csv", again = d.path / "again.csv";
      write_points_csv(out, in, {"svf"}, {{0.5}});
      // The cell at byte 0 is quoted, so its U+FEFF is not a byte-order mark.
      BOOST_TEST(slurp(out) == "\"\xEF\xBB\xBFid\",x,y,z,svf\na,0,0,1,0.5\n");
      const PointsTable back = read_points_csv(out);
      BOOST_TEST(back.header == (std::vector<std::string>{"\xEF\xBB\xBFid", "x", "y", "z", "svf"}));
      BOOST_TEST(back.rows[0] == (std::vector<std::string>{"a", "0", "0", "1", "0.5"}));
      BOOST_TEST(back.points[0].position == in.points[0].position);
      // Written again without the extra column: the same bytes as the first write's first four columns.
      PointsTable trimmed = back;
      trimmed.header.pop_back();
      for (auto& row : trimmed.rows) row.pop_back();
      write_points_csv(again, trimmed, {"svf"}, {{0.5}});
      BOOST_TEST(slurp(again) == slurp(out));
    }
  }
  // A cell beginning with U+FEFF anywhere but byte 0 needs no quotes; a plain first cell none.
  const PointsTable t = read_points_csv(write(d, "later.csv", "x,y,z,\xEF\xBB\xBFnote\n1,2,3,\xEF\xBB\xBF\n"));
  write_points_csv(d.path / "later_out.csv", t, {}, {});
  BOOST_TEST(slurp(d.path / "later_out.csv") == "x,y,z,\xEF\xBB\xBFnote\n1,2,3,\xEF\xBB\xBF\n");
}

// Values quoted in messages are printable: a NUL or a line break inside a cell is escaped, so
// the message is whole (what() is a C string) and one line.
BOOST_AUTO_TEST_CASE(messages_escape_control_characters_in_cells) {
  TempDir d;
  using namespace std::string_literals;
  const std::string nul = error_of(write(d, "nul.csv", "x,y,z\n1,2\0x,3\n"s));
  BOOST_TEST(contains(nul, "nul.csv:2: column 'y': value '2\\x00x' is not a number"), nul);
  const std::string lf = error_of(write(d, "lf.csv", "x,y,z\n1,\"2\n5\",3\n"));
  BOOST_TEST(contains(lf, "lf.csv:2: column 'y': value '2\\n5' is not a number"), lf);
}
