#include "geometry/exact/occluder_set.h"

#include <algorithm>
#include <numeric>
#include <unordered_map>

#include "geometry/core/disjoint_sets.h"
#include "geometry/core/exact_sign.h"
#include "geometry/mesh/boundary_cycle.h"
#include "geometry/mesh/grouped_bvh.h"
#include "geometry/mesh/welding.h"

namespace skyband {

namespace {

constexpr std::uint32_t kLeafSize = 4;
constexpr std::uint32_t kComponentLeafSize = 8;

// Exact: are a, b, c collinear (every coordinate projection of (b − a) × (c − a) zero)?
bool collinear(const Vec3& a, const Vec3& b, const Vec3& c) {
  const auto yz = [](const Vec3& p) { return Vec3(p.y(), p.z(), 0); };
  const auto zx = [](const Vec3& p) { return Vec3(p.z(), p.x(), 0); };
  return exact_orient2d_sign(a, b, c) == 0 && exact_orient2d_sign(yz(a), yz(b), yz(c)) == 0 &&
         exact_orient2d_sign(zx(a), zx(b), zx(c)) == 0;
}

// Exact orientation of a, b, c in the plane of the non-collinear triangle (p, q, r), by its
// projection onto the first coordinate plane where (p, q, r) is not degenerate (a projection along
// an axis the plane is not parallel to keeps orientation up to one global sign).
struct PlaneOrientation {
  int axis = 2;  // 0: drop x (yz), 1: drop y (zx), 2: drop z (xy)
  Vec3 project(const Vec3& p) const {
    if (axis == 0) return Vec3(p.y(), p.z(), 0);
    if (axis == 1) return Vec3(p.z(), p.x(), 0);
    return Vec3(p.x(), p.y(), 0);
  }
  explicit PlaneOrientation(const Vec3& p, const Vec3& q, const Vec3& r) {
    for (int k : {2, 0, 1}) {
      axis = k;
      if (exact_orient2d_sign(project(p), project(q), project(r)) != 0) return;
    }
  }
  int operator()(const Vec3& a, const Vec3& b, const Vec3& c) const {
    return exact_orient2d_sign(project(a), project(b), project(c));
  }
};

// Exact: does v lie strictly between u and w on their common line (u, v, w collinear)? Compared
// along a coordinate in which u and w differ.
bool strictly_between(const Vec3& u, const Vec3& v, const Vec3& w) {
  for (int a = 0; a < 3; ++a)
    if (u[a] != w[a]) return (u[a] < v[a] && v[a] < w[a]) || (w[a] < v[a] && v[a] < u[a]);
  return false;
}

// A region of edge-connected, exactly coplanar triangles (welded ids `id`) as one strictly convex
// polygon, when it is one: every triangle turned to the same orientation in the plane, the
// boundary 1-chain (edges whose net multiplicity is ±1, interior edges cancelling) one simple
// cycle, and that cycle, with the vertices strictly between their neighbours dropped, strictly
// convex with every vertex left of every edge. Then the triangles cover exactly the polygon, once:
// the sum of their indicators is the winding number of the boundary cycle (1 inside a convex
// simple polygon, 0 outside). Returns the polygon's vertex positions, or nothing.
std::vector<Vec3> convex_outline(const TriangleSoup& soup, const std::vector<std::uint32_t>& id,
                                 const std::vector<std::uint32_t>& tris) {
  const auto& t0 = soup.triangles[tris[0]];
  const PlaneOrientation orient(soup.vertices[t0[0]], soup.vertices[t0[1]], soup.vertices[t0[2]]);
  std::unordered_map<std::uint32_t, Vec3> position;
  std::vector<std::vector<std::uint32_t>> turned;  // the triangles, all positive in the plane
  for (const std::uint32_t t : tris) {
    const auto& tri = soup.triangles[t];
    std::vector<std::uint32_t> v = {id[tri[0]], id[tri[1]], id[tri[2]]};
    const int s = orient(soup.vertices[tri[0]], soup.vertices[tri[1]], soup.vertices[tri[2]]);
    if (s == 0) return {};
    if (s < 0) std::swap(v[1], v[2]);
    for (int k = 0; k < 3; ++k) position.emplace(id[tri[k]], soup.vertices[tri[k]]);
    turned.push_back(std::move(v));
  }
  const std::vector<std::uint32_t> cycle = boundary_cycle(turned);
  if (cycle.empty()) return {};
  std::vector<Vec3> poly;
  for (const std::uint32_t c : cycle) poly.push_back(position.at(c));
  // Drop vertices strictly between their neighbours (repeat: a dropped vertex changes neighbours).
  for (bool dropped = true; dropped && poly.size() > 3;) {
    dropped = false;
    for (std::size_t i = 0; i < poly.size() && poly.size() > 3; ++i) {
      const Vec3& u = poly[(i + poly.size() - 1) % poly.size()];
      const Vec3& w = poly[(i + 1) % poly.size()];
      if (collinear(u, poly[i], w) && strictly_between(u, poly[i], w)) {
        poly.erase(poly.begin() + std::ptrdiff_t(i));
        dropped = true;
        --i;
      }
    }
  }
  const std::size_t k = poly.size();
  if (k < 3) return {};
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = 0; j < k; ++j) {
      if (j == i || j == (i + 1) % k) continue;
      if (orient(poly[i], poly[(i + 1) % k], poly[j]) <= 0) return {};
    }
  return poly;
}

// The upper and lower chains of a vertical convex polygon (exact comparisons): along the
// horizontal coordinate in which its vertices differ most, from the leftmost to the rightmost
// vertex (the higher of a vertical pair for the upper chain, the lower for the lower chain), the
// way round whose inner vertices lie above (below) the line between them.
void set_vertical_chains(Occluder& o) {
  const std::uint32_t k = o.count;
  // The horizontal axis: x, or y where the polygon's xy segment is steeper.
  double x0 = o.v[0].x(), x1 = x0, y0 = o.v[0].y(), y1 = y0;
  for (std::uint32_t i = 1; i < k; ++i) {
    x0 = std::min(x0, o.v[i].x()), x1 = std::max(x1, o.v[i].x());
    y0 = std::min(y0, o.v[i].y()), y1 = std::max(y1, o.v[i].y());
  }
  const int axis = x1 - x0 >= y1 - y0 ? 0 : 1;
  const auto h = [&](std::uint32_t i) { return o.v[i][axis]; };
  // Leftmost and rightmost, top and bottom of each (ties: a vertical edge).
  std::uint32_t lt = 0, lb = 0, rt = 0, rb = 0;
  for (std::uint32_t i = 1; i < k; ++i) {
    if (h(i) < h(lt) || (h(i) == h(lt) && o.v[i].z() > o.v[lt].z())) lt = i;
    if (h(i) < h(lb) || (h(i) == h(lb) && o.v[i].z() < o.v[lb].z())) lb = i;
    if (h(i) > h(rt) || (h(i) == h(rt) && o.v[i].z() > o.v[rt].z())) rt = i;
    if (h(i) > h(rb) || (h(i) == h(rb) && o.v[i].z() < o.v[rb].z())) rb = i;
  }
  if (h(lt) == h(rt)) return;  // degenerate (no horizontal extent): left to the general path
  // In the plane (h, z): orientation of (left, right, v) > 0 means v lies above the line.
  const auto above = [&](std::uint32_t a, std::uint32_t b, std::uint32_t v) {
    const auto hz = [&](std::uint32_t i) { return Vec3(h(i), o.v[i].z(), 0); };
    return exact_orient2d_sign(hz(a), hz(b), hz(v));
  };
  // Walk from lt forwards or backwards to rt: the way whose inner vertices are all above (or, when
  // neither way has inner vertices above, the way without inner vertices).
  std::uint32_t ways[2][5], len[2] = {0, 0};
  int kind[2] = {0, 0};  // 2: inner vertices, all above; 1: no inner vertex; 0: other
  for (int w = 0; w < 2; ++w) {
    const int dir = w == 0 ? 1 : -1;
    bool all_above = true;
    for (std::uint32_t i = lt;; i = (i + k + dir) % k) {
      if (len[w] > k) {
        all_above = false;
        break;
      }
      ways[w][len[w]++] = i;
      if (i == rt) break;
      if (i != lt && above(lt, rt, i) <= 0) all_above = false;
    }
    kind[w] = ways[w][len[w] - 1] != rt ? 0 : len[w] == 2 ? 1 : all_above ? 2 : 0;
  }
  const int pick = kind[0] >= kind[1] ? 0 : 1;
  if (kind[pick] == 0) return;
  const std::uint32_t* chain = ways[pick];
  const std::uint32_t n = len[pick];
  if (n < 2 || chain[n - 1] != rt) return;
  for (std::uint32_t i = 0; i < n; ++i) o.upper[i] = std::uint8_t(chain[i]);
  o.upper_count = std::uint8_t(n);
  // The lower chain: every vertex not strictly inside the upper one, and the bottoms of the ends.
  double lower = -1e300;
  for (std::uint32_t i = 0; i < k; ++i) {
    bool inner = false;
    for (std::uint32_t j = 1; j + 1 < n; ++j) inner = inner || chain[j] == i;
    if ((i == lt && lt != lb) || (i == rt && rt != rb) || inner) continue;
    lower = std::max(lower, o.v[i].z());
  }
  o.lower_top_z = lower;
  o.across[0] = std::uint8_t(lt);
  o.across[1] = std::uint8_t(rt);
}

// The BVH (geometry/mesh/grouped_bvh.h): a component of up to kComponentLeafSize occluders (a box:
// four walls and a roof) is one leaf, lowest first — walls standing on the ground before the roof
// they carry, which they then mostly hide. `set.occluders` is reordered into leaf order.
void build_bvh(OccluderSet& set, const std::vector<std::uint32_t>& component) {
  std::vector<Aabb> boxes(set.occluders.size());
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::uint32_t k = 0; k < set.occluders[i].count; ++k) boxes[i].extend(set.occluders[i].v[k]);
  const std::vector<std::uint32_t> order =
      build_grouped_bvh(boxes, component, kLeafSize, kComponentLeafSize, set.nodes,
                        [&](std::uint32_t first, std::uint32_t count, std::vector<std::uint32_t>& ord) {
                          std::stable_sort(ord.begin() + first, ord.begin() + first + count,
                                           [&](std::uint32_t a, std::uint32_t b) { return boxes[a].lo.z() < boxes[b].lo.z(); });
                        });
  std::vector<Occluder> sorted(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    sorted[k] = set.occluders[order[k]];
    sorted[k].xy_sign = exact_orient2d_sign(sorted[k].v[0], sorted[k].v[1], sorted[k].v[2]);
    if (sorted[k].xy_sign == 0) set_vertical_chains(sorted[k]);
    const Occluder& o = sorted[k];
    Vec3 m = (o.v[1] - o.v[0]).cross(o.v[2] - o.v[0]);
    if (o.count == 4) m += (o.v[2] - o.v[0]).cross(o.v[3] - o.v[0]);
    sorted[k].area2_m2 = m.norm();
  }
  set.occluders.swap(sorted);
}

// The walls under each non-vertical occluder's edges (OccluderSet::support): vertical occluders
// sharing an edge with it (bit-equal end points) whose highest vertex is no higher than that edge.
void build_supports(OccluderSet& set) {
  const std::vector<Occluder>& occ = set.occluders;
  const std::size_t n = occ.size();
  std::vector<Vec3> flat;
  flat.reserve(4 * n);
  std::vector<std::uint32_t> first(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::uint32_t k = 0; k < occ[i].count; ++k) flat.push_back(occ[i].v[k]);
    first[i + 1] = first[i] + occ[i].count;
  }
  const std::vector<std::uint32_t> id = weld_positions(flat);
  // Every edge of a vertical occluder, by its welded end points, sorted.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> wall_edges;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (occ[i].upper_count < 2) continue;
    for (std::uint32_t k = 0; k < occ[i].count; ++k)
      wall_edges.emplace_back(edge_key(id[first[i] + k], id[first[i] + (k + 1) % occ[i].count]), i);
  }
  std::sort(wall_edges.begin(), wall_edges.end());
  set.support_first.assign(n + 1, 0);
  set.support.clear();
  for (std::uint32_t i = 0; i < n; ++i) {
    const Occluder& o = occ[i];
    if (o.xy_sign != 0 && !wall_edges.empty()) {
      const std::size_t start = set.support.size();
      for (std::uint32_t k = 0; k < o.count; ++k) {
        const Vec3& a = o.v[k];
        const Vec3& b = o.v[(k + 1) % o.count];
        const std::uint64_t key = edge_key(id[first[i] + k], id[first[i] + (k + 1) % o.count]);
        auto it = std::lower_bound(wall_edges.begin(), wall_edges.end(), std::pair<std::uint64_t, std::uint32_t>(key, 0));
        for (; it != wall_edges.end() && it->first == key; ++it) {
          const Occluder& w = occ[it->second];
          double top = -1e300;
          for (std::uint32_t j = 0; j < w.count; ++j) top = std::max(top, w.v[j].z());
          if (top > std::max(a.z(), b.z())) continue;  // rises above the edge: not under it
          if (std::find(set.support.begin() + std::ptrdiff_t(start), set.support.end(), it->second) == set.support.end())
            set.support.push_back(it->second);
        }
      }
    }
    set.support_first[i + 1] = std::uint32_t(set.support.size());
  }
}

}  // namespace

OccluderSet build_occluder_set(const TriangleSoup& soup) {
  OccluderSet set;
  const std::vector<std::uint32_t> id = weld_positions(soup.vertices);
  const std::size_t nt = soup.triangles.size();
  std::vector<char> usable(nt, 0), merged(nt, 0);
  std::unordered_map<std::uint64_t, std::array<std::uint32_t, 3>> edges;  // up to 2 triangles, [2]: count
  edges.reserve(3 * nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = soup.triangles[t];
    const std::uint32_t a = id[tri[0]], b = id[tri[1]], c = id[tri[2]];
    if (a == b || b == c || c == a || collinear(soup.vertices[tri[0]], soup.vertices[tri[1]], soup.vertices[tri[2]])) {
      ++set.degenerate_triangles;
      continue;
    }
    usable[t] = 1;
    for (int k = 0; k < 3; ++k) {
      auto& e = edges[edge_key(id[tri[k]], id[tri[(k + 1) % 3]])];
      if (e[2] < 2) e[e[2]] = std::uint32_t(t);
      ++e[2];
    }
  }
  for (const Vec3& v : soup.vertices) set.max_z = std::max(set.max_z, v.z());
  set.occluders.reserve(nt);
  // Regions of edge-connected, exactly coplanar triangles; each that is a convex polygon becomes
  // one occluder (or a fan of convex quads), the others keep their triangles.
  DisjointSets regions(nt);
  for (const auto& [key, e] : edges) {
    if (e[2] != 2) continue;  // boundary or non-manifold edge
    const std::uint32_t t = e[0], u = e[1];
    const auto& a = soup.triangles[t];
    const auto& b = soup.triangles[u];
    int d = 0;
    while (d < 3 && (id[b[d]] == id[a[0]] || id[b[d]] == id[a[1]] || id[b[d]] == id[a[2]])) ++d;
    if (d == 3) continue;  // a duplicate triangle
    if (exact_orientation(soup.vertices[a[0]], soup.vertices[a[1]], soup.vertices[a[2]], soup.vertices[b[d]]) == 0)
      regions.unite(t, u);
  }
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> members;
  for (std::size_t t = 0; t < nt; ++t)
    if (usable[t]) members[regions.find(std::uint32_t(t))].push_back(std::uint32_t(t));
  std::vector<std::uint32_t> roots;
  for (const auto& [r, m] : members)
    if (m.size() >= 3) roots.push_back(r);
  std::sort(roots.begin(), roots.end());
  for (const std::uint32_t r : roots) {
    const std::vector<std::uint32_t>& m = members[r];
    const std::vector<Vec3> poly = convex_outline(soup, id, m);
    if (poly.empty()) continue;
    for (const std::uint32_t t : m) merged[t] = 1;
    ++set.merged_regions;
    // A fan of quads (0, i, i + 1, i + 2) and a last triangle: convex pieces whose shared
    // diagonals give bit-identical arcs.
    for (std::size_t i = 1; i + 1 < poly.size(); i += 2) {
      Occluder o;
      o.triangle = m[0];
      o.v[0] = poly[0], o.v[1] = poly[i], o.v[2] = poly[i + 1];
      o.count = 3;
      if (i + 2 < poly.size()) o.v[3] = poly[i + 2], o.count = 4;
      set.occluders.push_back(o);
    }
  }
  for (std::size_t t = 0; t < nt; ++t) {
    if (!usable[t] || merged[t]) continue;
    const auto& tri = soup.triangles[t];
    Occluder o;
    o.triangle = std::uint32_t(t);
    for (int k = 0; k < 3; ++k) o.v[k] = soup.vertices[tri[k]];
    // A partner across one of its edges: exactly coplanar, forming a strictly convex quad.
    for (int k = 0; k < 3 && o.count == 3; ++k) {
      const auto it = edges.find(edge_key(id[tri[k]], id[tri[(k + 1) % 3]]));
      if (it == edges.end() || it->second[2] != 2) continue;
      const std::uint32_t u = it->second[0] == t ? it->second[1] : it->second[0];
      if (u == t || !usable[u] || merged[u]) continue;
      const auto& other = soup.triangles[u];
      // Corners: A = tri[k], B = tri[k+1] (the shared edge), C = tri[k+2], D = other's third.
      const std::uint32_t ia = id[tri[k]], ib = id[tri[(k + 1) % 3]];
      int d = 0;
      while (d < 3 && (id[other[d]] == ia || id[other[d]] == ib)) ++d;
      if (d == 3) continue;
      const Vec3 &A = soup.vertices[tri[k]], &B = soup.vertices[tri[(k + 1) % 3]], &C = soup.vertices[tri[(k + 2) % 3]];
      const Vec3& D = soup.vertices[other[d]];
      if (exact_orientation(A, B, C, D) != 0) continue;
      // The quad A, C, B, D (C and D on either side of the diagonal A–B) is strictly convex when
      // its four corners turn the same way.
      const PlaneOrientation orient(A, B, C);
      const int s0 = orient(A, C, B), s1 = orient(C, B, D), s2 = orient(B, D, A), s3 = orient(D, A, C);
      if (s0 == 0 || s1 != s0 || s2 != s0 || s3 != s0) continue;
      o.v = {A, C, B, D};
      o.count = 4;
      merged[u] = 1;
      ++set.merged_quads;
    }
    merged[t] = 1;
    set.occluders.push_back(o);
  }
  // Connected components (triangles linked through welded vertices), for the BVH's grouping.
  DisjointSets linked(soup.vertices.size());
  for (std::size_t t = 0; t < nt; ++t)
    if (usable[t]) {
      const auto& tri = soup.triangles[t];
      linked.unite(id[tri[0]], id[tri[1]]);
      linked.unite(id[tri[0]], id[tri[2]]);
    }
  std::vector<std::uint32_t> component(set.occluders.size());
  for (std::size_t i = 0; i < set.occluders.size(); ++i)
    component[i] = linked.find(id[soup.triangles[set.occluders[i].triangle][0]]);
  build_bvh(set, component);
  set.height_patches = build_height_patches(set.occluders);
  build_supports(set);
  return set;
}

}  // namespace skyband
