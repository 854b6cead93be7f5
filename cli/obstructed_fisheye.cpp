#include "cli/obstructed_fisheye.h"

#include "cli/bitmap_font.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "geometry/horizon/horizon_profile.h"
#include "geometry/visibility/sky_visibility.h"
#include "io/png_writer.h"

namespace skyband::cli {

namespace {

constexpr double kPi = 3.14159265358979323846;

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
                                            const std::function<Vec3(const Vec3&)>& radiance_rgb, double exposure,
                                            std::span<const SunPathMark> sun_path) {
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
        for (int c = 0; c < 3; ++c)
          f.sky_rgb[i * 3 + std::size_t(c)] = float(rgb[c]), f.visible_rgb[i * 3 + std::size_t(c)] = 1.0f;
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
  Picture pic(size, size, Rgb8{});
  pic.rgb = std::move(f.picture);
  // Picture position of a direction above the horizon (equi-angular, north up, east left).
  const auto position = [size](double azimuth_rad, double elevation_deg, int& col, int& row) {
    const double r = (90.0 - elevation_deg) / 90.0;
    const double u = -std::sin(azimuth_rad) * r, v = std::cos(azimuth_rad) * r;
    col = int(std::floor((u + 1.0) * 0.5 * size));
    row = int(std::floor((1.0 - v) * 0.5 * size));
  };
  // The exact horizon (normal up), every 0.25°.
  constexpr double kStep = 0.25;
  const QueryPoint up{q.position, Vec3(0, 0, 1)};
  const int dot = size / 256;
  for_each_horizon_profile(scene, std::span<const QueryPoint>(&up, 1), VisibilityOptions{}, kStep, 1, {},
                           [&](std::size_t, std::size_t, std::span<const double> e) {
                             for (std::size_t k = 0; k < e.size(); ++k) {
                               if (!(e[k] > 0)) continue;
                               int col = 0, row = 0;
                               position(double(k) * kStep * kPi / 180.0, e[k], col, row);
                               pic.fill_rect(col, row, col + dot + 1, row + dot + 1, Rgb8{230, 30, 30});
                             }
                           });
  // The sun's path: seen yellow, hidden dark orange.
  for (const SunPathMark& m : sun_path) {
    if (!(m.direction.z() > 0)) continue;
    ++f.sun_marks_up;
    const bool seen = vis.direction_visible(q, m.direction);
    if (seen) ++f.sun_marks_seen;
    const double elevation = std::asin(std::min(1.0, m.direction.z())) * 180.0 / kPi;
    int col = 0, row = 0;
    position(std::atan2(m.direction.x(), m.direction.y()), elevation, col, row);
    const int r = (m.hour ? 3 : 1) * std::max(1, size / 512);
    const Rgb8 c = seen ? Rgb8{255, 220, 0} : Rgb8{150, 80, 0};
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx)
        if (dx * dx + dy * dy <= r * r) pic.put(col + dx, row + dy, c);
  }
  // N, E, S, W at the rim (east left), white on black.
  const int scale = std::max(1, size / 128), m = 6 * scale;
  const Rgb8 white{255, 255, 255}, black{0, 0, 0};
  const auto label = [&](const char* t, int cx, int cy) {
    draw_text(pic, cx - text_width(t, scale) / 2, cy - text_height(scale) / 2, t, scale, white, &black);
  };
  label("N", size / 2, m);
  label("S", size / 2, size - m);
  label("E", m, size / 2);
  label("W", size - m, size / 2);
  f.picture = std::move(pic.rgb);
  return f;
}

}  // namespace skyband::cli
