#pragma once
// The boundary of a set of oriented polygons (vertex ids) as one simple cycle: the 1-chain of
// their edges, where an edge and its reverse cancel, must leave every edge with net multiplicity
// 0 or ±1, and the remaining edges must form a single cycle through distinct vertices. Used to
// prove that polygons tile one outline (geometry/exact/occluder_set.cpp: coplanar regions;
// geometry/exact/height_patch.cpp: height patches).
#include <cstdint>
#include <span>
#include <vector>

namespace skyband {

// An undirected edge's key: (min, max) in one word.
inline std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return a < b ? (std::uint64_t(a) << 32) | b : (std::uint64_t(b) << 32) | a;
}

// The cycle in the polygons' orientation, from its smallest id (deterministic), or empty when
// the boundary is not one simple cycle of at least three edges.
std::vector<std::uint32_t> boundary_cycle(std::span<const std::vector<std::uint32_t>> polygons);

}  // namespace skyband
