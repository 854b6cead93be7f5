#include "geometry/mesh/height_field.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "geometry/core/input_error.h"

namespace skyband {

namespace {

void check_field(const HeightField& f) {
  if (f.columns == 0 || f.rows == 0) throw InputError("height field: no pixels");
  if (f.heights.size() != f.columns * f.rows)
    throw InputError("height field: " + std::to_string(f.heights.size()) + " heights for " + std::to_string(f.columns) + " × " +
                     std::to_string(f.rows) + " pixels");
  if (!std::isfinite(f.dx) || !std::isfinite(f.dy) || f.dx == 0 || f.dy == 0 || !std::isfinite(f.x0) || !std::isfinite(f.y0))
    throw InputError("height field: pixel steps " + std::to_string(f.dx) + ", " + std::to_string(f.dy) + " or origin " +
                     std::to_string(f.x0) + ", " + std::to_string(f.y0) + " not finite and non-zero");
  for (std::size_t i = 0; i < f.heights.size(); ++i)
    if (std::isinf(f.heights[i]))
      throw InputError("height field: pixel (column " + std::to_string(i % f.columns) + ", row " + std::to_string(i / f.columns) +
                       ") has an infinite height");
}

// The vertices of the mesh: at each corner, one per distinct height among the pixels around it
// (and the floor where one of them has no height or lies outside the field), in ascending order.
class CornerVertices {
 public:
  CornerVertices(const HeightField& f, double floor_z, TriangleSoup& soup) : f_(f), cols_(f.columns + 1) {
    const std::size_t corners = cols_ * (f.rows + 1);
    start_.assign(corners + 1, 0);
    std::array<double, 5> h;
    for (std::size_t k = 0; k < corners; ++k) {
      const std::size_t n = heights_at(k, floor_z, h);
      start_[k + 1] = start_[k] + std::uint32_t(n);
    }
    heights_.resize(start_[corners]);
    soup.vertices.reserve(heights_.size());
    for (std::size_t k = 0; k < corners; ++k) {
      const std::size_t n = heights_at(k, floor_z, h);
      const double x = f.corner_x(k % cols_), y = f.corner_y(k / cols_);
      for (std::size_t i = 0; i < n; ++i) {
        heights_[start_[k] + i] = h[i];
        soup.vertices.emplace_back(x, y, h[i]);
      }
    }
  }

  std::size_t corner(std::size_t c, std::size_t r) const { return r * cols_ + c; }
  // The vertex of corner k at height z (z must be one of its heights).
  std::uint32_t at(std::size_t k, double z) const {
    std::uint32_t i = start_[k];
    while (heights_[i] != z) ++i;
    return i;
  }
  // Corner k's heights in [lo, hi], ascending, as vertex ids.
  void between(std::size_t k, double lo, double hi, std::vector<std::uint32_t>& out) const {
    out.clear();
    for (std::uint32_t i = start_[k]; i < start_[k + 1]; ++i)
      if (heights_[i] >= lo && heights_[i] <= hi) out.push_back(i);
  }
  double height_of(std::uint32_t v) const { return heights_[v]; }

 private:
  // Distinct heights around corner k, sorted; returns their number (≤ 5).
  std::size_t heights_at(std::size_t k, double floor_z, std::array<double, 5>& h) const {
    const std::size_t c = k % cols_, r = k / cols_;
    std::size_t n = 0;
    bool floor = false;
    for (int dr = -1; dr <= 0; ++dr)
      for (int dc = -1; dc <= 0; ++dc) {
        const long pc = long(c) + dc, pr = long(r) + dr;
        if (pc < 0 || pr < 0 || pc >= long(f_.columns) || pr >= long(f_.rows)) {
          floor = true;
          continue;
        }
        const double z = f_.height(std::size_t(pc), std::size_t(pr));
        if (std::isnan(z))
          floor = true;
        else
          h[n++] = z;
      }
    if (floor) h[n++] = floor_z;
    // Insertion sort of the n ≤ 5 heights: the result std::sort gives for so few (its final
    // insertion sort, strict <, stable), written out because GCC 12's -Warray-bounds cannot see
    // n ≤ 5 through std::sort's other branches at -O3.
    for (std::size_t i = 1; i < n; ++i)
      for (std::size_t j = i; j > 0 && h[j] < h[j - 1]; --j) std::swap(h[j], h[j - 1]);
    return std::size_t(std::unique(h.begin(), h.begin() + long(n)) - h.begin());
  }

  const HeightField& f_;
  std::size_t cols_;
  std::vector<std::uint32_t> start_;
  std::vector<double> heights_;
};

}  // namespace

double height_field_floor(const HeightField& field) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const double h : field.heights)
    if (std::isfinite(h)) {
      lo = std::min(lo, h);
      hi = std::max(hi, h);
    }
  if (!(lo <= hi)) throw InputError("height field: no pixel has a height (all nodata)");
  return lo - std::max(1.0, 0.01 * (hi - lo));
}

TriangleSoup height_field_mesh(const HeightField& f, double floor_z) {
  check_field(f);
  if (!std::isfinite(floor_z)) throw InputError("height field: floor height not finite");
  for (const double h : f.heights)
    if (!(std::isnan(h) || h > floor_z))
      throw InputError("height field: floor " + std::to_string(floor_z) + " m is not below the height " + std::to_string(h) +
                       " m");
  TriangleSoup soup;
  soup.material_names = {"top", "wall"};
  const CornerVertices v(f, floor_z, soup);
  const bool ccw = f.dx * f.dy > 0;  // corners (c, r) → (c+1, r) → (c+1, r+1) turn counter-clockwise
  const auto height_or_floor = [&](long c, long r) {
    if (c < 0 || r < 0 || c >= long(f.columns) || r >= long(f.rows)) return floor_z;
    const double z = f.height(std::size_t(c), std::size_t(r));
    return std::isnan(z) ? floor_z : z;
  };
  std::vector<std::uint32_t> left, right;
  // The wall along the pixel side from corner k1 to corner k2 between heights lo < hi, facing
  // direction (sx, sy) (the lower side): wound so that its normal (e_y, −e_x), e = k2 − k1,
  // points that way — with k1 on the left of the strip, every triangle (L_i, R_j, next) has it.
  const auto wall = [&](std::size_t k1, std::size_t k2, double lo, double hi, double ex, double ey, double sx, double sy) {
    if (ey * sx - ex * sy < 0) std::swap(k1, k2);
    v.between(k1, lo, hi, left);
    v.between(k2, lo, hi, right);
    std::size_t i = 0, j = 0;
    while (i + 1 < left.size() || j + 1 < right.size()) {
      const bool up_left =
          j + 1 == right.size() || (i + 1 < left.size() && v.height_of(left[i + 1]) <= v.height_of(right[j + 1]));
      if (up_left) {
        soup.triangles.push_back({left[i], right[j], left[i + 1]});
        ++i;
      } else {
        soup.triangles.push_back({left[i], right[j], right[j + 1]});
        ++j;
      }
      soup.triangle_material.push_back(1);
    }
  };
  for (std::size_t r = 0; r < f.rows; ++r)
    for (std::size_t c = 0; c < f.columns; ++c) {
      const double h = f.height(c, r);
      if (std::isnan(h)) continue;
      const std::uint32_t a = v.at(v.corner(c, r), h), b = v.at(v.corner(c + 1, r), h), d = v.at(v.corner(c + 1, r + 1), h),
                          e = v.at(v.corner(c, r + 1), h);
      if (ccw) {
        soup.triangles.push_back({a, b, d});
        soup.triangles.push_back({a, d, e});
      } else {
        soup.triangles.push_back({a, d, b});
        soup.triangles.push_back({a, e, d});
      }
      soup.triangle_material.insert(soup.triangle_material.end(), 2, 0);
      const long lc = long(c), lr = long(r);
      // The four sides: (neighbour column, row), the side's corners, its direction e and the
      // direction towards the neighbour.
      struct Side {
        long nc, nr;
        std::size_t k1, k2;
        double ex, ey, sx, sy;
      };
      const Side sides[4] = {
          {lc + 1, lr, v.corner(c + 1, r), v.corner(c + 1, r + 1), 0, f.dy, f.dx, 0},
          {lc - 1, lr, v.corner(c, r), v.corner(c, r + 1), 0, f.dy, -f.dx, 0},
          {lc, lr + 1, v.corner(c, r + 1), v.corner(c + 1, r + 1), f.dx, 0, 0, f.dy},
          {lc, lr - 1, v.corner(c, r), v.corner(c + 1, r), f.dx, 0, 0, -f.dy},
      };
      for (const Side& s : sides) {
        const double lo = height_or_floor(s.nc, s.nr);
        if (lo < h) wall(s.k1, s.k2, lo, h, s.ex, s.ey, s.sx, s.sy);
      }
    }
  return soup;
}

}  // namespace skyband
