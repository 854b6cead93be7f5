#include "io/png_writer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <png.h>

#include "geometry/core/input_error.h"
#include "io/atomic_file.h"

namespace skyband {

double srgb_oetf(double y) {
  y = std::clamp(y, 0.0, 1.0);
  return y <= 0.0031308 ? 12.92 * y : 1.055 * std::pow(y, 1.0 / 2.4) - 0.055;
}

double tone_map_channel(double linear, double exposure) {
  const double x = std::max(0.0, linear) * exposure;
  const double aces = std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
  return srgb_oetf(aces);
}

namespace {
void check_finite(std::span<const float> rgb, const std::string& what) {
  for (std::size_t i = 0; i < rgb.size(); ++i)
    if (!std::isfinite(rgb[i]))
      throw InputError(what + ": value " + std::to_string(i / 3) + "." + "RGB"[i % 3] + " = " + std::to_string(rgb[i]) +
                       " is not finite");
}
}  // namespace

double auto_exposure(std::span<const float> rgb, double key) {
  check_finite(rgb, "auto exposure");
  double sum_log = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) {
    const double y = 0.2126 * rgb[i] + 0.7152 * rgb[i + 1] + 0.0722 * rgb[i + 2];
    if (y > 0) {
      sum_log += std::log(y);
      ++count;
    }
  }
  if (count == 0) return 1.0;
  return key / std::exp(sum_log / static_cast<double>(count));
}

void write_png_srgb(const std::filesystem::path& path, int width, int height, std::span<const float> rgb, double exposure) {
  const std::string where = "PNG '" + path.string() + "'";
  if (width <= 0 || height <= 0)
    throw InputError(where + ": image size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3;
  if (rgb.size() != n) throw InputError(where + ": " + std::to_string(rgb.size()) + " values, expected " + std::to_string(n));
  if (!(exposure > 0) || !std::isfinite(exposure))
    throw InputError(where + ": exposure " + std::to_string(exposure) + " must be finite and > 0");
  check_finite(rgb, where);
  std::vector<std::uint8_t> bytes(n);
  for (std::size_t i = 0; i < n; ++i)
    bytes[i] = static_cast<std::uint8_t>(std::lround(255.0 * tone_map_channel(rgb[i], exposure)));
  write_png_rgb8(path, width, height, bytes);
}

void write_png_rgb8(const std::filesystem::path& path, int width, int height, std::span<const std::uint8_t> bytes) {
  const std::string where = "PNG '" + path.string() + "'";
  if (width <= 0 || height <= 0)
    throw InputError(where + ": image size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3;
  if (bytes.size() != n) throw InputError(where + ": " + std::to_string(bytes.size()) + " bytes, expected " + std::to_string(n));
  write_atomically(path, [&](const std::filesystem::path& temp) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = static_cast<png_uint_32>(width);
    image.height = static_cast<png_uint_32>(height);
    image.format = PNG_FORMAT_RGB;
    if (!png_image_write_to_file(&image, temp.c_str(), 0, bytes.data(), 0, nullptr)) {
      const std::string msg = image.message;
      png_image_free(&image);
      throw InputError("cannot write " + where + ": " + msg);
    }
  });
}

PngImage read_png_rgb8(const std::filesystem::path& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str()))
    throw InputError("cannot read PNG '" + path.string() + "': " + image.message);
  image.format = PNG_FORMAT_RGB;
  PngImage out;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr)) {
    const std::string msg = image.message;
    png_image_free(&image);
    throw InputError("cannot read PNG '" + path.string() + "': " + msg);
  }
  return out;
}

}  // namespace skyband
