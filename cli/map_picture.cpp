#include "cli/map_picture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace skyband::cli {

namespace {

std::string fixed(double v, int digits) {
  char b[32];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

constexpr Rgb8 kNoData{200, 200, 200};
constexpr Rgb8 kBackground{255, 255, 255};
constexpr Rgb8 kInk{20, 20, 20};

}  // namespace

Rgb8 viridis(double t) {
  // matplotlib's viridis at t = 0, 1/8, ..., 1 (van der Walt and Smith 2015).
  static constexpr std::array<std::array<double, 3>, 9> kSamples{{{68, 1, 84},
                                                                  {71, 44, 122},
                                                                  {59, 81, 139},
                                                                  {44, 113, 142},
                                                                  {33, 144, 141},
                                                                  {39, 173, 129},
                                                                  {92, 200, 99},
                                                                  {170, 220, 50},
                                                                  {253, 231, 37}}};
  if (!(t > 0)) t = 0;  // NaN too
  if (t > 1) t = 1;
  const double s = t * 8;
  const std::size_t i = std::min<std::size_t>(std::size_t(s), 7);
  const double f = s - double(i);
  const auto mix = [&](int k) {
    return std::uint8_t(std::lround(kSamples[i][std::size_t(k)] * (1 - f) + kSamples[i + 1][std::size_t(k)] * f));
  };
  return {mix(0), mix(1), mix(2)};
}

void map_range(std::span<const float> values, float nodata, double& lo, double& hi) {
  lo = 1e300, hi = -1e300;
  for (const float v : values)
    if (v != nodata && std::isfinite(v)) lo = std::min(lo, double(v)), hi = std::max(hi, double(v));
  if (!(lo <= hi)) lo = 0, hi = 1;
  lo = std::floor(lo / 0.05 + 1e-9) * 0.05;
  hi = std::ceil(hi / 0.05 - 1e-9) * 0.05;
  lo = std::max(lo, 0.0);
  hi = std::min(hi, 1.0);
  if (!(hi > lo)) {
    if (hi >= 1.0)
      lo = hi - 0.05;
    else
      hi = lo + 0.05;
  }
}

Picture map_picture(const MapPictureInput& in) {
  double lo = 0, hi = 1;
  map_range(in.values, in.nodata, lo, hi);
  const std::size_t longest = std::max(in.columns, in.rows);
  const double target = std::clamp(double(longest), 400.0, 1600.0);
  const double zoom = target / double(longest);  // picture pixels per raster pixel
  const int mw = std::max(1, int(std::lround(double(in.columns) * zoom)));
  const int mh = std::max(1, int(std::lround(double(in.rows) * zoom)));
  const int margin = 16, legend_w = 260;
  const int h = std::max(mh + 2 * margin, 420);
  Picture p(mw + legend_w + 3 * margin, h, kBackground);

  double sum = 0, vmin = 1e300, vmax = -1e300;
  std::size_t n = 0;
  for (const float v : in.values)
    if (v != in.nodata && std::isfinite(v)) sum += v, ++n, vmin = std::min(vmin, double(v)), vmax = std::max(vmax, double(v));
  for (int y = 0; y < mh; ++y) {
    const std::size_t r = std::min(in.rows - 1, std::size_t(double(y) / zoom));
    for (int x = 0; x < mw; ++x) {
      const std::size_t c = std::min(in.columns - 1, std::size_t(double(x) / zoom));
      const float v = in.values[r * in.columns + c];
      p.put(margin + x, margin + y, v == in.nodata || !std::isfinite(v) ? kNoData : viridis((v - lo) / (hi - lo)));
    }
  }
  // North arrow: N over a small triangle, top-left of the map.
  const Rgb8 white{255, 255, 255}, black{0, 0, 0};
  draw_text(p, margin + 8, margin + 8, "N", 2, white, &black);
  for (int k = 0; k < 8; ++k) p.fill_rect(margin + 13 - k / 2, margin + 26 + k, margin + 15 + k / 2, margin + 27 + k, white);

  // Legend.
  const int lx = margin * 2 + mw;
  int y = margin;
  draw_text(p, lx, y, in.quantity, 2, kInk);
  y += text_height(2) + 6;
  draw_text(p, lx, y, in.units, 1, kInk);
  y += text_height(1) + 14;
  const int bar_top = y, bar_h = std::max(160, std::min(mh - 140, 360)), bar_w = 28;
  for (int k = 0; k < bar_h; ++k)
    p.fill_rect(lx, bar_top + k, lx + bar_w, bar_top + k + 1, viridis(1.0 - double(k) / double(bar_h - 1)));
  // Ticks at multiples of the smallest of 0.05, 0.1, 0.2, 0.25, 0.5 that gives at most 6 of them.
  double step = 0.5;
  for (const double s : {0.25, 0.2, 0.1, 0.05})
    if ((hi - lo) / s <= 5.0 + 1e-9) step = s;
  for (long k = long(std::ceil(lo / step - 1e-9)); double(k) * step <= hi + 1e-9; ++k) {
    const double f = (double(k) * step - lo) / (hi - lo);
    const int ty = bar_top + int(std::lround((1 - f) * (bar_h - 1)));
    p.fill_rect(lx + bar_w, ty, lx + bar_w + 6, ty + 1, kInk);
    draw_text(p, lx + bar_w + 10, ty - 7, fixed(double(k) * step, 2), 2, kInk);
  }
  y = bar_top + bar_h + 16;
  p.fill_rect(lx, y, lx + bar_w, y + 14, kNoData);
  draw_text(p, lx + bar_w + 10, y, "NO DATA", 2, kInk);
  y += 30;
  if (in.pixel_m > 0) {
    draw_text(p, lx, y, "PIXEL " + fixed(in.pixel_m, in.pixel_m < 1 ? 2 : 1) + " M", 1, kInk);
    y += text_height(1) + 6;
  }
  if (n > 0) {
    draw_text(p, lx, y, "MIN " + fixed(vmin, 3) + "  MEAN " + fixed(sum / double(n), 3) + "  MAX " + fixed(vmax, 3), 1, kInk);
    y += text_height(1) + 6;
  }
  return p;
}

}  // namespace skyband::cli
