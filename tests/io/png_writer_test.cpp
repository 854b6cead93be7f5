#define BOOST_TEST_MODULE png_writer
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <limits>

#include "geometry/core/input_error.h"
#include "io/png_writer.h"

namespace tt = boost::test_tools;
namespace fs = std::filesystem;
using namespace skyband;

namespace {
fs::path temp_dir() {
  const fs::path d = fs::path(SKYBAND_BINARY_DIR) / "test_output" / "png_writer";
  fs::create_directories(d);
  return d;
}
}  // namespace

BOOST_AUTO_TEST_CASE(srgb_oetf_published_points) {
  // IEC 61966-2-1: linear 0.5 → 0.7354 (8-bit 188); the linear segment 12.92·x below 0.0031308;
  // 1 → 1. Four-decimal reference → 1e-4.
  BOOST_TEST(std::abs(srgb_oetf(0.5) - 0.7354) < 1e-4);
  BOOST_TEST(srgb_oetf(0.002) == 12.92 * 0.002, tt::tolerance(1e-12));
  BOOST_TEST(srgb_oetf(1.0) == 1.0, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(tone_curve_hand_values) {
  // By hand: x = 1 → ACES (2.51 + 0.03)/(2.43 + 0.59 + 0.14) = 2.54/3.16 = 0.803797;
  // OETF 1.055·0.803797^(1/2.4) − 0.055 = 0.90823 → byte round(231.60) = 232.
  BOOST_TEST(std::abs(tone_map_channel(1.0, 1.0) - 0.90823) < 2e-5);
  BOOST_TEST(std::abs(tone_map_channel(0.25, 4.0) - 0.90823) < 2e-5);   // exposure scales first
  BOOST_TEST(tone_map_channel(-3.0, 1.0) == 0.0);                       // negatives clamp to 0
  BOOST_TEST(tone_map_channel(1e9, 1.0) == 1.0, tt::tolerance(1e-12));  // saturates (rounding of 1.055 − 0.055)
}

BOOST_AUTO_TEST_CASE(auto_exposure_log_average) {
  // Two grey pixels of luminance 1 and 4 (log-average 2) and one black pixel (ignored):
  // exposure = 0.18/2 = 0.09 (Reinhard key). Grey: R = G = B = Y exactly (luma weights sum to 1).
  const std::vector<float> rgb = {1, 1, 1, 4, 4, 4, 0, 0, 0};
  BOOST_TEST(auto_exposure(rgb) == 0.09, tt::tolerance(1e-6));
  BOOST_TEST(auto_exposure(std::vector<float>{0, 0, 0}) == 1.0);
  BOOST_CHECK_THROW(auto_exposure(std::vector<float>{1, std::numeric_limits<float>::quiet_NaN(), 1}), InputError);
}

BOOST_AUTO_TEST_CASE(png_round_trip_with_libpng) {
  const int w = 5, h = 3;
  std::vector<float> rgb(static_cast<std::size_t>(w * h * 3));
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<float>(0.05 * static_cast<double>(i));
  const fs::path p = temp_dir() / "round.png";
  const double exposure = 0.7;
  write_png_srgb(p, w, h, rgb, exposure);
  const PngImage img = read_png_rgb8(p);
  BOOST_TEST(img.width == w);
  BOOST_TEST(img.height == h);
  BOOST_REQUIRE_EQUAL(img.rgb.size(), rgb.size());
  // Each byte must be the tone curve of its value, rounded (the file is lossless).
  for (std::size_t i = 0; i < rgb.size(); ++i)
    BOOST_TEST(static_cast<int>(img.rgb[i]) == static_cast<int>(std::lround(255.0 * tone_map_channel(rgb[i], exposure))));
}

BOOST_AUTO_TEST_CASE(png_bad_input_throws_and_writes_nothing) {
  const fs::path p = temp_dir() / "bad.png";
  fs::remove(p);
  std::vector<float> rgb(12, 1.0f);
  rgb[5] = std::numeric_limits<float>::infinity();
  BOOST_CHECK_THROW(write_png_srgb(p, 2, 2, rgb, 1.0), InputError);
  BOOST_TEST(!fs::exists(p));
  rgb[5] = 1.0f;
  BOOST_CHECK_THROW(write_png_srgb(p, 2, 2, rgb, 0.0), InputError);
  BOOST_CHECK_THROW(write_png_srgb(p, 3, 2, rgb, 1.0), InputError);
  BOOST_TEST(!fs::exists(p));
  BOOST_CHECK_THROW(read_png_rgb8(temp_dir() / "missing.png"), InputError);
}
