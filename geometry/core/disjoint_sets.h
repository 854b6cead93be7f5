#pragma once
// Union–find over indices 0 … n−1 (path halving). The root of a set is its smallest index, so
// the result does not depend on the order of the unions.
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace skyband {

struct DisjointSets {
  std::vector<std::uint32_t> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace skyband
