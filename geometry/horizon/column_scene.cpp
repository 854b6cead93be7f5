#include "geometry/horizon/column_scene.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <tuple>
#include <vector>

#include "geometry/core/exact_sign.h"
#include "geometry/mesh/grouped_bvh.h"
#include "geometry/mesh/welding.h"

namespace skyband {

namespace {

struct DirectedEdge {
  std::uint32_t lo, hi;  // welded ids, lo < hi
  bool forward;          // traversed lo → hi
  std::uint32_t triangle;
  std::uint8_t side;  // k: the side v_k → v_{k+1}
};

// For coplanar a, b, c, d: are c and d strictly on opposite sides of line ab? Exact, in the
// coordinate plane the points' plane projects onto without collapsing.
bool opposite_sides_in_plane(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 n = (b - a).cross(c - a);
  int drop = 2;  // the axis along the normal's largest component
  if (std::abs(n.x()) >= std::abs(n.y()) && std::abs(n.x()) >= std::abs(n.z()))
    drop = 0;
  else if (std::abs(n.y()) >= std::abs(n.z()))
    drop = 1;
  const auto proj = [drop](const Vec3& v) {
    return drop == 0 ? Vec3(v.y(), v.z(), 0) : drop == 1 ? Vec3(v.z(), v.x(), 0) : Vec3(v.x(), v.y(), 0);
  };
  const int sc = exact_orient2d_sign(proj(a), proj(b), proj(c)), sd = exact_orient2d_sign(proj(a), proj(b), proj(d));
  return sc * sd < 0;
}

// Does the xy projection of segment (a, b) without its end points meet that of triangle (p, q, w)
// (closed)? The triangle is not degenerate in xy. Exact: two convex sets are disjoint exactly when
// a line parallel to an edge of one of them separates them (the triangle's three edges, with the
// open segment on the line or beyond it; the segment's line, with the triangle strictly on one
// side); a segment lying on an edge's line counts as meeting. The end points are left out: a
// highest point there is seen in one azimuth only, a set of measure zero.
bool xy_open_segment_meets_triangle(const Vec3& a, const Vec3& b, const Vec3& p, const Vec3& q, const Vec3& w) {
  const std::array<const Vec3*, 3> v{&p, &q, &w};
  for (int i = 0; i < 3; ++i) {
    const Vec3 &u = *v[i], &x = *v[(i + 1) % 3], &y = *v[(i + 2) % 3];
    const int inside = exact_orient2d_sign(u, x, y);
    const int sa = exact_orient2d_sign(u, x, a), sb = exact_orient2d_sign(u, x, b);
    if (sa != inside && sb != inside && (sa != 0 || sb != 0)) return false;
  }
  const int sp = exact_orient2d_sign(a, b, p), sq = exact_orient2d_sign(a, b, q), sw = exact_orient2d_sign(a, b, w);
  return !((sp > 0 && sq > 0 && sw > 0) || (sp < 0 && sq < 0 && sw < 0));
}

struct Candidate {
  SilhouetteEdge edge;
  std::array<Vec3, 2> c;  // the faces' third vertices
  double base_floor_z = 0;
  std::vector<RaisedPart> raised;
};

// The parameter range [t0, t1] ⊂ [0, 1] of segment a → b whose xy projection lies in that of
// triangle (p, q, w), widened by a bound of its rounding (and 10⁻⁹) so that it holds the exact
// range; the whole segment where that bound is not small (a segment nearly along an edge's line).
void xy_part_in_triangle(const Vec3& a, const Vec3& b, const Vec3& p, const Vec3& q, const Vec3& w, double& t0, double& t1) {
  constexpr double kEps = 2.3e-16;
  t0 = 0, t1 = 1;
  double widen = 1e-9;
  const std::array<const Vec3*, 3> v{&p, &q, &w};
  const auto cross = [](double ux, double uy, double vx, double vy) { return ux * vy - uy * vx; };
  for (int i = 0; i < 3; ++i) {
    const Vec3 &u = *v[i], &x = *v[(i + 1) % 3], &y = *v[(i + 2) % 3];
    const double ex = x.x() - u.x(), ey = x.y() - u.y();
    const double s = cross(ex, ey, y.x() - u.x(), y.y() - u.y()) > 0 ? 1.0 : -1.0;  // the inner side
    const double f0 = s * cross(ex, ey, a.x() - u.x(), a.y() - u.y());
    const double f1 = s * cross(ex, ey, b.x() - u.x(), b.y() - u.y());
    // Each product's rounding, bounded by a few units of the last place of the magnitudes.
    const double scale = (std::abs(ex) + std::abs(ey)) *
                         (std::abs(a.x() - u.x()) + std::abs(a.y() - u.y()) + std::abs(b.x() - u.x()) + std::abs(b.y() - u.y()));
    const double err = 8 * kEps * scale;
    if (f0 >= -err && f1 >= -err) continue;  // (nearly) inside this edge's half-plane all along
    if (f0 < -err && f1 < -err) {            // outside by rounding only: the exact test said it meets
      t0 = 0, t1 = 1;
      return;
    }
    const double d = std::abs(f0 - f1);
    const double t = f0 / (f0 - f1);
    widen = std::max(widen, 4 * err / d + 4 * kEps);
    if (f0 < 0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
  }
  if (widen > 1e-3 || !(t0 <= t1 + 2 * widen)) {
    t0 = 0, t1 = 1;
    return;
  }
  t0 = std::max(0.0, t0 - widen), t1 = std::min(1.0, t1 + widen);
}

// BVH over the edges (geometry/mesh/grouped_bvh.h): leaves hold ≤ 4 edges of one solid, so a leaf's
// box is (part of) one building's; `edges` is reordered into leaf order.
void build_edge_bvh(ColumnScene& out, std::vector<Candidate>& edges, const std::vector<std::uint32_t>& edge_solid) {
  std::vector<Aabb> boxes(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    boxes[i].extend(edges[i].edge.a);
    boxes[i].extend(edges[i].edge.b);
  }
  const std::vector<std::uint32_t> order = build_grouped_bvh(boxes, edge_solid, 4, 4, out.edge_nodes,
                                                             [](std::uint32_t, std::uint32_t, std::vector<std::uint32_t>&) {});
  std::vector<Candidate> sorted(edges.size());
  for (std::size_t k = 0; k < order.size(); ++k) sorted[k] = edges[order[k]];
  edges.swap(sorted);
}

// The other components' triangles in a median-split BVH (leaves of ≤ 4 triangles, one group:
// build_grouped_bvh without buildings); `triangles` is reordered into leaf order.
void build_triangle_bvh(const TriangleSoup& soup, std::vector<std::uint32_t>& triangles, std::vector<BvhNode>& nodes) {
  std::vector<Aabb> boxes(triangles.size());
  for (std::size_t k = 0; k < triangles.size(); ++k)
    for (std::uint32_t v : soup.triangles[triangles[k]]) boxes[k].extend(soup.vertices[v]);
  const std::vector<std::uint32_t> one_group(triangles.size(), 0);
  const std::vector<std::uint32_t> order =
      build_grouped_bvh(boxes, one_group, 4, 4, nodes, [](std::uint32_t, std::uint32_t, std::vector<std::uint32_t>&) {});
  std::vector<std::uint32_t> sorted(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) sorted[k] = triangles[order[k]];
  triangles.swap(sorted);
}

}  // namespace

ColumnScene classify_column_scene(const TriangleSoup& soup) {
  ColumnScene out;
  const std::size_t nt = soup.triangles.size();
  if (nt == 0) return out;
  const std::vector<std::uint32_t> wid = weld_positions(soup.vertices);

  // A triangle repeating a (welded) vertex has no area, and its two other sides traverse one
  // segment both ways, so it adds nothing to any surface's boundary: it is left out (neither a
  // face of a column solid nor a triangle of another component — it hides nothing).
  std::vector<char> degenerate(nt, 0);
  std::vector<DirectedEdge> edges;
  edges.reserve(3 * nt);
  for (std::uint32_t t = 0; t < nt; ++t) {
    const auto& tri = soup.triangles[t];
    const std::array<std::uint32_t, 3> w{wid[tri[0]], wid[tri[1]], wid[tri[2]]};
    if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) {
      degenerate[t] = 1;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t p = w[k], q = w[(k + 1) % 3];
      edges.push_back({std::min(p, q), std::max(p, q), p < q, t, std::uint8_t(k)});
    }
  }
  // Every undirected edge in exactly two triangles links them (the files' windings need not
  // agree: each triangle gets a flip bit that makes the two traverse it in opposite directions);
  // an edge in one triangle is open (it lifts its solid's floor height to its ends: at the floor
  // for a floor left open, buildings modelled as walls and a roof standing on the ground); a vertical
  // edge in 4, 6, ... triangles links nothing (columns meeting along a vertical line only:
  // height-field pixels touching diagonally, buildings touching at a corner) and must be
  // balanced once every triangle is oriented; any other edge (three triangles, or four on a
  // horizontal edge: a party wall modelled twice) makes the surfaces through it other components.
  // Ranges [first, last) into `edges`.
  std::sort(edges.begin(), edges.end(),
            [](const DirectedEdge& x, const DirectedEdge& y) { return std::tie(x.lo, x.hi) < std::tie(y.lo, y.hi); });
  std::vector<std::uint32_t> adjacency_start(nt + 1, 0);
  std::vector<std::pair<std::uint32_t, bool>> adjacency;  // (neighbour, the two must differ in flip)
  std::vector<std::size_t> open_edges;
  std::vector<std::pair<std::size_t, std::size_t>> multi_edges, bad_edges;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
    const DirectedEdge& e = edges[i];
    if (j - i == 2) {
      ++adjacency_start[edges[i].triangle + 1];
      ++adjacency_start[edges[i + 1].triangle + 1];
    } else if (j - i == 1) {
      open_edges.push_back(i);
    } else {
      const auto& te = soup.triangles[e.triangle];
      const Vec3 &p = soup.vertices[te[e.side]], &q = soup.vertices[te[(e.side + 1) % 3]];
      if ((j - i) % 2 == 0 && p.x() == q.x() && p.y() == q.y())
        multi_edges.emplace_back(i, j);
      else
        bad_edges.emplace_back(i, j);
    }
    i = j;
  }
  for (std::size_t t = 0; t < nt; ++t) adjacency_start[t + 1] += adjacency_start[t];
  adjacency.resize(adjacency_start[nt]);
  {
    std::vector<std::uint32_t> fill(adjacency_start.begin(), adjacency_start.end() - 1);
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
      if (j - i == 2) {
        const DirectedEdge &e = edges[i], &f = edges[i + 1];
        const bool differ = e.forward == f.forward;  // same direction: one of the two must flip
        adjacency[fill[e.triangle]++] = {f.triangle, differ};
        adjacency[fill[f.triangle]++] = {e.triangle, differ};
      }
      i = j;
    }
  }
  // The candidate solids are the orientation regions: the triangles one walk over linked edges
  // reaches. Each is tested on its own — buildings of one file touching at a corner vertex, or
  // along a vertical line, are separate solids with floors of their own, and a broken building
  // beside them makes only itself another component.
  std::vector<std::int8_t> flip(nt, -1);
  std::vector<std::uint32_t> region(nt, UINT32_MAX);
  std::vector<char> region_ok;
  std::vector<double> region_z_min;
  std::vector<Vec3> region_reference;
  {
    std::vector<std::uint32_t> queue;
    for (std::uint32_t t0 = 0; t0 < nt; ++t0) {
      if (flip[t0] >= 0 || degenerate[t0]) continue;
      const std::uint32_t r = std::uint32_t(region_ok.size());
      region_ok.push_back(1);
      region_z_min.push_back(1e300);
      region_reference.push_back(soup.vertices[soup.triangles[t0][0]]);
      flip[t0] = 0;
      region[t0] = r;
      queue.assign(1, t0);
      while (!queue.empty()) {
        const std::uint32_t t = queue.back();
        queue.pop_back();
        for (std::uint32_t vi : soup.triangles[t]) region_z_min[r] = std::min(region_z_min[r], soup.vertices[vi].z());
        for (std::uint32_t k = adjacency_start[t]; k < adjacency_start[t + 1]; ++k) {
          const auto [u, differ] = adjacency[k];
          const std::int8_t want = std::int8_t(flip[t] ^ (differ ? 1 : 0));
          if (flip[u] < 0) {
            flip[u] = want;
            region[u] = r;
            queue.push_back(u);
          } else if (flip[u] != want) {
            region_ok[r] = 0;  // not orientable
          }
        }
      }
    }
  }
  const std::size_t regions = region_ok.size();
  for (const auto& [first, last] : bad_edges)
    for (std::size_t k = first; k < last; ++k) region_ok[region[edges[k].triangle]] = 0;
  const auto winding = [&](std::uint32_t t) { return flip[t] == 1 ? -1 : 1; };
  // The signed volume of each region relative to a point at its lowest height z_min (for a surface
  // closed but for a floor left open there, the volume of the solid capped in that plane). Its
  // sign orients the region outward; the method's validity does not rest on that choice (a
  // surface oriented inside out has its roofs facing down, which lifts its floor height above
  // them). A region is closed by itself but for its open edges (every linked edge joins two of its
  // own triangles; multi-edges must be balanced within it, below).
  std::vector<double> region_volume6(regions, 0.0);
  for (std::uint32_t t = 0; t < nt; ++t) {
    if (degenerate[t]) continue;
    const std::uint32_t r = region[t];
    const auto& tri = soup.triangles[t];
    const Vec3 &a = soup.vertices[tri[0]], &b = soup.vertices[tri[1]], &c = soup.vertices[tri[2]];
    const Vec3 ref(region_reference[r].x(), region_reference[r].y(), region_z_min[r]);
    region_volume6[r] += winding(t) * (a - ref).dot((b - ref).cross(c - ref));
  }
  for (std::size_t r = 0; r < regions; ++r)
    if (region_volume6[r] == 0) region_ok[r] = 0;
  // +1 where the oriented winding of t is outward.
  const auto outward = [&](std::uint32_t t) { return winding(t) * (region_volume6[region[t]] > 0 ? 1 : -1); };
  // Multi-edges: balanced within each region once oriented outward (so that every region is a
  // closed oriented surface by itself).
  for (const auto& [first, last] : multi_edges) {
    for (std::size_t k = first; k < last; ++k) {
      const std::uint32_t r = region[edges[k].triangle];
      int balance = 0;
      for (std::size_t m = first; m < last; ++m)
        if (region[edges[m].triangle] == r) balance += (edges[m].forward ? 1 : -1) * outward(edges[m].triangle);
      if (balance != 0) region_ok[r] = 0;
    }
  }
  // Floor heights. A region's base floor is its lowest height raised to the highest end of its
  // open edges (their cap lies below it). Its down-facing triangles (outward normal below the
  // horizontal, exact xy orientation) above the base floor — soffits of overhangs, outward leans —
  // raise the floor height only of the parts of edges over them (in xy): going up a vertical line
  // that meets none of them above a point's height, the winding number never rises there
  // (docs/geometry.md, "Exact horizon"). The region's floor height is the highest of them.
  std::vector<double> base_floor(region_z_min);
  for (const std::size_t i : open_edges) {
    const DirectedEdge& e = edges[i];
    const auto& te = soup.triangles[e.triangle];
    double& f = base_floor[region[e.triangle]];
    f = std::max({f, soup.vertices[te[e.side]].z(), soup.vertices[te[(e.side + 1) % 3]].z()});
  }
  std::vector<double> region_floor(base_floor);
  std::vector<std::uint32_t> raised;  // down-facing triangles above their region's base floor
  for (std::uint32_t t = 0; t < nt; ++t) {
    if (degenerate[t] || !region_ok[region[t]]) continue;
    const auto& tri = soup.triangles[t];
    const Vec3 &a = soup.vertices[tri[0]], &b = soup.vertices[tri[1]], &c = soup.vertices[tri[2]];
    if (exact_orient2d_sign(a, b, c) * outward(t) >= 0) continue;
    const double top = std::max({a.z(), b.z(), c.z()});
    if (top <= base_floor[region[t]]) continue;
    raised.push_back(t);
    region_floor[region[t]] = std::max(region_floor[region[t]], top);
  }
  const auto column = [&](std::uint32_t t) { return !degenerate[t] && region_ok[region[t]]; };

  for (std::size_t r = 0; r < regions; ++r) {
    if (region_ok[r]) {
      ++out.column_solids;
      out.max_column_floor_z = std::max(out.max_column_floor_z, region_floor[r]);
      out.min_column_floor_z = std::min(out.min_column_floor_z, base_floor[r]);
    } else {
      ++out.other_components;
    }
  }
  for (std::uint32_t t = 0; t < nt; ++t)
    if (!degenerate[t] && !column(t))
      for (std::uint32_t vi : soup.triangles[t]) out.max_other_z = std::max(out.max_other_z, soup.vertices[vi].z());

  // The floor height of a candidate edge (a, b) of region r: its base floor, raised by the raised
  // triangles of r whose xy projection meets the edge's without its end points (exact), found
  // through a BVH; each of them gives the part of the edge over it (`parts`).
  std::vector<BvhNode> raised_nodes;
  {
    std::vector<Aabb> boxes(raised.size());
    std::vector<std::uint32_t> groups(raised.size());
    for (std::size_t k = 0; k < raised.size(); ++k) {
      for (std::uint32_t vi : soup.triangles[raised[k]]) boxes[k].extend(soup.vertices[vi]);
      groups[k] = region[raised[k]];
    }
    const std::vector<std::uint32_t> order =
        build_grouped_bvh(boxes, groups, 4, 4, raised_nodes, [](std::uint32_t, std::uint32_t, std::vector<std::uint32_t>&) {});
    std::vector<std::uint32_t> sorted(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) sorted[k] = raised[order[k]];
    raised.swap(sorted);
  }
  std::vector<std::uint32_t> raised_stack;
  const auto edge_floor = [&](std::uint32_t r, const Vec3& a, const Vec3& b, std::vector<RaisedPart>& parts) {
    double floor = base_floor[r];
    parts.clear();
    if (raised_nodes.empty() || region_floor[r] == floor) return floor;
    const double x0 = std::min(a.x(), b.x()), x1 = std::max(a.x(), b.x());
    const double y0 = std::min(a.y(), b.y()), y1 = std::max(a.y(), b.y());
    raised_stack.assign(1, 0);
    while (!raised_stack.empty()) {
      const BvhNode& node = raised_nodes[raised_stack.back()];
      raised_stack.pop_back();
      if (node.box.lo.x() > x1 || node.box.hi.x() < x0 || node.box.lo.y() > y1 || node.box.hi.y() < y0 ||
          node.box.hi.z() <= base_floor[r])
        continue;
      if (node.count == 0) {
        raised_stack.push_back(node.first);
        raised_stack.push_back(node.first + 1);
        continue;
      }
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
        const std::uint32_t t = raised[k];
        if (region[t] != r) continue;
        const auto& tri = soup.triangles[t];
        const Vec3 &p = soup.vertices[tri[0]], &q = soup.vertices[tri[1]], &w = soup.vertices[tri[2]];
        const double top = std::max({p.z(), q.z(), w.z()});
        if (top <= base_floor[r] || !xy_open_segment_meets_triangle(a, b, p, q, w)) continue;
        RaisedPart part{0, 1, top};
        xy_part_in_triangle(a, b, p, q, w, part.t0, part.t1);
        parts.push_back(part);
        floor = std::max(floor, top);
      }
    }
    return floor;
  };

  // Silhouette candidates: the edges of column solids in two triangles (consecutive after the
  // sort), and their open edges (in one: a boundary can always carry the highest point; such an
  // edge lies at or below its solid's base floor, so only points below it — which the method
  // declines on reaching it — see it above their horizontal). Vertical multi-edges have no
  // azimuth range.
  std::vector<std::uint32_t> edge_solid;
  std::vector<Candidate> candidates;
  for (std::size_t i = 0, j = 0; i < edges.size(); i = j) {
    j = i + 1;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
    if (j - i > 2 || !column(edges[i].triangle)) continue;
    const bool open = j - i == 1;
    const DirectedEdge &e = edges[i], &f = edges[open ? i : i + 1];
    const auto& te = soup.triangles[e.triangle];
    const auto& tf = soup.triangles[f.triangle];
    Candidate candidate;
    SilhouetteEdge& s = candidate.edge;
    std::array<Vec3, 2>& c3 = candidate.c;
    // Ends by welded id: e traverses v_side → v_side+1; forward means lo → hi.
    const Vec3& e0 = soup.vertices[te[e.side]];
    const Vec3& e1 = soup.vertices[te[(e.side + 1) % 3]];
    s.a = e.forward ? e0 : e1;
    s.b = e.forward ? e1 : e0;
    if (s.a.x() == s.b.x() && s.a.y() == s.b.y()) continue;  // vertical: no azimuth range
    if (s.a.z() <= out.min_column_floor_z && s.b.z() <= out.min_column_floor_z) continue;
    s.floor_z = edge_floor(region[e.triangle], s.a, s.b, candidate.raised);
    candidate.base_floor_z = base_floor[region[e.triangle]];
    c3[0] = soup.vertices[te[(e.side + 2) % 3]];
    c3[1] = soup.vertices[tf[(f.side + 2) % 3]];
    // Coplanar faces on opposite sides of the edge (a flat continuation, the same outer side):
    // never a silhouette. (Coplanar on the same side is a zero-thickness fin: kept.)
    if (!open && exact_orientation(s.a, s.b, c3[0], c3[1]) == 0 && opposite_sides_in_plane(s.a, s.b, c3[0], c3[1])) continue;
    // det[a − p, b − p, c − p] is the triangle's orientation when (a, b, c) follows its winding
    // (e.forward for e; f traverses the edge the other way), and is negative when p is on the
    // winding normal's side; the outward sign turns that into "front-facing".
    // (Both faces are in one region: a paired edge links them.)
    const int out_sign = region_volume6[region[e.triangle]] > 0 ? 1 : -1;
    const bool e_forward = e.forward != (flip[e.triangle] == 1), f_forward = f.forward != (flip[f.triangle] == 1);
    s.facing_sign[0] = std::int8_t(-out_sign * (e_forward ? 1 : -1));
    s.facing_sign[1] = std::int8_t(-out_sign * (f_forward ? 1 : -1));
    if (open) s.facing_sign[1] = std::int8_t(-s.facing_sign[0]);  // one face: never both facing one way
    for (int k = 0; k < 2; ++k) {
      const Vec3& c = c3[k];
      s.face_kind[k] = SilhouetteEdge::kGeneral;
      s.kind_sign[k] = 0;
      const int o2 = exact_orient2d_sign(s.a, s.b, c);
      if (s.a.z() == s.b.z() && s.b.z() == c.z() && o2 != 0) {
        // det[a − p, b − p, c − p] = n·(a − p), n = (b − a) × (c − a) = (0, 0, orient2d(a, b, c)).
        s.face_kind[k] = SilhouetteEdge::kHorizontal;
        s.kind_sign[k] = std::int8_t(o2);
      } else if (o2 == 0) {
        // A vertical plane: det[a − p, b − p, c − p] is linear in p and vanishes exactly where
        // orient2d(a, b, p) does, so it is K·orient2d(a, b, p); K's sign from one point off it.
        const Vec3 off(s.a.x() - (s.b.y() - s.a.y()), s.a.y() + (s.b.x() - s.a.x()), s.a.z());
        const int d = exact_orientation(s.a, s.b, c, off), o = exact_orient2d_sign(s.a, s.b, off);
        if (d != 0 && o != 0) {
          s.face_kind[k] = SilhouetteEdge::kVertical;
          s.kind_sign[k] = std::int8_t(d * o);
        }
      }
    }
    candidates.push_back(candidate);
    edge_solid.push_back(region[e.triangle]);
  }
  // Candidates continued by a collinear one at an end (exact collinearity of the three points).
  {
    std::vector<std::pair<std::array<double, 3>, std::uint32_t>> ends;
    ends.reserve(2 * candidates.size());
    for (std::uint32_t i = 0; i < candidates.size(); ++i)
      for (const Vec3& v : {candidates[i].edge.a, candidates[i].edge.b}) ends.push_back({{v.x(), v.y(), v.z()}, i});
    std::sort(ends.begin(), ends.end());
    std::vector<char> split(candidates.size(), 0);
    for (std::size_t i = 0; i + 1 < ends.size(); ++i) {
      if (ends[i].first != ends[i + 1].first) continue;
      const SilhouetteEdge &e = candidates[ends[i].second].edge, &f = candidates[ends[i + 1].second].edge;
      const Vec3 shared(ends[i].first[0], ends[i].first[1], ends[i].first[2]);
      const Vec3& u = e.a == shared ? e.b : e.a;
      const Vec3& w = f.a == shared ? f.b : f.a;
      const auto yz = [](const Vec3& p) { return Vec3(p.y(), p.z(), 0); };
      const auto zx = [](const Vec3& p) { return Vec3(p.z(), p.x(), 0); };
      if (exact_orient2d_sign(u, shared, w) == 0 && exact_orient2d_sign(yz(u), yz(shared), yz(w)) == 0 &&
          exact_orient2d_sign(zx(u), zx(shared), zx(w)) == 0)
        split[ends[i].second] = split[ends[i + 1].second] = 1;
    }
    out.split_edges = std::size_t(std::count(split.begin(), split.end(), 1));
  }
  build_edge_bvh(out, candidates, edge_solid);
  out.raised_first.push_back(0);
  for (const Candidate& c : candidates) {
    out.edges.push_back(c.edge);
    out.edge_third_vertices.push_back(c.c);
    out.edge_base_floor_z.push_back(c.base_floor_z);
    out.raised_parts.insert(out.raised_parts.end(), c.raised.begin(), c.raised.end());
    out.raised_first.push_back(std::uint32_t(out.raised_parts.size()));
  }

  // The other components' triangles, with a median-split BVH (leaves of ≤ 4 triangles).
  for (std::uint32_t t = 0; t < nt; ++t)
    if (!degenerate[t] && !column(t)) out.other_triangles.push_back(t);
  build_triangle_bvh(soup, out.other_triangles, out.other_nodes);
  return out;
}

}  // namespace skyband
