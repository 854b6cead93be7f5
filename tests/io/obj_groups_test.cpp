#define BOOST_TEST_MODULE obj_groups
#include <boost/test/unit_test.hpp>

// OBJ `o` and `g` lines become the triangles' objects (TriangleSoup::triangle_object), as
// CityObject ids do for CityJSON: what per-building work (facade orientation) groups by.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "io/mesh_reader.h"

using namespace skyband;
namespace fs = std::filesystem;

namespace {

fs::path write_obj(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("skyband_obj_groups_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

std::map<std::string, std::size_t> triangles_per_object(const TriangleSoup& s) {
  std::map<std::string, std::size_t> n;
  for (const std::uint32_t o : s.triangle_object) ++n[s.object_names.at(o)];
  return n;
}

const char* kVertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n";

}  // namespace

BOOST_AUTO_TEST_CASE(o_and_g_name_the_faces_objects) {
  // A quad (2 triangles) before any name, a triangle in object "house 1", a quad in group
  // "wall roof" (a group line listing two names), and a triangle back in "house 1".
  const std::string text = std::string(kVertices) + "f 1 2 3 4\no house 1\nf 1 2 5\ng wall roof\nf 1 2 3 4\no house 1\nf 2 3 5\n";
  for (const char* name : {"groups.obj"}) {
    const TriangleSoup s = read_mesh(write_obj(name, text));
    BOOST_TEST_REQUIRE(s.triangle_object.size() == s.triangle_count());
    BOOST_TEST((triangles_per_object(s) == std::map<std::string, std::size_t>{{"", 2}, {"house 1", 2}, {"wall roof", 2}}));
    BOOST_TEST(s.object_names.size() == 3u);
  }
  // No o or g: no objects at all.
  const TriangleSoup plain = read_mesh(write_obj("plain.obj", std::string(kVertices) + "f 1 2 3 4\n"));
  BOOST_TEST(plain.triangle_object.empty());
  BOOST_TEST(plain.object_names.empty());
}
