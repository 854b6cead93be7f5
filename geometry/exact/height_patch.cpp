#include "geometry/exact/height_patch.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <unordered_map>

#include "geometry/core/exact_sign.h"
#include "geometry/exact/occluder_set.h"
#include "geometry/mesh/boundary_cycle.h"
#include "geometry/mesh/welding.h"

namespace skyband {

namespace {

// Exact: is the turn u → v → w in xy convex (left), or straight with v strictly between?
bool convex_turn(const Vec3& u, const Vec3& v, const Vec3& w) {
  const int s = exact_orient2d_sign(u, v, w);
  return s > 0 || (s == 0 && strictly_between_xy(u, v, w));
}

// An occluder's welded vertex ids, counter-clockwise in xy.
std::vector<std::uint32_t> ccw_ids(const Occluder& o, const std::uint32_t* ids) {
  std::vector<std::uint32_t> v(ids, ids + o.count);
  if (o.xy_sign < 0) std::reverse(v.begin(), v.end());
  return v;
}

// The exact test of height_patch.h: the boundary cycle of the members (welded ids, with their
// positions) when they tile a convex polygon of xy once, else nothing.
std::vector<std::uint32_t> convex_height_outline(const std::vector<std::vector<std::uint32_t>>& polygons,
                                                 const std::unordered_map<std::uint32_t, Vec3>& position) {
  const std::vector<std::uint32_t> cycle = boundary_cycle(polygons);
  if (cycle.empty()) return {};
  // Convex: every turn left (or straight, through a vertex strictly between its neighbours), and
  // one turn round in all — a locally convex closed polygon turning k times round has k lowest
  // vertices in (y, x) order, so exactly one such vertex makes it a convex, simple polygon.
  const std::size_t k = cycle.size();
  const auto below = [](const Vec3& a, const Vec3& b) { return a.y() < b.y() || (a.y() == b.y() && a.x() < b.x()); };
  std::size_t lowest = 0;
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& u = position.at(cycle[(i + k - 1) % k]);
    const Vec3& v = position.at(cycle[i]);
    const Vec3& w = position.at(cycle[(i + 1) % k]);
    if (v.x() == w.x() && v.y() == w.y()) return {};  // a vertical step: two boundary points at one xy
    if (!convex_turn(u, v, w)) return {};
    lowest += below(v, u) && below(v, w);
  }
  if (lowest != 1) return {};
  return cycle;
}

}  // namespace

HeightPatches build_height_patches(std::vector<Occluder>& occluders, std::uint32_t max_members) {
  HeightPatches out;
  const std::size_t n = occluders.size();
  std::vector<Vec3> flat;
  flat.reserve(4 * n);
  for (const Occluder& o : occluders)
    for (std::uint32_t k = 0; k < o.count; ++k) flat.push_back(o.v[k]);
  const std::vector<std::uint32_t> id = weld_positions(flat);
  std::vector<std::uint32_t> first(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) first[i + 1] = first[i] + occluders[i].count;
  // Edges between two non-vertical occluders (and no third occluder of any kind).
  std::unordered_map<std::uint64_t, std::array<std::uint32_t, 3>> edges;
  edges.reserve(3 * n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const Occluder& o = occluders[i];
    for (std::uint32_t k = 0; k < o.count; ++k) {
      auto& e = edges[edge_key(id[first[i] + k], id[first[i] + (k + 1) % o.count])];
      if (e[2] < 2) e[e[2]] = o.xy_sign != 0 ? i : kNoPatch;
      ++e[2];
    }
  }
  const auto neighbour = [&](std::uint32_t i, std::uint32_t k) -> std::uint32_t {
    const Occluder& o = occluders[i];
    const auto it = edges.find(edge_key(id[first[i] + k], id[first[i] + (k + 1) % o.count]));
    if (it == edges.end() || it->second[2] != 2) return kNoPatch;
    return it->second[0] == i ? it->second[1] : it->second[0];
  };
  std::vector<std::uint32_t> owner(n, kNoPatch);
  std::unordered_map<std::uint32_t, Vec3> position;
  for (std::uint32_t seed = 0; seed < n; ++seed) {
    if (occluders[seed].xy_sign == 0 || owner[seed] != kNoPatch) continue;
    // Greedy growth: the outline as a counter-clockwise cycle of welded ids; a neighbour across an
    // outline edge u → v joins when its other vertices are new and every turn stays convex.
    std::vector<std::uint32_t> cycle = ccw_ids(occluders[seed], &id[first[seed]]);
    std::vector<std::uint32_t> members{seed};
    position.clear();
    for (std::uint32_t k = 0; k < occluders[seed].count; ++k) position.emplace(id[first[seed] + k], occluders[seed].v[k]);
    const auto pos = [&](std::uint32_t v) -> const Vec3& { return position.at(v); };
    owner[seed] = seed;
    std::deque<std::uint32_t> queue;
    for (std::uint32_t k = 0; k < occluders[seed].count; ++k) queue.push_back(neighbour(seed, k));
    while (!queue.empty() && members.size() < max_members) {
      const std::uint32_t q = queue.front();
      queue.pop_front();
      if (q == kNoPatch || owner[q] != kNoPatch || occluders[q].xy_sign == 0) continue;
      const std::vector<std::uint32_t> qv = ccw_ids(occluders[q], &id[first[q]]);
      const std::size_t qk = qv.size(), ck = cycle.size();
      // The shared outline edge: cycle has u → v where q has v → u.
      std::size_t at = ck, qi = 0;
      for (std::size_t c = 0; c < ck && at == ck; ++c)
        for (std::size_t j = 0; j < qk; ++j)
          if (cycle[c] == qv[(j + 1) % qk] && cycle[(c + 1) % ck] == qv[j]) {
            at = c, qi = j;
            break;
          }
      if (at == ck) continue;
      std::vector<std::uint32_t> inserted;  // q's vertices from after u round to before v
      for (std::size_t s = 2; s < qk; ++s) inserted.push_back(qv[(qi + s) % qk]);
      bool fresh = true;
      for (const std::uint32_t w : inserted) fresh = fresh && std::find(cycle.begin(), cycle.end(), w) == cycle.end();
      if (!fresh) continue;
      std::unordered_map<std::uint32_t, Vec3> added;
      for (std::uint32_t k = 0; k < occluders[q].count; ++k) added.emplace(id[first[q] + k], occluders[q].v[k]);
      const auto qpos = [&](std::uint32_t v) -> const Vec3& {
        const auto it = position.find(v);
        return it != position.end() ? it->second : added.at(v);
      };
      std::vector<std::uint32_t> grown(cycle.begin(), cycle.begin() + std::ptrdiff_t(at + 1));
      grown.insert(grown.end(), inserted.begin(), inserted.end());
      grown.insert(grown.end(), cycle.begin() + std::ptrdiff_t(at + 1), cycle.end());
      const std::size_t gk = grown.size();
      bool convex = true;
      for (std::size_t s = 0; s <= inserted.size() + 1 && convex; ++s) {
        const std::size_t c = (at + s) % gk;
        convex = convex_turn(qpos(grown[(c + gk - 1) % gk]), qpos(grown[c]), qpos(grown[(c + 1) % gk]));
      }
      if (!convex) continue;
      for (const auto& [v, p] : added) position.emplace(v, p);
      cycle.swap(grown);
      members.push_back(q);
      owner[q] = seed;
      for (std::uint32_t k = 0; k < occluders[q].count; ++k) queue.push_back(neighbour(q, k));
    }
    if (members.size() < 2) {
      owner[seed] = kNoPatch;
      continue;
    }
    std::vector<std::vector<std::uint32_t>> polygons;
    for (const std::uint32_t m : members) polygons.push_back(ccw_ids(occluders[m], &id[first[m]]));
    const std::vector<std::uint32_t> outline = convex_height_outline(polygons, position);
    if (outline.empty()) {
      for (const std::uint32_t m : members) owner[m] = kNoPatch;
      continue;
    }
    HeightPatch patch;
    patch.first_vertex = std::uint32_t(out.vertices.size());
    patch.vertex_count = std::uint32_t(outline.size());
    for (const std::uint32_t v : outline) out.vertices.push_back(pos(v));
    patch.first_member = std::uint32_t(out.members.size());
    patch.member_count = std::uint32_t(members.size());
    std::sort(members.begin(), members.end());
    for (const std::uint32_t m : members) {
      out.members.push_back(m);
      occluders[m].patch = std::uint32_t(out.patches.size());
      for (std::uint32_t k = 0; k < occluders[m].count; ++k) patch.box.extend(occluders[m].v[k]);
    }
    patch.cx = 0.5 * (patch.box.lo.x() + patch.box.hi.x());
    patch.cy = 0.5 * (patch.box.lo.y() + patch.box.hi.y());
    patch.cz = 0.5 * (patch.box.lo.z() + patch.box.hi.z());
    patch.h_min = std::numeric_limits<double>::infinity();
    patch.h_max = -patch.h_min;
    for (const std::uint32_t m : members) {
      const Occluder& o = occluders[m];
      const Vec3 c(patch.cx, patch.cy, patch.cz);
      const Vec3 a = o.v[0] - c, nrm = (o.v[1] - o.v[0]).cross(o.v[2] - o.v[0]);
      const double sx = -nrm.x() / nrm.z(), sy = -nrm.y() / nrm.z();
      const double h = a.z() - sx * a.x() - sy * a.y();  // the plane's height over (cx, cy)
      patch.slope_x = std::max(patch.slope_x, std::abs(sx));
      patch.slope_y = std::max(patch.slope_y, std::abs(sy));
      patch.h_min = std::min(patch.h_min, h);
      patch.h_max = std::max(patch.h_max, h);
    }
    if (!std::isfinite(patch.slope_x + patch.slope_y + patch.h_min + patch.h_max))
      patch.slope_x = patch.slope_y = std::numeric_limits<double>::infinity();
    patch.first_edge = std::uint32_t(out.edges.size());
    const auto index_of = [&](std::uint32_t occluder) {
      return std::uint32_t(std::lower_bound(members.begin(), members.end(), occluder) - members.begin());
    };
    for (const std::uint32_t m : members)
      for (std::uint32_t k = 0; k < occluders[m].count; ++k) {
        const std::uint32_t q = neighbour(m, k);
        if (q == kNoPatch || q < m || occluders[q].patch != occluders[m].patch) continue;
        out.edges.push_back({occluders[m].v[k], occluders[m].v[(k + 1) % occluders[m].count], {index_of(m), index_of(q)}});
      }
    patch.edge_count = std::uint32_t(out.edges.size()) - patch.first_edge;
    out.patches.push_back(patch);
  }
  return out;
}

bool strictly_beyond_every_plane(const HeightPatch& patch, double x, double y, double z, int sign) {
  const double dx = std::abs(x - patch.cx), dy = std::abs(y - patch.cy);
  const double spread = patch.slope_x * dx + patch.slope_y * dy;
  const double dz = z - patch.cz;
  // Rounding of the planes' coefficients and of these sums: far below 1e-9 relative of the terms.
  const double margin = 1e-9 * (std::abs(dz) + std::abs(patch.h_min) + std::abs(patch.h_max) + spread) + 1e-9;
  if (sign > 0) return dz > patch.h_max + spread + margin;
  return dz < patch.h_min - spread - margin;
}

}  // namespace skyband
