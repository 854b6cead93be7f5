#pragma once
// Multi-layer linear OpenEXR images (scanline, ZIP compression) with string header attributes
// for provenance. Each layer is an RGB triple of channels named "<layer>.R", "<layer>.G",
// "<layer>.B" (OpenEXR's layer naming convention; an empty layer name gives plain "R", "G", "B").
// Pixels are row-major, top row first, interleaved RGB (width·height·3 floats), in whatever
// linear unit the caller states in an attribute (skyband writes a "units" attribute).
// Writing is atomic (io/atomic_file.h). NaN or infinite values, or values that overflow half
// precision, never reach the file: they throw InputError naming the layer and pixel.
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace skyband {

struct ImageLayer {
  std::string name;
  std::vector<float> rgb;  // width·height·3, row-major, top row first
};

enum class ExrPixelType { Half, Float };

void write_exr(const std::filesystem::path& path, int width, int height, std::span<const ImageLayer> layers,
               const std::map<std::string, std::string>& attributes, ExrPixelType pixel_type = ExrPixelType::Float);

struct ExrImage {
  int width = 0, height = 0;
  std::vector<ImageLayer> layers;                 // layers with complete R, G, B channels, sorted by name
  std::map<std::string, std::string> attributes;  // every string attribute of the header
};

// Reads every RGB layer as float (half channels are converted). Throws InputError naming the
// file on any read error.
ExrImage read_exr_layers(const std::filesystem::path& path);

}  // namespace skyband
