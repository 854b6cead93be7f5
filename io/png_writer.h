#pragma once
// Tone-mapped 8-bit sRGB PNG previews of linear RGB images.
//
// Tone curve (per channel, documented so that a series of images can share one exposure):
//   1. negative values (out-of-gamut linear sRGB) are clamped to 0;
//   2. x ← exposure · x (exposure is explicit: pass the same value for every image of a series);
//   3. ACES filmic fit of K. Narkowicz (2015, "ACES Filmic Tone Mapping Curve"):
//        y = x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14), clamped to [0, 1];
//   4. sRGB OETF (IEC 61966-2-1): 12.92y for y ≤ 0.0031308, else 1.055·y^(1/2.4) − 0.055;
//   5. round to 8 bits.
// auto_exposure() gives the exposure that maps the log-average luminance of the image to the
// middle grey key 0.18 (Reinhard et al. 2002, "Photographic tone reproduction", eq. 1–2).
// Writing is atomic; NaN/Inf values or a non-positive/non-finite exposure throw InputError.
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace skyband {

// Tone curve steps 1–4 for one linear value; result in [0, 1].
double tone_map_channel(double linear, double exposure);
double srgb_oetf(double linear01);

// Exposure = 0.18 / exp(mean(ln Y)) over pixels with luminance Y = 0.2126R + 0.7152G + 0.0722B > 0
// (Rec. 709 luma weights; pixels with Y ≤ 0, e.g. outside a fisheye circle, are ignored).
// Returns 1 when no pixel has positive luminance. Throws InputError on NaN/Inf.
double auto_exposure(std::span<const float> rgb, double key = 0.18);

void write_png_srgb(const std::filesystem::path& path, int width, int height, std::span<const float> rgb, double exposure);

// 8-bit RGB as it is (display values, e.g. tone-mapped pixels with drawings over them), atomically.
void write_png_rgb8(const std::filesystem::path& path, int width, int height, std::span<const std::uint8_t> rgb);

struct PngImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // 8-bit sRGB, interleaved, top row first
};
PngImage read_png_rgb8(const std::filesystem::path& path);

}  // namespace skyband
