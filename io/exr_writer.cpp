#include "io/exr_writer.h"

#include <cmath>
#include <set>

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <half.h>

#include "geometry/core/input_error.h"
#include "io/atomic_file.h"

namespace skyband {

namespace {
constexpr const char* kChannelSuffix[3] = {"R", "G", "B"};
constexpr float kHalfMax = 65504.0f;  // largest finite IEEE half

std::string channel_name(const std::string& layer, int c) {
  return layer.empty() ? std::string(kChannelSuffix[c]) : layer + "." + kChannelSuffix[c];
}

void validate(const std::filesystem::path& path, int width, int height, std::span<const ImageLayer> layers, ExrPixelType type) {
  const std::string where = "EXR '" + path.string() + "': ";
  if (width <= 0 || height <= 0)
    throw InputError(where + "image size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
  if (layers.empty()) throw InputError(where + "no layers to write");
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3;
  std::set<std::string> names;
  for (const auto& l : layers) {
    if (!names.insert(l.name).second) throw InputError(where + "duplicate layer name '" + l.name + "'");
    if (l.rgb.size() != n)
      throw InputError(where + "layer '" + l.name + "' has " + std::to_string(l.rgb.size()) + " values, expected " +
                       std::to_string(n));
    for (std::size_t i = 0; i < n; ++i) {
      const float v = l.rgb[i];
      const bool bad = !std::isfinite(v) || (type == ExrPixelType::Half && std::abs(v) > kHalfMax);
      if (bad) {
        const std::size_t px = i / 3;
        throw InputError(where + "layer '" + l.name + "' pixel (" + std::to_string(px % static_cast<std::size_t>(width)) + ", " +
                         std::to_string(px / static_cast<std::size_t>(width)) + ") channel " + kChannelSuffix[i % 3] + " = " +
                         std::to_string(v) + (std::isfinite(v) ? " overflows half precision" : " is not finite"));
      }
    }
  }
}
}  // namespace

void write_exr(const std::filesystem::path& path, int width, int height, std::span<const ImageLayer> layers,
               const std::map<std::string, std::string>& attributes, ExrPixelType pixel_type) {
  validate(path, width, height, layers, pixel_type);
  const Imf::PixelType pt = pixel_type == ExrPixelType::Half ? Imf::HALF : Imf::FLOAT;
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3;

  // Half data is converted up front (OpenEXR takes the buffer in the file's pixel type).
  std::vector<std::vector<half>> half_data;
  if (pixel_type == ExrPixelType::Half) {
    half_data.resize(layers.size());
    for (std::size_t k = 0; k < layers.size(); ++k) {
      half_data[k].resize(n);
      for (std::size_t i = 0; i < n; ++i) half_data[k][i] = half(layers[k].rgb[i]);
    }
  }

  write_atomically(path, [&](const std::filesystem::path& temp) {
    try {
      Imf::Header header(width, height);
      header.compression() = Imf::ZIP_COMPRESSION;
      for (const auto& [key, value] : attributes) header.insert(key, Imf::StringAttribute(value));
      Imf::FrameBuffer fb;
      for (std::size_t k = 0; k < layers.size(); ++k) {
        const std::size_t elem = pixel_type == ExrPixelType::Half ? sizeof(half) : sizeof(float);
        char* base = pixel_type == ExrPixelType::Half ? reinterpret_cast<char*>(half_data[k].data())
                                                      : reinterpret_cast<char*>(const_cast<float*>(layers[k].rgb.data()));
        for (int c = 0; c < 3; ++c) {
          const std::string name = channel_name(layers[k].name, c);
          header.channels().insert(name, Imf::Channel(pt));
          fb.insert(name, Imf::Slice(pt, base + static_cast<std::size_t>(c) * elem, 3 * elem,
                                     3 * elem * static_cast<std::size_t>(width)));
        }
      }
      Imf::OutputFile file(temp.c_str(), header);
      file.setFrameBuffer(fb);
      file.writePixels(height);
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      throw InputError("cannot write EXR '" + path.string() + "': " + e.what());
    }
  });
}

ExrImage read_exr_layers(const std::filesystem::path& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i dw = header.dataWindow();
    ExrImage img;
    img.width = dw.max.x - dw.min.x + 1;
    img.height = dw.max.y - dw.min.y + 1;
    for (auto it = header.begin(); it != header.end(); ++it)
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) img.attributes[it.name()] = s->value();

    // Group channels by layer prefix.
    std::map<std::string, int> found;  // layer → bitmask of R, G, B
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
      const std::string name = it.name();
      const auto dot = name.rfind('.');
      const std::string layer = dot == std::string::npos ? std::string() : name.substr(0, dot);
      const std::string suffix = dot == std::string::npos ? name : name.substr(dot + 1);
      for (int c = 0; c < 3; ++c)
        if (suffix == kChannelSuffix[c]) found[layer] |= 1 << c;
    }
    const std::size_t n = static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) * 3;
    Imf::FrameBuffer fb;
    for (const auto& [layer, mask] : found) {
      if (mask != 7) continue;
      img.layers.push_back(ImageLayer{layer, std::vector<float>(n)});
    }
    for (auto& l : img.layers) {
      char* base = reinterpret_cast<char*>(l.rgb.data()) -
                   (static_cast<std::ptrdiff_t>(dw.min.x) + static_cast<std::ptrdiff_t>(dw.min.y) * img.width) * 3 *
                       static_cast<std::ptrdiff_t>(sizeof(float));
      for (int c = 0; c < 3; ++c)
        fb.insert(channel_name(l.name, c), Imf::Slice(Imf::FLOAT, base + c * sizeof(float), 3 * sizeof(float),
                                                      3 * sizeof(float) * static_cast<std::size_t>(img.width)));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return img;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError("cannot read EXR '" + path.string() + "': " + e.what());
  }
}

}  // namespace skyband
