#include "geometry/mesh/welding.h"

#include <array>
#include <cstring>
#include <unordered_map>

namespace skyband {

namespace {

struct PositionKey {
  std::array<std::uint64_t, 3> bits;
  bool operator==(const PositionKey&) const = default;
};
struct PositionKeyHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (const std::uint64_t b : k.bits) h = (h ^ b) * 1099511628211ull ^ (b >> 29);
    return static_cast<std::size_t>(h);
  }
};

// Exact equality of doubles as a hashable key: +0 and −0 compare equal, so both map to +0.
PositionKey key_of(const Vec3& p) {
  PositionKey k{};
  for (int i = 0; i < 3; ++i) {
    const double v = p[i] + 0.0;  // −0 + 0 = +0
    std::memcpy(&k.bits[static_cast<std::size_t>(i)], &v, sizeof v);
  }
  return k;
}

}  // namespace

std::vector<std::uint32_t> weld_positions(const std::vector<Vec3>& vertices) {
  std::vector<std::uint32_t> id(vertices.size());
  std::unordered_map<PositionKey, std::uint32_t, PositionKeyHash> ids;
  ids.reserve(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i)
    id[i] = ids.emplace(key_of(vertices[i]), static_cast<std::uint32_t>(ids.size())).first->second;
  return id;
}

}  // namespace skyband
