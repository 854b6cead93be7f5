#include "examples/obstructed_fisheye.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "geometry/horizon_profile.h"
#include "geometry/sky_visibility.h"
#include "io/png_writer.h"

namespace skyband::cli {

namespace {

constexpr double kPi = 3.14159265358979323846;

// 5 × 7 glyphs of the compass letters, rows top to bottom, bit 4 the leftmost column.
constexpr std::array<std::uint8_t, 7> kGlyphN{0b10001, 0b11001, 0b10101, 0b10011, 0b10001, 0b10001, 0b10001};
constexpr std::array<std::uint8_t, 7> kGlyphE{0b11111, 0b10000, 0b10000, 0b11110, 0b10000, 0b10000, 0b11111};
constexpr std::array<std::uint8_t, 7> kGlyphS{0b01111, 0b10000, 0b10000, 0b01110, 0b00001, 0b00001, 0b11110};
constexpr std::array<std::uint8_t, 7> kGlyphW{0b10001, 0b10001, 0b10001, 0b10101, 0b10101, 0b10101, 0b01010};

void put(std::vector<std::uint8_t>& img, int size, int col, int row, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  if (col < 0 || row < 0 || col >= size || row >= size) return;
  std::uint8_t* p = &img[(std::size_t(row) * std::size_t(size) + std::size_t(col)) * 3];
  p[0] = r, p[1] = g, p[2] = b;
}

// A glyph centred on (cx, cy), white on a black outline, `scale` pixels per glyph pixel.
void glyph(std::vector<std::uint8_t>& img, int size, const std::array<std::uint8_t, 7>& g, int cx, int cy, int scale) {
  const int x0 = cx - 5 * scale / 2, y0 = cy - 7 * scale / 2;
  for (int pass = 0; pass < 2; ++pass)
    for (int r = 0; r < 7; ++r)
      for (int c = 0; c < 5; ++c) {
        if (!(g[std::size_t(r)] & (1 << (4 - c)))) continue;
        for (int dy = 0; dy < scale; ++dy)
          for (int dx = 0; dx < scale; ++dx) {
            const int x = x0 + c * scale + dx, y = y0 + r * scale + dy;
            if (pass == 0) {
              for (int oy = -1; oy <= 1; ++oy)
                for (int ox = -1; ox <= 1; ++ox) put(img, size, x + ox, y + oy, 0, 0, 0);
            } else {
              put(img, size, x, y, 255, 255, 255);
            }
          }
      }
}

}  // namespace

bool fisheye_direction(int size, int col, int row, Vec3& d) {
  const double u = 2.0 * (col + 0.5) / size - 1.0;  // right
  const double v = 1.0 - 2.0 * (row + 0.5) / size;  // up
  const double r = std::hypot(u, v);
  if (r >= 1.0) return false;
  const double zen = r * 0.5 * kPi;
  const double az = std::atan2(-u, v);  // north up, east left
  d = Vec3(std::sin(az) * std::sin(zen), std::cos(az) * std::sin(zen), std::cos(zen));
  return true;
}

ObstructedFisheye render_obstructed_fisheye(const Scene& scene, const QueryPoint& q, int size,
                                            const std::function<Vec3(const Vec3&)>& radiance_rgb, double exposure) {
  ObstructedFisheye f;
  f.size = size;
  const std::size_t n = std::size_t(size) * std::size_t(size);
  f.sky_rgb.assign(n * 3, 0.0f);
  f.visible_rgb.assign(n * 3, 0.0f);
  SkyVisibility vis(scene, VisibilityOptions{}, SkyFactorsMethod::automatic);
  const VisibleSky& sky = vis.compute(q, true);
  f.svf = sky.factors.svf, f.sky_exposure = sky.factors.sky_exposure;
  std::vector<float> open_rgb(n * 3, 0.0f);  // the sky everywhere: the exposure is the open sky's
  std::vector<std::uint8_t> inside(n, 0), seen(n, 0);
  for (int row = 0; row < size; ++row)
    for (int col = 0; col < size; ++col) {
      Vec3 d;
      if (!fisheye_direction(size, col, row, d)) continue;
      const std::size_t i = std::size_t(row) * std::size_t(size) + std::size_t(col);
      inside[i] = 1;
      ++f.sky_pixels;
      const Vec3 rgb = radiance_rgb(d);
      for (int c = 0; c < 3; ++c) open_rgb[i * 3 + std::size_t(c)] = float(rgb[c]);
      if (vis.direction_visible(q, d)) {
        seen[i] = 1;
        ++f.visible_pixels;
        for (int c = 0; c < 3; ++c) f.sky_rgb[i * 3 + std::size_t(c)] = float(rgb[c]), f.visible_rgb[i * 3 + std::size_t(c)] = 1.0f;
      }
    }
  const double ex = exposure > 0 ? exposure : auto_exposure(open_rgb);
  f.picture.assign(n * 3, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!inside[i]) continue;
    for (int c = 0; c < 3; ++c) {
      const double display = tone_map_channel(open_rgb[i * 3 + std::size_t(c)], ex);
      // Hidden: a third of the sky's value in grey, so the sky behind stays legible.
      const double grey = 0.30 + 0.25 * display;
      f.picture[i * 3 + std::size_t(c)] = std::uint8_t(std::lround(255.0 * (seen[i] ? display : grey * 0.8)));
    }
  }
  // The exact horizon (normal up), every 0.25°.
  constexpr double kStep = 0.25;
  const QueryPoint up{q.position, Vec3(0, 0, 1)};
  for_each_horizon_profile(scene, std::span<const QueryPoint>(&up, 1), VisibilityOptions{}, kStep, 1, {},
                           [&](std::size_t, std::size_t, std::span<const double> e) {
                             for (std::size_t k = 0; k < e.size(); ++k) {
                               if (!(e[k] > 0)) continue;
                               const double az = double(k) * kStep * kPi / 180.0, r = (90.0 - e[k]) / 90.0;
                               const double u = -std::sin(az) * r, v = std::cos(az) * r;  // east left
                               const int col = int(std::floor((u + 1.0) * 0.5 * size)), row = int(std::floor((1.0 - v) * 0.5 * size));
                               for (int dy = 0; dy <= size / 256; ++dy)
                                 for (int dx = 0; dx <= size / 256; ++dx) put(f.picture, size, col + dx, row + dy, 230, 30, 30);
                             }
                           });
  const int scale = std::max(1, size / 128), m = 6 * scale;
  glyph(f.picture, size, kGlyphN, size / 2, m, scale);
  glyph(f.picture, size, kGlyphS, size / 2, size - m, scale);
  glyph(f.picture, size, kGlyphE, m, size / 2, scale);
  glyph(f.picture, size, kGlyphW, size - m, size / 2, scale);
  return f;
}

}  // namespace skyband::cli
