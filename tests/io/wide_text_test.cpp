#define BOOST_TEST_MODULE wide_text
#include <boost/test/unit_test.hpp>

// Text in UTF-16 or UTF-32 (what Windows tools save as "Unicode") is refused by every text reader
// up front, in one line naming the file and the encoding and how to convert it, instead of a
// format error about the zero bytes ("not XML", "row has 1 cells", "NUL byte"). Binary formats
// are not affected: a binary STL whose header is zeros still reads.

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <unistd.h>

#include "input_error_of.h"
#include "io/cityjson_reader.h"
#include "io/epw_reader.h"
#include "io/mesh_reader.h"
#include "io/points_csv.h"
#include "io/tmy3_reader.h"
#include "io/utf8_text.h"

using namespace skyband;
namespace fs = std::filesystem;

namespace {

// UTF-16 or UTF-32 of an ASCII text, little or big endian, with or without a byte-order mark.
std::string wide(const std::string& ascii, int bytes, bool big_endian, bool bom) {
  std::string out;
  const auto unit = [&](std::uint32_t c) {
    for (int k = 0; k < bytes; ++k) {
      const int shift = 8 * (big_endian ? bytes - 1 - k : k);
      out += static_cast<char>((c >> shift) & 0xFF);
    }
  };
  if (bom) unit(0xFEFF);
  for (const char c : ascii) unit(static_cast<unsigned char>(c));
  return out;
}

const fs::path& folder() {
  static const fs::path d = fs::temp_directory_path() / ("skyband_wide_text_test_" + std::to_string(::getpid()));
  return d;
}

fs::path write(const std::string& name, const std::string& bytes) {
  const fs::path& d = folder();
  fs::create_directories(d);
  const fs::path p = d / name;
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

}  // namespace

BOOST_AUTO_TEST_CASE(encodings_are_told_from_the_first_bytes) {
  for (const bool big : {false, true})
    for (const bool bom : {false, true}) {
      BOOST_TEST(wide_text_encoding(wide("x,y,z\n", 2, big, bom)) == "UTF-16");
      BOOST_TEST(wide_text_encoding(wide("x,y,z\n", 4, big, bom)) == "UTF-32");
    }
  for (const std::string plain : {"x,y,z\n", "\xEF\xBB\xBFx,y,z\n", "", "v", "\x01\x02\xff", "f\xC3\xA7"})
    BOOST_TEST(wide_text_encoding(plain).empty(), plain);
  // Zero bytes inside UTF-8 text are not UTF-16 (a quoted CSV cell of zero bytes, as a points file
  // written back quotes it: a fuzzer's round trip): the first units must all look like text.
  BOOST_TEST(wide_text_encoding(std::string("\"\0\0\xfc\xff\xff\xff\xff\xff"
                                            "D",
                                            10))
                 .empty());
  BOOST_TEST(wide_text_encoding(std::string("\"\0x\0", 4)) == "UTF-16");  // all a short text has
  // After a UTF-8 byte-order mark (as a reader strips it, so that a round trip agrees).
  BOOST_TEST(wide_text_encoding("\xEF\xBB\xBF" + wide("x,y", 2, false, true)) == "UTF-16");
}

BOOST_AUTO_TEST_CASE(every_text_reader_names_the_encoding) {
  const std::string csv = "x,y,z\n1,2,3\n";
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const std::string gml = "<?xml version=\"1.0\" encoding=\"UTF-16\"?>\n<core:CityModel/>\n";
  const std::string json = "{\"type\": \"CityJSON\"}\n";
  const std::string epw = "LOCATION,Testville,ST,XYZ,synthetic,012345,40.0,-105.0,-7.0,1600.0\n";
  struct Case {
    std::string name, text;
    std::function<void(const fs::path&)> read;
  };
  const std::vector<Case> cases = {
      {"points.csv", csv, [](const fs::path& p) { read_points_csv(p); }},
      {"mesh.obj", obj, [](const fs::path& p) { read_mesh(p); }},
      {"mesh.off", off, [](const fs::path& p) { read_mesh(p); }},
      {"model.gml", gml, [](const fs::path& p) { read_mesh(p); }},
      {"model.city.json", json, [](const fs::path& p) { read_cityjson(p); }},
      {"model.city.jsonl", json, [](const fs::path& p) { read_cityjson(p); }},
      {"weather.epw", epw, [](const fs::path& p) { read_epw(p); }},
      {"weather.csv", csv, [](const fs::path& p) { read_weather_file(p); }},
      {"tmy3.csv", csv, [](const fs::path& p) { read_tmy3_csv(p); }},
  };
  for (const Case& c : cases)
    for (const int bytes : {2, 4}) {
      const fs::path p = write(std::to_string(bytes) + "_" + c.name, wide(c.text, bytes, false, true));
      const std::string e = test::error_of([&] { c.read(p); });
      const std::string encoding = bytes == 2 ? "UTF-16" : "UTF-32";
      BOOST_TEST(e.find(p.string() + ": " + encoding + " text") == 0u, c.name << ": " << e);
      BOOST_TEST(e.find("iconv -f " + encoding + " -t UTF-8") != std::string::npos, e);
      BOOST_TEST(e.find('\n') == std::string::npos, e);
    }
}

BOOST_AUTO_TEST_CASE(a_binary_stl_with_a_zero_header_still_reads) {
  std::string stl(80, '\0');
  const std::uint32_t n = 1;
  stl.append(reinterpret_cast<const char*>(&n), 4);
  const float data[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
  stl.append(reinterpret_cast<const char*>(data), sizeof data);
  stl.append(2, '\0');
  BOOST_TEST(read_mesh(write("zeros.stl", stl)).triangle_count() == 1u);
}

BOOST_AUTO_TEST_CASE(cleanup) {
  fs::remove_all(folder());
}
