#include "geometry/horizon/horizon_svf.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "geometry/core/exact_sign.h"
#include "geometry/horizon/horizon_envelope.h"

namespace skyband {

struct HorizonSvf::Impl {
  const Scene& scene;
  const ColumnScene& columns;
  double offset_m;

  Vec3 p;  // the evaluated point
  HorizonEnvelope env;
  std::vector<std::uint32_t> stack;
  std::array<std::vector<std::uint32_t>, 128> buckets;
  std::size_t edge_tests = 0;
  struct FloatingPart {
    std::uint32_t edge;
    double t0, t1;  // along the edge from a (0) to b (1)
    double low2;    // a lower bound of the squared tan of its elevation (0 where it reaches p's height)
  };
  int current_bucket = 127;                        // the ordered walk's bucket being visited
  std::vector<FloatingPart> floating;              // see add_edge
  std::vector<std::pair<double, double>> waiting;  // scratch: an edge's parts above p's reach

  Impl(const Scene& s, const ColumnScene& c, double off) : scene(s), columns(c), offset_m(off) {}

  // The great circle through p of the plane with normal m (m_z ≠ 0).
  std::uint32_t add_circle(const Vec3& m) { return env.add_circle(-m.x() / m.z(), -m.y() / m.z()); }

  // The part of edge (a, b) (offsets from p) above the horizontal of p, as an arc.
  void insert_edge(const Vec3& a, const Vec3& b, double ta, double tb) {
    const bool a_up = a.z() > 0, b_up = b.z() > 0;
    if (!a_up && !b_up) return;
    Vec3 lo = a, hi = b;
    double tlo = ta, thi = tb;
    if (!a_up || !b_up) {
      // Clip at z = 0: hi the end above, lo the crossing of p's horizontal plane.
      if (!b_up) std::swap(lo, hi), std::swap(tlo, thi);
      const double l = hi.z() / (hi.z() - lo.z());
      lo = hi + l * (lo - hi);
      lo.z() = 0;
      tlo = diamond_angle(lo.x(), lo.y());
    }
    // The great circle through p, lo and hi: the plane with normal m; along a unit horizontal
    // direction w, tan(elevation) = −(m_x w_x + m_y w_y)/m_z.
    const Vec3 m = lo.cross(hi);
    if (!(m.z() != 0) || tlo == thi) return;                                     // radial or vertical: covers no azimuth range
    if (!std::isfinite(m.x() / m.z()) || !std::isfinite(m.y() / m.z())) return;  // a sliver of ~0 azimuth
    const double rl = 1.0 / std::sqrt(lo.x() * lo.x() + lo.y() * lo.y());
    const double rh = 1.0 / std::sqrt(hi.x() * hi.x() + hi.y() * hi.y());
    env.insert_range(add_circle(m), tlo, lo.x() * rl, lo.y() * rl, thi, hi.x() * rh, hi.y() * rh);
  }

  // Is p under (or on) a triangle reaching above it — inside a column solid or on its surface?
  // Exact; only triangles whose xy box holds p's xy are tested (a point query on the scene BVH).
  bool under_a_triangle() {
    const auto& v = scene.soup().vertices;
    return scene.any_triangle_over(p.x(), p.y(), p.z(), stack, [&](std::uint32_t t) {
      const auto& tri = scene.soup().triangles[t];
      const Vec3 &A = v[tri[0]], &B = v[tri[1]], &C = v[tri[2]];
      if (A.z() <= p.z() && B.z() <= p.z() && C.z() <= p.z()) return false;
      if (std::min({A.x(), B.x(), C.x()}) > p.x() || std::max({A.x(), B.x(), C.x()}) < p.x() ||
          std::min({A.y(), B.y(), C.y()}) > p.y() || std::max({A.y(), B.y(), C.y()}) < p.y())
        return false;
      const int s = exact_orient2d_sign(A, B, C);
      const int o1 = exact_orient2d_sign(A, B, p), o2 = exact_orient2d_sign(B, C, p), o3 = exact_orient2d_sign(C, A, p);
      const bool inside = s != 0 ? (o1 * s >= 0 && o2 * s >= 0 && o3 * s >= 0) : (o1 == 0 && o2 == 0 && o3 == 0);
      if (!inside) return false;
      if (s == 0) return true;  // a vertical triangle through p's vertical
      // det[A − p, B − p, C − p] has the sign of n·(A − p), n = (B − A) × (C − A), n_z ∝ s:
      // same signs — the triangle is above p there (p under it, or on it). A triangle below p
      // at p's xy (p on a roof) is fine: its highest point in each azimuth is on an edge.
      return exact_orientation(A, B, C, p) * s >= 0;
    });
  }

  // The box of the part [t0, t1] of edge e.
  static Aabb part_box(const SilhouetteEdge& e, double t0, double t1) {
    Aabb box;
    box.extend(t0 == 0 ? e.a : e.a + t0 * (e.b - e.a));
    box.extend(t1 == 1 ? e.b : e.a + t1 * (e.b - e.a));
    return box;
  }
  // A lower bound of tan² of the elevation of the part [t0, t1] of edge e: its lowest height over
  // its box's farthest corner (0 where it reaches down to p's height).
  double low2_of(const SilhouetteEdge& e, double t0, double t1) const {
    const Aabb box = part_box(e, t0, t1);
    const double dz = box.lo.z() - p.z();
    if (!(dz > 0)) return 0;
    const double fx = std::max(std::abs(box.lo.x() - p.x()), std::abs(box.hi.x() - p.x()));
    const double fy = std::max(std::abs(box.lo.y() - p.y()), std::abs(box.hi.y() - p.y()));
    return dz * dz / (fx * fx + fy * fy) * (1 - 1e-12);
  }
  // An upper bound of the squared elevation bound of every node the ordered walk visits from
  // bucket k on (buckets are quarter-octaves of it, highest first; 126 and 127 hold all above).
  static double bucket_ceiling2(int k) {
    if (k >= 126) return std::numeric_limits<double>::infinity();
    const int q = k - 84;  // 4 · exponent + the top two mantissa bits (bucket_of)
    const int e = q >= 0 ? q / 4 : -((3 - q) / 4), m = q - 4 * e;
    return std::ldexp(1.0 + (m + 1) / 4.0, e);
  }

  // One silhouette candidate. Only silhouette edges can carry a solid's highest point in an
  // azimuth (docs/geometry.md, "Exact horizon"): an edge whose two faces are both strictly
  // front-facing, or both strictly back-facing, from p is skipped.
  // Returns false when p is below the base floor of the edge's solid (a solid floating above p, or
  // one open above it) and the edge is not hidden: the method is not valid. The parts of an edge
  // over a soffit higher than p are not inserted but kept in `floating`: unless they end hidden
  // below the envelope, the sky below them may be visible and the method declines (compute).
  bool add_edge(std::uint32_t index) {
    const SilhouetteEdge& e = columns.edges[index];
    if (e.a.z() <= p.z() && e.b.z() <= p.z()) return true;  // at or below p's horizontal plane
    ++edge_tests;
    int o2 = 2;  // orient2d(a, b, p), computed once if a face is vertical
    const auto side = [&](int k) {
      switch (e.face_kind[k]) {
        case SilhouetteEdge::kHorizontal:
          return e.kind_sign[k] * (e.a.z() > p.z() ? 1 : e.a.z() < p.z() ? -1 : 0);  // c.z = a.z
        case SilhouetteEdge::kVertical:
          if (o2 == 2) o2 = exact_orient2d_sign(e.a, e.b, p);
          return e.kind_sign[k] * o2;
        default:
          return exact_orientation(e.a, e.b, columns.edge_third_vertices[index][k], p);
      }
    };
    const int f0 = e.facing_sign[0] * side(0);
    const int f1 = e.facing_sign[1] * side(1);
    if (f0 == f1 && f0 != 0) return true;
    const Vec3 a = e.a - p, b = e.b - p;
    const double dx = std::max({std::min(a.x(), b.x()), -std::max(a.x(), b.x()), 0.0});
    const double dy = std::max({std::min(a.y(), b.y()), -std::max(a.y(), b.y()), 0.0});
    const double ta = diamond_angle(a.x(), a.y()), tb = diamond_angle(b.x(), b.y());
    if (dx > 0 || dy > 0) {
      // Cull: the edge's elevation is at most atan(max z / distance to its xy box).
      const double bound = std::max(a.z(), b.z()) / std::sqrt(dx * dx + dy * dy) * (1 + 1e-12);
      double lo = std::min(ta, tb), hi = std::max(ta, tb);
      if (hi - lo >= 2) {  // spans t = 0 (less than π: p is outside its xy box)
        lo = std::max(ta, tb);
        hi = std::min(ta, tb) + 4;
      }
      if (env.hidden_below(lo, hi, bound)) return true;
    }
    if (e.floor_z > p.z()) {
      // p is below this edge's floor height: the parts of the edge whose floor height is above p
      // wait — valid only if they end hidden below the envelope (then they cannot carry the
      // highest point; compute) — and the rest of it is inserted.
      // Below the solid's base floor (a solid floating above p, or one open above it) the method
      // declines at once: the edge is not hidden now, and such points rarely end as a horizon.
      if (columns.edge_base_floor_z[index] > p.z()) return false;
      waiting.clear();
      for (std::uint32_t k = columns.raised_first[index]; k < columns.raised_first[index + 1]; ++k) {
        const RaisedPart& part = columns.raised_parts[k];
        if (part.floor_z > p.z()) waiting.push_back({part.t0, part.t1});
      }
      std::sort(waiting.begin(), waiting.end());
      double from = 0;  // the edge's part from here on is still to be inserted
      const auto insert_part = [&](double u0, double u1) {
        if (!(u0 < u1)) return;
        const Vec3 c = u0 == 0 ? a : a + u0 * (b - a), d = u1 == 1 ? b : a + u1 * (b - a);
        insert_edge(c, d, u0 == 0 ? ta : diamond_angle(c.x(), c.y()), u1 == 1 ? tb : diamond_angle(d.x(), d.y()));
      };
      for (std::size_t k = 0; k < waiting.size();) {
        const double w0 = waiting[k].first;
        double w1 = waiting[k].second;
        for (++k; k < waiting.size() && waiting[k].first <= w1; ++k) w1 = std::max(w1, waiting[k].second);
        insert_part(from, w0);
        floating.push_back({index, w0, w1, low2_of(e, w0, w1)});
        from = std::max(from, w1);
      }
      insert_part(from, 1.0);
      return true;
    }
    insert_edge(a, b, ta, tb);
    return true;
  }

  // Conservative: true when everything inside the box is at or below p's horizontal plane or hidden
  // below the envelope over the box's azimuth range.
  bool node_hidden(const Aabb& box) const {
    if (box.hi.z() <= p.z()) return true;
    const double x0 = box.lo.x() - p.x(), x1 = box.hi.x() - p.x();
    const double y0 = box.lo.y() - p.y(), y1 = box.hi.y() - p.y();
    const double dx = std::max({x0, -x1, 0.0}), dy = std::max({y0, -y1, 0.0});
    if (dx == 0 && dy == 0) return false;
    const double bound = (box.hi.z() - p.z()) / std::sqrt(dx * dx + dy * dy) * (1 + 1e-12);
    double lo, hi;
    box_azimuth_range(x0, x1, y0, y1, lo, hi);
    return env.hidden_below(lo, hi, bound);
  }

  // Is every triangle of the other components at or below p's horizontal plane, or hidden below
  // the final envelope (then it can only occlude sky the column solids already hide)? Its highest
  // elevation is at most atan(max z / distance to its xy box), over the azimuth range of its
  // vertices (p outside the box); a triangle over p's xy box that rises above p is not hidden.
  bool others_hidden() {
    if (columns.valid_from_height(p.z())) return true;  // none rises above p
    const auto& soup = scene.soup();
    return walk(columns.other_nodes, false, [&](std::uint32_t k) {
      Aabb box;
      for (std::uint32_t v : soup.triangles[columns.other_triangles[k]]) box.extend(soup.vertices[v]);
      return node_hidden(box);
    });
  }

  // Walks a BVH, skipping nodes hidden below the envelope, calling leaf_item(k) for the items of
  // the leaves reached until one returns false (then false). `ordered`: best first — the node that
  // can rise highest, (z_max − z_p)/horizontal distance — so that the envelope rises early and
  // hides the most (a third fewer instructions than nearer-child-first on the 1M-triangle city);
  // otherwise depth first.
  //
  // The ordered walk is the silhouette edges' (columns.edge_nodes): pushing a node prefetches what
  // visiting it will read — its children's boxes, or its edges (one cache line each: 64 bytes).
  // Without it, loads missing the cache take about a fifth of the time on the 1M-triangle city;
  // prefetched 64-byte edges run ~20 % more points/s there than unprefetched 112-byte ones.
  template <class LeafItem>
  bool walk(const std::vector<BvhNode>& nodes, bool ordered, LeafItem&& leaf_item) {
    return walk(nodes, ordered, leaf_item, [] { return true; });
  }
  // The same, with leaf_end() called after each leaf's items (false: stop, and return false).
  template <class LeafItem, class LeafEnd>
  bool walk(const std::vector<BvhNode>& nodes, bool ordered, LeafItem&& leaf_item, LeafEnd&& leaf_end) {
    if (nodes.empty()) return true;
    const auto visit = [&](std::uint32_t index, auto&& push) {
      const BvhNode& node = nodes[index];
      if (node_hidden(node.box)) return true;
      if (node.count > 0) {
        for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
          if (!leaf_item(k)) return false;
        return leaf_end();
      }
      push(node.first);
      push(node.first + 1);
      return true;
    };
    if (!ordered) {
      stack.assign(1, 0);
      while (!stack.empty()) {
        const std::uint32_t index = stack.back();
        stack.pop_back();
        if (!visit(index, [&](std::uint32_t c) { stack.push_back(c); })) return false;
      }
      return true;
    }
    // A bucket queue over the squared bound in quarter-octaves (128 buckets covering bounds of
    // about 2⁻¹⁰ … 2⁵, highest first; last in, first out within one): best first up to a factor
    // of 2^⅛ in the bound, at O(1) per node — cheaper than a binary heap and as good at raising
    // the envelope early (a binary heap takes ~10 % more instructions on both cities, half-octave
    // buckets 2 % more than quarter-octaves on the 1M city).
    const auto bucket_of = [&](const Aabb& b) {
      const double d2 = node_distance2(b, p), dz = b.hi.z() - p.z();
      if (!(d2 > 0)) return 127;  // over p's xy: first
      if (!(dz > 0)) return 0;
      // The exponent of dz²/d2 and its first two mantissa bits: 4·⌊log2⌋ + ⌊4·(mantissa − 1)⌋.
      const auto quarter_octaves = int(std::bit_cast<std::uint64_t>(dz * dz / d2) >> 50);
      return std::clamp(quarter_octaves - 4 * 1023 + 84, 1, 126);
    };
    for (int k = 0; k < 128; ++k) buckets[k].clear();
    std::uint64_t filled[2] = {0, 0};
    const auto push = [&](std::uint32_t c) {
      const BvhNode& node = nodes[c];
      if (node.count == 0) {
        __builtin_prefetch(&nodes[node.first]);
        __builtin_prefetch(reinterpret_cast<const char*>(nodes.data() + node.first + 2) - 1);  // the pair's last byte
      } else
        for (std::uint32_t e = node.first; e < node.first + node.count; ++e) __builtin_prefetch(&columns.edges[e]);
      const int k = bucket_of(node.box);
      buckets[k].push_back(c);
      filled[k >> 6] |= std::uint64_t(1) << (k & 63);
    };
    push(0);
    while (filled[0] | filled[1]) {
      const int k = filled[1] ? 127 - __builtin_clzll(filled[1]) : 63 - __builtin_clzll(filled[0]);
      const std::uint32_t index = buckets[k].back();
      buckets[k].pop_back();
      if (buckets[k].empty()) filled[k >> 6] &= ~(std::uint64_t(1) << (k & 63));
      current_bucket = k;
      if (!visit(index, push)) return false;
    }
    return true;
  }

  static double node_distance2(const Aabb& box, const Vec3& p) {
    const double dx = std::max({box.lo.x() - p.x(), p.x() - box.hi.x(), 0.0});
    const double dy = std::max({box.lo.y() - p.y(), p.y() - box.hi.y(), 0.0});
    return dx * dx + dy * dy;
  }

  bool compute(const QueryPoint& q, SkyFactors& out) {
    const Vec3& n = q.normal;
    edge_tests = 0;
    if (!(n.z() >= 0)) return false;
    p = q.position + offset_m * n;

    env.reset();
    const bool horizontal = n.x() == 0 && n.y() == 0;
    if (!horizontal) {
      // The face's own plane bounds its sky on the far side of the normal: a great circle above
      // the horizon there (n_z > 0), or the whole far half (a vertical face: no sky behind it).
      const double tl = diamond_angle(-n.y(), n.x()), tm = diamond_angle(-n.x(), -n.y()), tr = diamond_angle(n.y(), -n.x());
      env.insert_half_turn(n.z() > 0 ? add_circle(n) : HorizonEnvelope::kBlocked, tl, tm, tr);
      env.clear_raised();
    }

    // Below every column solid's base floor: declined at once (and the candidates wholly at or
    // below the lowest base floor are left out of the classification).
    if (columns.column_solids > 0 && p.z() < columns.min_column_floor_z) return false;
    if (under_a_triangle()) return false;
    // The silhouette candidates, the node that can rise highest first. The parts over a soffit
    // higher than p left waiting (add_edge): after each leaf, those now hidden are
    // dropped, and the point is declined as soon as one is not hidden and no node still to come
    // can rise to its lowest elevation (then the envelope will not hide it: it would decline at
    // the end); the rest are tested once the walk is done.
    floating.clear();
    const auto part_hidden = [&](const FloatingPart& f) { return node_hidden(part_box(columns.edges[f.edge], f.t0, f.t1)); };
    const auto leaf_end = [&] {
      if (floating.empty()) return true;
      const double ceiling2 = bucket_ceiling2(current_bucket);
      std::size_t kept = 0;
      for (const FloatingPart& f : floating) {
        if (part_hidden(f)) continue;
        if (f.low2 > ceiling2) return false;
        floating[kept++] = f;
      }
      floating.resize(kept);
      return true;
    };
    const auto edge = [&](std::uint32_t k) { return add_edge(k); };
    current_bucket = 127;
    if (!walk(columns.edge_nodes, true, edge, leaf_end)) return false;
    for (const FloatingPart& f : floating)
      if (!part_hidden(f)) return false;

    if (!others_hidden()) return false;

    if (!env.raised()) {
      // The open sky in front of the face in closed form: SVF (1 + sin β)/2, exposure 1/2 + β/π.
      const double beta = std::asin(std::clamp(n.z(), -1.0, 1.0));
      out.svf = horizontal ? 1.0 : 0.5 * (1 + n.z());
      out.sky_exposure = horizontal ? 1.0 : 0.5 + beta / kPi;
      return true;
    }
    integrate(n, out);
    return true;
  }

  // The visible region as a fan of spherical triangles (zenith, a, b), in counter-clockwise
  // order: on_triangle(a, b) per piece (pieces longer than a quarter turn cut in equal parts, so
  // each spans less than π), on_blocked() per blocked piece (behind a vertical face).
  template <class OnTriangle, class OnBlocked>
  void for_each_fan_triangle(OnTriangle&& on_triangle, OnBlocked&& on_blocked) const {
    env.for_each_run([&](double start, double end, std::uint32_t c) {
      if (c == HorizonEnvelope::kBlocked) {
        on_blocked();
        return;
      }
      const double step = end - start <= 1.0 ? end - start : (end - start) / std::ceil(end - start);
      for (double u0 = start; u0 < end;) {
        const double u1 = std::min(end, u0 + step);
        double ax, ay, bx, by;
        diamond_direction(u0, ax, ay);
        diamond_direction(u1, bx, by);
        on_triangle(Vec3(ax, ay, env.value(c, ax, ay)).normalized(), Vec3(bx, by, env.value(c, bx, by)).normalized());
        u0 = u1;
      }
    });
  }

  void visible_fan(std::vector<SkyFanTriangle>& out) const {
    out.clear();
    for_each_fan_triangle([&](const Vec3& a, const Vec3& b) { out.push_back({a, b}); }, [] {});
  }

  // Lambert's formula over the visible region, as the fan of spherical triangles (zenith, a, b)
  // of for_each_fan_triangle: ½ Σ Θ_e n·ĝ_e over the
  // arcs Z→a, a→b, b→Z (counter-clockwise seen from above). The meridian arcs Z→a and b→Z of
  // neighbouring triangles cancel where the envelope is continuous, so they are summed only at
  // its jumps and beside blocked pieces (and not at all for a horizontal face: n·(Z × v) = 0).
  void integrate(const Vec3& n, SkyFactors& out) const {
    const Vec3 Z(0, 0, 1);
    const bool meridians = n.x() != 0 || n.y() != 0;
    // ½·Θ·n·ĝ of the meridian arc Z→v (the arc v→Z is its negative).
    const auto meridian = [&](const Vec3& v) {
      const Vec3 g = Z.cross(v);
      const double ng = g.norm();
      return ng > 0 ? std::atan2(ng, v.z()) * n.dot(g) / ng : 0.0;
    };
    double phi = 0, omega = 0;
    Vec3 prev_b = Z;
    bool prev_valid = false;
    for_each_fan_triangle(
        [&](const Vec3& a, const Vec3& b) {
          const Vec3 ab = a.cross(b);
          const double nab = ab.norm();
          if (nab > 0) phi += std::atan2(nab, a.dot(b)) * n.dot(ab) / nab;
          if (meridians) {
            const bool continuous = prev_valid && (a - prev_b).lpNorm<Eigen::Infinity>() <= 1e-13;
            if (!continuous) {
              if (prev_valid) phi -= meridian(prev_b);
              phi += meridian(a);
            }
          }
          prev_b = b;
          prev_valid = true;
          // Solid angle of the triangle (Van Oosterom & Strackee 1983).
          omega += 2 * std::atan2(Z.dot(ab), 1 + a.z() + a.dot(b) + b.z());
        },
        [&] {
          if (prev_valid && meridians) phi -= meridian(prev_b);
          prev_valid = false;
        });
    if (prev_valid && meridians) phi -= meridian(prev_b);
    out.svf = std::clamp(0.5 * phi / kPi, 0.0, 1.0);
    out.sky_exposure = std::clamp(omega / (2 * kPi), 0.0, 1.0);
  }
};

void HorizonSvf::visible_fan(std::vector<SkyFanTriangle>& out) const {
  impl_->visible_fan(out);
}

HorizonSvf::HorizonSvf(const Scene& scene, const ColumnScene& columns, double surface_offset_m)
    : impl_(std::make_unique<Impl>(scene, columns, surface_offset_m)) {}
HorizonSvf::~HorizonSvf() = default;
bool HorizonSvf::compute(const QueryPoint& q, SkyFactors& out) {
  return impl_->compute(q, out);
}
const HorizonEnvelope& HorizonSvf::envelope() const {
  return impl_->env;
}
std::size_t HorizonSvf::last_edge_tests() const {
  return impl_->edge_tests;
}
std::size_t HorizonSvf::last_envelope_pieces() const {
  return impl_->env.run_count();
}

}  // namespace skyband
