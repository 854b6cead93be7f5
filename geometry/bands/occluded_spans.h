#pragma once
// The occluded parts of one sample line as a sorted list of disjoint, merged spans in
// pseudo-angle units (geometry/core/pseudo_angle.h: [0, 2] ↔ α ∈ [0, π]): the interval set the
// band method (band_visibility.cpp) inserts each triangle's occluded α-span into, and tests
// nodes and triangles against before any exact work.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace skyband::band_detail {

// An occluded interval on a sample line, in pseudo-angle units (pseudo_angle.h): [0, 2] ↔ [0, π].
struct Span {
  double lo, hi;
};

// First span of a sorted merged list with hi ≥ x (short lists scanned linearly: faster there).
inline std::vector<Span>::iterator first_reaching(std::vector<Span>& v, double x) {
  if (v.size() <= 16) {
    auto it = v.begin();
    while (it != v.end() && it->hi < x) ++it;
    return it;
  }
  return std::lower_bound(v.begin(), v.end(), x, [](const Span& s, double y) { return s.hi < y; });
}

// Inserts [lo, hi] into a sorted merged list (touching intervals merge: shared end points of
// triangles sharing an edge are bit-identical, so a closed surface leaves no gap). Returns false,
// leaving the list unchanged, when [lo, hi] already lies inside one span.
inline bool insert_span(std::vector<Span>& v, double lo, double hi) {
  auto first = first_reaching(v, lo);
  if (first != v.end() && first->lo <= lo && first->hi >= hi) return false;
  auto last = first;
  while (last != v.end() && last->lo <= hi) {
    lo = std::min(lo, last->lo);
    hi = std::max(hi, last->hi);
    ++last;
  }
  if (first == last) {
    v.insert(first, Span{lo, hi});
  } else {
    *first = Span{lo, hi};
    v.erase(first + 1, last);
  }
  return true;
}

// Is [lo, hi] inside one occluded span? The hottest test of the traversal (per node and plane,
// per triangle and plane): short lists are scanned linearly, which beats a binary search there.
inline bool covered(const std::vector<Span>& v, double lo, double hi) {
  const std::size_t n = v.size();
  if (n <= 16) {
    for (std::size_t i = 0; i < n; ++i)
      if (v[i].hi >= lo) return v[i].lo <= lo && v[i].hi >= hi;
    return false;
  }
  auto it = std::lower_bound(v.begin(), v.end(), lo, [](const Span& s, double x) { return s.hi < x; });
  return it != v.end() && it->lo <= lo && it->hi >= hi;
}

}  // namespace skyband::band_detail
