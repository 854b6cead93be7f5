#include "geometry/mesh/boundary_cycle.h"

#include <algorithm>
#include <unordered_map>

namespace skyband {

std::vector<std::uint32_t> boundary_cycle(std::span<const std::vector<std::uint32_t>> polygons) {
  std::unordered_map<std::uint64_t, int> net;  // key (a, b), a < b: count(a→b) − count(b→a)
  for (const auto& poly : polygons)
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const std::uint32_t a = poly[k], b = poly[(k + 1) % poly.size()];
      net[edge_key(a, b)] += a < b ? 1 : -1;
    }
  std::unordered_map<std::uint32_t, std::uint32_t> next;  // vertex → successor on the boundary
  std::size_t boundary = 0;
  for (const auto& [key, m] : net) {
    if (m == 0) continue;
    if (m != 1 && m != -1) return {};
    const auto lo = std::uint32_t(key >> 32), hi = std::uint32_t(key & 0xffffffffu);
    if (!next.emplace(m > 0 ? lo : hi, m > 0 ? hi : lo).second) return {};  // two edges leave one vertex
    ++boundary;
  }
  if (boundary < 3) return {};
  std::uint32_t start = next.begin()->first;
  for (const auto& [a, b] : next) start = std::min(start, a);
  std::vector<std::uint32_t> cycle;
  std::uint32_t v = start;
  do {
    cycle.push_back(v);
    const auto it = next.find(v);
    if (it == next.end() || cycle.size() > boundary) return {};
    v = it->second;
  } while (v != start);
  if (cycle.size() != boundary) return {};
  return cycle;
}

}  // namespace skyband
