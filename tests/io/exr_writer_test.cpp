#define BOOST_TEST_MODULE exr_writer
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <limits>

#include "geometry/core/input_error.h"
#include "io/exr_writer.h"

namespace tt = boost::test_tools;
namespace fs = std::filesystem;
using namespace skyband;

namespace {
fs::path temp_dir() {
  const fs::path d = fs::path(SKYBAND_BINARY_DIR) / "test_output" / "exr_writer";
  fs::create_directories(d);
  return d;
}

std::vector<ImageLayer> make_layers(int w, int h) {
  ImageLayer a{"total", std::vector<float>(static_cast<std::size_t>(w * h * 3))};
  ImageLayer b{"sun_diffuse", std::vector<float>(static_cast<std::size_t>(w * h * 3))};
  for (std::size_t i = 0; i < a.rgb.size(); ++i) {
    a.rgb[i] = static_cast<float>(0.001 * static_cast<double>(i) * static_cast<double>(i) + 1e-3);  // spans 6 decades
    b.rgb[i] = static_cast<float>(std::sin(0.1 * static_cast<double>(i)));                          // includes negatives
  }
  return {a, b};
}
}  // namespace

BOOST_AUTO_TEST_CASE(float_round_trip_is_exact) {
  const int w = 7, h = 5;  // odd sizes catch stride mistakes
  const auto layers = make_layers(w, h);
  const fs::path p = temp_dir() / "float.exr";
  const std::map<std::string, std::string> attrs{{"skyband_version", "0.1.0"}, {"units", "W m-2 sr-1"}, {"sun", "alt 30 az 180"}};
  write_exr(p, w, h, layers, attrs, ExrPixelType::Float);
  const ExrImage img = read_exr_layers(p);
  BOOST_TEST(img.width == w);
  BOOST_TEST(img.height == h);
  BOOST_REQUIRE_EQUAL(img.layers.size(), 2u);
  // Layers come back sorted by name: sun_diffuse, total. Float storage is lossless (ZIP).
  BOOST_TEST(img.layers[0].name == "sun_diffuse");
  BOOST_TEST(img.layers[1].name == "total");
  BOOST_TEST(img.layers[0].rgb == layers[1].rgb, tt::per_element());
  BOOST_TEST(img.layers[1].rgb == layers[0].rgb, tt::per_element());
  for (const auto& [k, v] : attrs) BOOST_TEST(img.attributes.at(k) == v);
}

BOOST_AUTO_TEST_CASE(half_round_trip_within_half_precision) {
  const int w = 4, h = 3;
  const auto layers = make_layers(w, h);
  const fs::path p = temp_dir() / "half.exr";
  write_exr(p, w, h, layers, {}, ExrPixelType::Half);
  const ExrImage img = read_exr_layers(p);
  BOOST_REQUIRE_EQUAL(img.layers.size(), 2u);
  // Half has an 11-bit significand: round-to-nearest relative error ≤ 2⁻¹¹ ≈ 4.9e-4 (normal
  // range; our values ≥ 1e-3 are normal, |sin| values near 0 get an absolute 2⁻²⁵ check).
  for (std::size_t i = 0; i < layers[0].rgb.size(); ++i) {
    BOOST_TEST(img.layers[1].rgb[i] == layers[0].rgb[i], tt::tolerance(4.9e-4f));
    BOOST_TEST(std::abs(img.layers[0].rgb[i] - layers[1].rgb[i]) <= 4.9e-4f * std::abs(layers[1].rgb[i]) + 3e-8f);
  }
}

BOOST_AUTO_TEST_CASE(bad_values_never_reach_a_file) {
  const int w = 3, h = 2;
  auto layers = make_layers(w, h);
  const fs::path p = temp_dir() / "bad.exr";
  fs::remove(p);
  layers[1].rgb[7] = std::numeric_limits<float>::quiet_NaN();
  BOOST_CHECK_THROW(write_exr(p, w, h, layers, {}), InputError);
  BOOST_TEST(!fs::exists(p));
  layers[1].rgb[7] = std::numeric_limits<float>::infinity();
  BOOST_CHECK_THROW(write_exr(p, w, h, layers, {}), InputError);
  layers[1].rgb[7] = 1e6f;  // fine as float, overflows half (max 65504)
  BOOST_CHECK_NO_THROW(write_exr(p, w, h, layers, {}, ExrPixelType::Float));
  const auto before = fs::file_size(p);
  BOOST_CHECK_THROW(write_exr(p, w, h, layers, {}, ExrPixelType::Half), InputError);
  BOOST_TEST(fs::file_size(p) == before);  // the previous file is untouched
  // Wrong sizes, duplicate names, empty image, missing folder.
  auto short_layers = make_layers(w, h);
  short_layers[0].rgb.pop_back();
  BOOST_CHECK_THROW(write_exr(p, w, h, short_layers, {}), InputError);
  auto dup = make_layers(w, h);
  dup[1].name = dup[0].name;
  BOOST_CHECK_THROW(write_exr(p, w, h, dup, {}), InputError);
  BOOST_CHECK_THROW(write_exr(p, 0, h, make_layers(w, h), {}), InputError);
  BOOST_CHECK_THROW(write_exr(temp_dir() / "no_such_dir" / "x.exr", w, h, make_layers(w, h), {}), InputError);
  BOOST_CHECK_THROW(read_exr_layers(temp_dir() / "does_not_exist.exr"), InputError);
}
