#include "geometry/points/point_order.h"

#include <algorithm>
#include <utility>

namespace skyband {

namespace {

// The 16 low bits of v spread to the even bits (bit k to bit 2k).
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0xffff;
  v = (v | (v << 8)) & 0x00ff00ffull;
  v = (v | (v << 4)) & 0x0f0f0f0full;
  v = (v | (v << 2)) & 0x33333333ull;
  v = (v | (v << 1)) & 0x55555555ull;
  return v;
}

}  // namespace

std::vector<std::uint32_t> xy_morton_order(std::span<const QueryPoint> points) {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double x = points[i].position.x(), y = points[i].position.y();
    if (i == 0) x0 = x1 = x, y0 = y1 = y;
    x0 = std::min(x0, x), x1 = std::max(x1, x);
    y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  const double sx = x1 > x0 ? 65535.0 / (x1 - x0) : 0.0, sy = y1 > y0 ? 65535.0 / (y1 - y0) : 0.0;
  const auto cell = [](double f) { return std::uint64_t(std::clamp(f, 0.0, 65535.0)); };  // NaN-free: finite input
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::uint64_t ix = cell((points[i].position.x() - x0) * sx), iy = cell((points[i].position.y() - y0) * sy);
    keyed[i] = {spread_bits(ix) | (spread_bits(iy) << 1), std::uint32_t(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order(points.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace skyband
