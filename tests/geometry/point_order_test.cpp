// xy_morton_order (geometry/points/point_order.h): a permutation, the Z curve on a grid (its closed form),
// and ties in input order.
#define BOOST_TEST_MODULE point_order
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "geometry/points/point_order.h"

using namespace skyband;

namespace {
QueryPoint at(double x, double y) {
  return QueryPoint{Vec3(x, y, 1.0), Vec3(0, 0, 1)};
}
}  // namespace

BOOST_AUTO_TEST_CASE(empty_and_single) {
  BOOST_TEST(xy_morton_order({}).empty());
  const std::vector<QueryPoint> one{at(4e5, 6e6)};
  BOOST_TEST(xy_morton_order(one) == std::vector<std::uint32_t>{0});
}

BOOST_AUTO_TEST_CASE(is_a_permutation) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  std::vector<QueryPoint> pts;
  for (int i = 0; i < 1000; ++i) {
    const double x = 4e5 + u(rng);  // drawn in order (a call's arguments have none)
    pts.push_back(at(x, 6e6 + u(rng)));
  }
  std::vector<std::uint32_t> order = xy_morton_order(pts);
  std::sort(order.begin(), order.end());
  std::vector<std::uint32_t> all(pts.size());
  std::iota(all.begin(), all.end(), 0u);
  BOOST_TEST(order == all);
}

BOOST_AUTO_TEST_CASE(z_curve_on_a_grid) {
  // A 4 × 4 grid given row by row (index 4·row + column). The Z curve visits the quadrants
  // lower-left, lower-right, upper-left, upper-right, each the same way: its index is the
  // interleave of the column's bits (even) and the row's (odd).
  std::vector<QueryPoint> pts;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) pts.push_back(at(10.0 * col, 10.0 * row));
  const std::vector<std::uint32_t> expected{0, 1, 4, 5, 2, 3, 6, 7, 8, 9, 12, 13, 10, 11, 14, 15};
  BOOST_TEST(xy_morton_order(pts) == expected);
}

BOOST_AUTO_TEST_CASE(ties_keep_the_input_order) {
  const std::vector<QueryPoint> pts{at(5, 5), at(0, 0), at(5, 5), at(0, 0), at(5, 5)};
  const std::vector<std::uint32_t> expected{1, 3, 0, 2, 4};
  BOOST_TEST(xy_morton_order(pts) == expected);
}
