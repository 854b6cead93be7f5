#pragma once
// A bounding-volume hierarchy over items grouped by connected component (buildings): first over
// whole groups (median split of their boxes' centres along the longest axis), then inside a group
// over its items the same way, so that a leaf's box is (part of) one building's and a hidden
// building is skipped whole. Deterministic (ties broken by index), O(n log n). The exact horizon
// (its silhouette edges and, as one group, the other components' triangles,
// geometry/horizon/column_scene.h) and the exact union (its occluders, geometry/exact/occluder_set.h)
// use it: their walks are best first by elevation bound, where a building kept whole culls best.
// The scene's own BVH (geometry/mesh/scene.cpp) is built by the surface-area heuristic instead,
// the cost model of its ray and sample-plane traversals.
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "geometry/mesh/scene.h"

namespace skyband {

// Builds `nodes` (node 0 the root; an inner node's children at first, first + 1; a leaf holds
// [first, first + count) of the returned order) over items with `boxes` and `groups` (any ids).
// Leaves hold ≤ leaf_size items, or a whole group of ≤ group_leaf_size items; leaf_order(first,
// count, order) may reorder a leaf's items. Returns the items in leaf order.
template <class Node, class LeafOrder>
std::vector<std::uint32_t> build_grouped_bvh(const std::vector<Aabb>& boxes, const std::vector<std::uint32_t>& groups,
                                             std::uint32_t leaf_size, std::uint32_t group_leaf_size, std::vector<Node>& nodes,
                                             LeafOrder&& leaf_order) {
  const auto n = std::uint32_t(boxes.size());
  nodes.clear();
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  if (n == 0) return order;
  std::vector<Vec3> centres(n);
  for (std::uint32_t i = 0; i < n; ++i) centres[i] = boxes[i].centre();
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return groups[a] < groups[b]; });
  struct Group {
    std::uint32_t first, count;
    Aabb box;
  };
  std::vector<Group> group_list;
  for (std::uint32_t i = 0; i < n;) {
    std::uint32_t j = i;
    Group g{i, 0, {}};
    while (j < n && groups[order[j]] == groups[order[i]]) g.box.extend(boxes[order[j++]]);
    g.count = j - i;
    group_list.push_back(g);
    i = j;
  }
  const auto longest = [](const Aabb& b) {
    const Vec3 e = b.hi - b.lo;
    return e.x() >= e.y() ? (e.x() >= e.z() ? 0 : 2) : (e.y() >= e.z() ? 1 : 2);
  };
  struct Task {
    std::uint32_t node, first, count;
    bool over_groups;  // [first, first + count) of groups, or of order (inside one group)
    std::uint32_t leaf_limit;
  };
  nodes.reserve(2 * n / std::max<std::uint32_t>(1, leaf_size) + 2 * group_list.size() + 2);
  nodes.push_back({});
  std::vector<Task> stack{{0, 0, std::uint32_t(group_list.size()), true, leaf_size}};
  while (!stack.empty()) {
    Task task = stack.back();
    stack.pop_back();
    if (task.over_groups && task.count == 1) {
      const Group& g = group_list[task.first];
      task = {task.node, g.first, g.count, false, g.count <= group_leaf_size ? group_leaf_size : leaf_size};
    }
    Aabb box, cbox;
    for (std::uint32_t k = task.first; k < task.first + task.count; ++k) {
      if (task.over_groups) {
        box.extend(group_list[k].box);
        cbox.extend(group_list[k].box.centre());
      } else {
        box.extend(boxes[order[k]]);
        cbox.extend(centres[order[k]]);
      }
    }
    nodes[task.node].box = box;
    const Vec3 extent = cbox.hi - cbox.lo;
    if (!task.over_groups && (task.count <= task.leaf_limit || !(extent.maxCoeff() > 0))) {
      nodes[task.node].first = task.first;
      nodes[task.node].count = task.count;
      leaf_order(task.first, task.count, order);
      continue;
    }
    const int axis = longest(cbox);
    const std::uint32_t half = task.count / 2;
    if (task.over_groups) {
      auto begin = group_list.begin() + task.first;
      std::nth_element(begin, begin + half, begin + task.count, [&](const Group& x, const Group& y) {
        const double cx = x.box.centre()[axis], cy = y.box.centre()[axis];
        return cx != cy ? cx < cy : x.first < y.first;
      });
    } else {
      auto begin = order.begin() + task.first;
      std::nth_element(begin, begin + half, begin + task.count, [&](std::uint32_t a, std::uint32_t b) {
        return centres[a][axis] < centres[b][axis] || (centres[a][axis] == centres[b][axis] && a < b);
      });
    }
    const auto left = std::uint32_t(nodes.size());
    nodes.push_back({});
    nodes.push_back({});
    nodes[task.node].first = left;
    nodes[task.node].count = 0;
    stack.push_back({left + 1, task.first + half, task.count - half, task.over_groups, task.leaf_limit});
    stack.push_back({left, task.first, half, task.over_groups, task.leaf_limit});
  }
  return order;
}

}  // namespace skyband
