// Exact band visibility of one point (method.md §2–3): the pencil of sample planes, the culls
// and BVH traversal, the exact plane–triangle crossing, and adaptive refinement. The occluded
// spans of a line are occluded_spans.h, the refined bands' rule band_rule.h, the parallel driver
// band_visibility_driver.cpp. See band_visibility.h for the robustness policy and
// docs/geometry.md for the design.
#include "geometry/bands/band_visibility.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "geometry/bands/band_rule.h"
#include "geometry/bands/occluded_spans.h"
#include "geometry/bands/sky_integral.h"
#include "geometry/core/exact_sign.h"
#include "geometry/core/pseudo_angle.h"

namespace skyband {

namespace {

using band_detail::covered;
using band_detail::first_reaching;
using band_detail::insert_span;
using band_detail::Span;

// A sample half-plane through the point: all directions cos α·x + sin α·u, u = cos δ·h + sin δ·z.
struct Plane {
  double s = 0;       // weight coordinate sin(δ − β)
  double delta = 0;   // radians
  double pdelta = 0;  // pseudo-angle of δ in the (h, z) plane
  double cosd = 1, sind = 0;
  Vec3 m;                                // plane normal −sin δ·h + cos δ·z (world frame, rounded once: *the* plane)
  std::vector<Span> occluded;            // sorted, disjoint, merged
  double line_integral = 0;              // ∫_visible sin²α dα (uniform sky, for refinement)
  double exposure_integral = 0;          // ∫_visible sin α dα (solid angle, for refinement)
  std::vector<VisibleInterval> visible;  // the cache's intervals of this line (finish_plane)
};

// A band of the refined partition, in δ (radians). With refinement, its lines are the two edges
// and the δ-midpoint, combined by the three-node rule of band_rule() below.
struct BandState {
  double d0, d1;
  int e0, c, e1;     // plane indices of the edges and the centre (e0/e1 = −1 without refinement)
  double error = 0;  // estimated error of the band's midpoint value, SVF units
  int depth = 0;
  bool from_breakpoints = false;       // made by a breakpoint split: the next split bisects
  double cached_error = -1;            // band_error() once computed (its lines never change), else −1
  double cached_exposure_error = -1;   // band_exposure_error(), with cached_error
  double unseen_error = 0;             // bound of what geometry between its lines can hide, SVF units
  double unseen_exposure_error = 0;    // the same, exposure units
  double unseen_cut = -1;              // δ through the largest of that geometry (−1: none)
  double unseen_largest = 0;           // its bound
  int sibling = -1;                    // the other half of a bisected band (−1: none)
  double parent_q = 0, parent_qe = 0;  // the bisected band's rule values (SVF, exposure), before π
};

}  // namespace

namespace {
// A leaf whose plane range holds at most this many planes hands its plane and α-ranges to its
// triangles instead of each computing its own (paper building, N = 64: ~5 % faster).
constexpr int kLeafOwnRanges = 4;
}  // namespace

struct BandVisibility::Impl {
  const Scene& scene;
  VisibilityOptions opt;
  double tail_p = 0;  // pseudo-angle of the axis tail (see VisibilityOptions::axis_tail_rad)

  // Per-point state (reused between points: no allocation in steady state).
  Vec3 p;
  BandFrame frame;
  Eigen::Matrix3d local_from_world;  // rows x, h, z
  Eigen::Matrix3d abs_local_from_world;
  std::vector<Plane> planes;
  std::size_t plane_count = 0;
  std::vector<int> active;  // indices of the planes of this pass, sorted by pdelta
  // The same planes, contiguous in that order with what the per-(triangle, plane) loop reads.
  struct ActivePlane {
    Vec3 m;
    double cosd, sind;
    std::vector<Span>* occluded;
  };
  std::vector<ActivePlane> act;
  // Node occlusion test over many planes: consecutive active planes in blocks of kBlock, each
  // with the intersection of their occluded lists (recomputed lazily after an insertion). An
  // α-range lies inside an occluded span on every plane of the block exactly when it lies inside
  // one span of the intersection (the intersection of unions of intervals is a union of
  // intervals, and a connected range inside it lies in one component).
  static constexpr int kBlock = 8;
  struct Block {
    std::vector<Span> common;
    bool dirty = true;
  };
  std::vector<Block> blocks;
  std::vector<Span> scratch;
  std::vector<double> active_keys;  // their pdelta
  std::vector<std::uint32_t> stack;
  // Pencil pseudo-angles of triangle edges (nearly) parallel to the axis that changed some
  // line's occlusion: where f(δ) steps (method.md §2). Refinement splits step bands there.
  std::vector<double> breakpoints;
  double breakpoint_span = 0;  // edges spanning less than this pseudo-angle count as parallel
  // Geometry that no sample line meets (refinement only): nodes and triangles in front of the face
  // and above the horizon whose pencil span holds no plane, with their conservative α-ranges
  // (pseudo-angles). Each can hide at most its span's share of the band it lies in.
  struct Unseen {
    double plo, phi, alo, ahi;
  };
  std::vector<Unseen> unseen;
  bool record_unseen = false;
  std::size_t triangle_tests = 0;
  std::size_t total_planes = 0;

  Impl(const Scene& s, const VisibilityOptions& o) : scene(s), opt(o) {
    tail_p = pseudo_angle(std::cos(opt.axis_tail_rad), std::sin(opt.axis_tail_rad));
  }

  // Per-orientation memo: the frame, the initial bands and the planes' trigonometry depend only
  // on the normal, and neighbouring points (a facade, a street, a rendered wall) share it. Reused
  // only on bit-identical normals and (s, δ), so results are the same as without the memo.
  struct PlaneGeometry {
    double s, delta, pdelta, cosd, sind;
    Vec3 m;
  };
  bool memo_valid = false;
  Vec3 memo_normal;
  BandFrame memo_frame;
  std::vector<PlaneGeometry> memo_planes;  // the planes of the last point(s), in creation order
  std::vector<Band> memo_initial;          // equal_weight_bands(frame, opt.bands)
  std::vector<BandState> memo_states;      // their δ-edges (refinement)
  std::vector<double> memo_centre_delta;   // δ of their weight medians (fixed bands)
  bool memo_states_ready = false;

  void begin_point(const QueryPoint& q) {
    if (!(memo_valid && q.normal == memo_normal)) {
      memo_frame = BandFrame::make(q.normal);
      memo_normal = q.normal;
      memo_valid = true;
      memo_planes.clear();
      memo_initial = equal_weight_bands(memo_frame, opt.bands);
      memo_states.clear();
      memo_states_ready = false;
      memo_centre_delta.clear();
    }
    frame = memo_frame;
    p = q.position + opt.surface_offset_m * frame.normal;
    local_from_world.row(0) = frame.x.transpose();
    local_from_world.row(1) = frame.h.transpose();
    local_from_world.row(2) = frame.z.transpose();
    abs_local_from_world = local_from_world.cwiseAbs();
    plane_count = 0;
    triangle_tests = 0;
    record_unseen = false;
  }

  int add_plane(double s, double delta) {
    if (plane_count == planes.size()) planes.emplace_back();
    Plane& pl = planes[plane_count];
    pl.s = s;
    pl.delta = delta;
    if (plane_count < memo_planes.size() && memo_planes[plane_count].s == s && memo_planes[plane_count].delta == delta) {
      const PlaneGeometry& g = memo_planes[plane_count];
      pl.cosd = g.cosd;
      pl.sind = g.sind;
      pl.pdelta = g.pdelta;
      pl.m = g.m;
    } else {
      pl.cosd = std::cos(delta);
      pl.sind = std::sin(delta);
      pl.pdelta = pseudo_angle(pl.cosd, pl.sind);
      pl.m = -pl.sind * frame.h + pl.cosd * frame.z;
      if (plane_count < memo_planes.size()) memo_planes.resize(plane_count);
      if (plane_count == memo_planes.size()) memo_planes.push_back({s, delta, pl.pdelta, pl.cosd, pl.sind, pl.m});
    }
    pl.occluded.clear();
    pl.line_integral = 0;
    pl.exposure_integral = 0;
    return static_cast<int>(plane_count++);
  }

  // Evaluates the planes [first, plane_count) in one BVH traversal.
  void run_pass(std::size_t first) {
    active.clear();
    for (std::size_t i = first; i < plane_count; ++i) active.push_back(static_cast<int>(i));
    std::sort(active.begin(), active.end(), [&](int a, int b) { return planes[a].pdelta < planes[b].pdelta; });
    active_keys.clear();
    act.clear();
    blocks.resize((plane_count - first + kBlock - 1) / kBlock);
    for (Block& b : blocks) b.dirty = true;
    for (int i : active) {
      active_keys.push_back(planes[i].pdelta);
      act.push_back(ActivePlane{planes[i].m, planes[i].cosd, planes[i].sind, &planes[i].occluded});
    }
    total_planes += active.size();
    if (opt.accelerate) {
      traverse();
    } else {
      const int n = static_cast<int>(active.size());
      for (std::uint32_t t = 0; t < scene.soup().triangles.size(); ++t) process_triangle(t, 0, n);
    }
    for (int i : active) finish_plane(planes[i], opt.tolerance > 0);
  }

  // Range [j0, j1) of active planes whose pseudo-angle lies in [plo, phi] (widened by a margin far
  // larger than the rounding of either side, so the range is a superset; exact predicates decide).
  // Searched within [lo, hi) of the active planes (the range of the enclosing node).
  void plane_range(double plo, double phi, int lo, int hi, int& j0, int& j1) const {
    constexpr double kMargin = 1e-9;
    const double* keys = active_keys.data();
    j0 = static_cast<int>(std::lower_bound(keys + lo, keys + hi, plo - kMargin) - keys);
    j1 = static_cast<int>(std::upper_bound(keys + j0, keys + hi, phi + kMargin) - keys);
  }

  // An axis-aligned box in the point's local frame (x along the axis, h, z), metres.
  struct LocalBox {
    double x_lo, x_hi, h_lo, h_hi, z_lo, z_hi;
  };

  // A BVH node's box in the local frame (conservative: the local box of the rotated world box);
  // false if the node lies wholly below the horizon or wholly behind the face plane (all sample
  // half-planes lie in the closed front half-space), so it cannot hide sky.
  bool node_box(const BvhNode& node, double cos_beta, double sin_beta, LocalBox& b) const {
    if (node.box.hi.z() <= p.z()) return false;
    const Vec3 c = local_from_world * (node.box.centre() - p);
    const Vec3 e = abs_local_from_world * (0.5 * (node.box.hi - node.box.lo));
    b = {c.x() - e.x(), c.x() + e.x(), c.y() - e.y(), c.y() + e.y(), c.z() - e.z(), c.z() + e.z()};
    const double front = cos_beta * (cos_beta >= 0 ? b.h_hi : b.h_lo) + sin_beta * (sin_beta >= 0 ? b.z_hi : b.z_lo);
    return front >= -1e-7;
  }

  // The local bounding box of a triangle's local vertices, in two parts (the (h, z) range decides
  // the pencil span first; the x range is needed only if that passes).
  static void triangle_hz(const Vec3 L[3], LocalBox& b) {
    b.h_lo = std::min(std::min(L[0].y(), L[1].y()), L[2].y());
    b.h_hi = std::max(std::max(L[0].y(), L[1].y()), L[2].y());
    b.z_lo = std::min(std::min(L[0].z(), L[1].z()), L[2].z());
    b.z_hi = std::max(std::max(L[0].z(), L[1].z()), L[2].z());
  }
  static void triangle_x(const Vec3 L[3], LocalBox& b) {
    b.x_lo = std::min(std::min(L[0].x(), L[1].x()), L[2].x());
    b.x_hi = std::max(std::max(L[0].x(), L[1].x()), L[2].x());
  }

  // Conservative pseudo-angle span in the (h, z) plane of an axis-aligned local rectangle,
  // clipped to the sky side z ≥ 0. Returns false if it cannot reach a sky half-plane.
  static bool pencil_span(double h_lo, double h_hi, double z_lo, double z_hi, double& plo, double& phi) {
    if (z_hi <= 0) return false;
    z_lo = std::max(z_lo, 0.0);
    if (z_lo == 0 && h_lo <= 0 && h_hi >= 0) {  // touches the axis: every half-plane
      plo = 0;
      phi = 2;
      return true;
    }
    const double a = pseudo_angle(h_lo, z_lo), b = pseudo_angle(h_lo, z_hi);
    const double c = pseudo_angle(h_hi, z_lo), d = pseudo_angle(h_hi, z_hi);
    plo = std::min(std::min(a, b), std::min(c, d));
    phi = std::max(std::max(a, b), std::max(c, d));
    return true;
  }

  // Conservative α-range (pseudo-angle units) of a local box [lx]×[lh]×[lz] seen along any sample
  // line, clipped to the part outside the axis tails. False if nothing is left.
  bool alpha_range(const LocalBox& b, double& alo, double& ahi, double* raw_lo = nullptr, double* raw_hi = nullptr) const {
    const double lx_lo = b.x_lo, lx_hi = b.x_hi, lh_lo = b.h_lo, lh_hi = b.h_hi, lz_lo = b.z_lo, lz_hi = b.z_hi;
    // ρ is the distance to the axis (the b coordinate of a point on its own sample line).
    const double zl = std::max(lz_lo, 0.0);
    const double dh = lh_lo > 0 ? lh_lo : (lh_hi < 0 ? -lh_hi : 0.0);
    const double rho_min = std::sqrt(dh * dh + zl * zl);
    const double hm = std::max(std::abs(lh_lo), std::abs(lh_hi));
    const double rho_max = std::sqrt(hm * hm + lz_hi * lz_hi);
    // The angle of (a, ρ) falls with a; it rises with ρ where a > 0 and falls where a < 0. The
    // bounds are widened by far more than their rounding (they only cull).
    alo = pseudo_angle(lx_hi, lx_hi >= 0 ? rho_min : rho_max) - 1e-12;
    ahi = pseudo_angle(lx_lo, lx_lo >= 0 ? rho_max : rho_min) + 1e-12;
    if (raw_lo) *raw_lo = alo;
    if (raw_hi) *raw_hi = ahi;
    alo = std::max(alo, tail_p);
    ahi = std::min(ahi, 2.0 - tail_p);
    return alo < ahi;
  }

  // Intersection of the occluded lists of active planes [j, j + kBlock) into b.common.
  void intersect_block(Block& b, int j) {
    b.common = *act[j].occluded;
    for (int k = j + 1; k < j + kBlock && !b.common.empty(); ++k) {
      const std::vector<Span>& v = *act[k].occluded;
      scratch.clear();
      std::size_t x = 0, y = 0;
      while (x < b.common.size() && y < v.size()) {
        const double lo = std::max(b.common[x].lo, v[y].lo), hi = std::min(b.common[x].hi, v[y].hi);
        if (lo <= hi) scratch.push_back(Span{lo, hi});
        if (b.common[x].hi < v[y].hi)
          ++x;
        else
          ++y;
      }
      b.common.swap(scratch);
    }
    b.dirty = false;
  }

  // Is [alo, ahi] inside an occluded span on every active plane of [j0, j1)? The first plane is
  // tried alone (most nodes fail there); then whole blocks use their intersections.
  bool covered_on_all(int j0, int j1, double alo, double ahi) {
    if (!covered(*act[j0].occluded, alo, ahi)) return false;
    for (int j = j0 + 1; j < j1;) {
      if (j % kBlock == 0 && j + kBlock <= j1) {
        Block& b = blocks[j / kBlock];
        if (b.dirty) intersect_block(b, j);
        if (!covered(b.common, alo, ahi)) return false;
        j += kBlock;
      } else {
        if (!covered(*act[j].occluded, alo, ahi)) return false;
        ++j;
      }
    }
    return true;
  }

  // Front-to-back order: the child whose box centre is nearer the point is popped first.
  [[gnu::always_inline]] void push_children_near_first(const BvhNode& node) {
    const auto& nodes = scene.bvh_nodes();
    const std::uint32_t l = node.first, r = node.first + 1;
    const double dl = (nodes[l].box.centre() - p).squaredNorm();
    const double dr = (nodes[r].box.centre() - p).squaredNorm();
    stack.push_back(dl < dr ? r : l);
    stack.push_back(dl < dr ? l : r);
  }

  // What a BVH walk does with a node that passed the common culls.
  enum class Visit { kSkip, kDescend, kStop };

  // Front-to-back walk from the root. Nodes wholly below the horizon, behind the face plane or
  // outside every sample half-plane are culled here; `visit(node, local_box, plo, phi)` (the
  // node's pencil span) decides the rest: kDescend opens an inner node, kStop ends the walk.
  // Returns true if the walk was stopped.
  template <class F>
  bool walk_bvh(F&& visit) {
    const auto& nodes = scene.bvh_nodes();
    if (nodes.empty()) return false;
    const double cb = std::cos(frame.beta_rad), sb = std::sin(frame.beta_rad);
    stack.clear();
    stack.push_back(0);
    while (!stack.empty()) {
      const BvhNode& node = nodes[stack.back()];
      stack.pop_back();
      LocalBox b;
      if (!node_box(node, cb, sb, b)) continue;
      double plo, phi;
      if (!pencil_span(b.h_lo, b.h_hi, b.z_lo, b.z_hi, plo, phi)) continue;
      const Visit v = visit(node, b, plo, phi);
      if (v == Visit::kStop) return true;
      if (v == Visit::kDescend && node.count == 0) push_children_near_first(node);
    }
    return false;
  }

  void traverse() {
    if (active.empty()) return;
    const auto& order = scene.bvh_triangle_order();
    walk_bvh([&](const BvhNode& node, const LocalBox& b, double plo, double phi) {
      int j0, j1;
      plane_range(plo, phi, 0, static_cast<int>(active_keys.size()), j0, j1);
      double alo, ahi;
      if (j0 >= j1) {
        if (record_unseen && alpha_range(b, alo, ahi)) unseen.push_back({plo, phi, alo, ahi});
        return Visit::kSkip;
      }
      if (!alpha_range(b, alo, ahi)) return Visit::kSkip;  // only in the axis tails
      if (covered_on_all(j0, j1, alo, ahi)) return Visit::kSkip;
      if (node.count == 0) return Visit::kDescend;
      // A leaf reaching few planes hands its ranges down: cheaper than each triangle's own.
      // Not where the leaf's α-range was cut by an axis tail: whether a triangle lies wholly in
      // a tail is decided on its own range, so the result does not depend on the BVH.
      const bool own = j1 - j0 > kLeafOwnRanges || alo == tail_p || ahi == 2.0 - tail_p;
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) process_triangle(order[i], j0, j1, own, alo, ahi);
      return Visit::kSkip;
    });
  }

  // A triangle seen from the point: its vertices, their offsets d = V − P, the same in the local
  // frame (L), and their global ids (canonical crossing order).
  struct PointTriangle {
    const Vec3* v[3];
    Vec3 d[3], L[3];
    // Edge k joins vertices k and k+1; from[k] is the one with the smaller global id, to[k] the
    // other: the canonical order in which crossings are interpolated (crossing_segment).
    std::uint8_t from[3], to[3];
  };

  // Fills `tr` for triangle t; false if it lies wholly at or below the point's horizon (exact:
  // fl(a − b) keeps the sign of a − b), where it hides no sky.
  bool point_triangle(std::uint32_t t, PointTriangle& tr) const {
    const auto& soup = scene.soup();
    const auto& tri = soup.triangles[t];
    for (int k = 0; k < 3; ++k) tr.v[k] = &soup.vertices[tri[k]];
    if (tr.v[0]->z() <= p.z() && tr.v[1]->z() <= p.z() && tr.v[2]->z() <= p.z()) return false;
    for (int k = 0; k < 3; ++k) {
      tr.d[k] = *tr.v[k] - p;
      tr.L[k] = local_from_world * tr.d[k];
      const int k2 = (k + 1) % 3;
      const bool swap = tri[k2] < tri[k];
      tr.from[k] = static_cast<std::uint8_t>(swap ? k2 : k);
      tr.to[k] = static_cast<std::uint8_t>(swap ? k : k2);
    }
    return true;
  }

  // own_ranges = false: use the enclosing leaf's plane range [j0, j1) and α-range [alo, ahi]
  // (conservative for its triangles) instead of the triangle's own, tighter ones.
  void process_triangle(std::uint32_t t, int j0, int j1, bool own_ranges = true, double leaf_alo = 0, double leaf_ahi = 2) {
    PointTriangle tr;
    if (!point_triangle(t, tr)) return;
    ++triangle_tests;
    const Vec3* L = tr.L;
    double alo = leaf_alo, ahi = leaf_ahi;
    int k0 = j0, k1 = j1;
    if (own_ranges) {
      double plo, phi;
      LocalBox tb;
      triangle_hz(L, tb);
      if (!pencil_span(tb.h_lo, tb.h_hi, tb.z_lo, tb.z_hi, plo, phi)) return;
      triangle_x(L, tb);
      if (!alpha_range(tb, alo, ahi)) return;
      plane_range(plo, phi, j0, j1, k0, k1);
      if (k0 >= k1) {
        if (record_unseen) unseen.push_back({plo, phi, alo, ahi});
        return;
      }
    }
    bool contributed = false;
    bool edge_on_checked = false;
    bool met = false;  // some plane crossed it, or was hidden over its α-range
    for (int j = k0; j < k1; ++j) {
      const ActivePlane& pl = act[j];
      std::vector<Span>& occluded = *pl.occluded;
      if (covered(occluded, alo, ahi)) {  // already hidden on this line (front-to-back)
        met = true;
        continue;
      }
      if (!edge_on_checked) {
        // Exact: a triangle whose plane contains the point is seen edge-on: it hides a set of
        // measure zero (this is also what keeps a face from hiding the sky above itself).
        // Tested lazily: most triangles that get this far are hidden on every plane anyway.
        if (exact_orientation(*tr.v[0], *tr.v[1], *tr.v[2], p) == 0) return;
        edge_on_checked = true;
      }
      double ea[2], eb[2];
      if (!crossing_segment(pl, tr, ea, eb)) continue;
      met = true;
      if (add_segment(occluded, ea[0], eb[0], ea[1], eb[1])) {
        contributed = true;
        blocks[j / kBlock].dirty = true;
      }
    }
    if (!met && !own_ranges && record_unseen) {
      // Between the leaf's planes: recorded with its own ranges (whether a plane lies inside
      // them is decided with all the point's planes, unseen_bounds).
      double plo, phi;
      LocalBox tb;
      triangle_hz(L, tb);
      triangle_x(L, tb);
      if (pencil_span(tb.h_lo, tb.h_hi, tb.z_lo, tb.z_hi, plo, phi) && alpha_range(tb, alo, ahi))
        unseen.push_back({plo, phi, alo, ahi});
    }
    if (contributed && breakpoint_span > 0) {
      for (int k = 0; k < 3; ++k) {
        const Vec3& a = L[k];
        const Vec3& b = L[(k + 1) % 3];
        if (a.z() <= 0 || b.z() <= 0) continue;
        const double pa = pseudo_angle(a.y(), a.z()), pb = pseudo_angle(b.y(), b.z());
        if (std::abs(pa - pb) < breakpoint_span) {
          breakpoints.push_back(pa);
          if (pb != pa) breakpoints.push_back(pb);
        }
      }
    }
  }

  // The section of a triangle seen from the point (vertex offsets d, the same in the local frame L,
  // canonical edge order from/to) by the plane: its two in-plane end points (a along the axis, b
  // across it). False unless the triangle crosses the plane, i.e. has vertices strictly on both sides
  // (exact signs); touching it at a vertex or along an edge hides nothing the neighbours do not
  // (docs/geometry.md).
  static bool crossing_segment(const ActivePlane& pl, const PointTriangle& tr, double ea[2], double eb[2]) {
    const Vec3* d = tr.d;
    const Vec3* L = tr.L;
    double val[3];
    int sg[3];
    for (int k = 0; k < 3; ++k) sg[k] = exact_dot_sign(pl.m, d[k], val[k]);
    if (!((sg[0] > 0 || sg[1] > 0 || sg[2] > 0) && (sg[0] < 0 || sg[1] < 0 || sg[2] < 0))) return false;
    int n = 0;
    for (int k = 0; k < 3 && n < 2; ++k) {
      if (sg[k] == 0) {
        ea[n] = L[k].x();
        eb[n] = L[k].y() * pl.cosd + L[k].z() * pl.sind;
        ++n;
      }
    }
    for (int k = 0; k < 3 && n < 2; ++k) {
      const int k2 = (k + 1) % 3;
      if (sg[k] * sg[k2] >= 0) continue;
      // Canonical order (by global vertex id): both triangles sharing this edge compute the
      // bit-identical crossing point.
      const int a = tr.from[k], b = tr.to[k];
      double t = val[a] / (val[a] - val[b]);
      t = std::clamp(t, 0.0, 1.0);
      const Vec3 q = L[a] + t * (L[b] - L[a]);
      ea[n] = q.x();
      eb[n] = q.y() * pl.cosd + q.z() * pl.sind;
      ++n;
    }
    return n == 2;
  }

  // The in-plane segment (a, b) → occluded pseudo-angle span, clipped to the sky side b ≥ 0.
  static bool add_segment(std::vector<Span>& occluded, double a0, double b0, double a1, double b1) {
    double lo, hi;
    return segment_span(a0, b0, a1, b1, lo, hi) && insert_span(occluded, lo, hi);
  }

  // The pseudo-angle span [lo, hi] (hi > lo) that the in-plane segment (a, b) hides, clipped to
  // the sky side b ≥ 0; false if it hides nothing.
  static bool segment_span(double a0, double b0, double a1, double b1, double& lo, double& hi) {
    if (b0 <= 0 && b1 <= 0) return false;
    double p0, p1;
    if (b0 < 0 || b1 < 0) {
      // Clip at the axis: the cut point lies on the axis, at α = 0 (a > 0) or α = π (a < 0).
      const double t = b0 / (b0 - b1);
      const double ac = a0 + t * (a1 - a0);
      if (ac == 0) return false;  // the segment passes through the point itself
      const double pc = ac > 0 ? 0.0 : 2.0;
      if (b0 < 0) {
        p0 = pc;
        p1 = pseudo_angle(a1, b1);
      } else {
        p0 = pseudo_angle(a0, b0);
        p1 = pc;
      }
    } else {
      if ((a0 == 0 && b0 == 0) || (a1 == 0 && b1 == 0)) return false;  // an end point at the point
      p0 = pseudo_angle(a0, b0);
      p1 = pseudo_angle(a1, b1);
    }
    lo = std::min(p0, p1);
    hi = std::max(p0, p1);
    return hi > lo;
  }

  // The line's visible α-intervals in radians (the gaps between occluded spans, each end
  // converted once) and, when refining (`with_integral`), their uniform-sky integral
  // ∫_visible sin²α dα, which only the refinement's error estimate reads.
  static void finish_plane(Plane& pl, bool with_integral) {
    double f = 0, g = 0, prev = 0;
    pl.visible.clear();
    // f integrates up to π itself at the far end (not to angle_of_pseudo(2)).
    auto gap = [&](double lo, double hi, bool last) {
      const double lo_rad = angle_of_pseudo(lo), hi_rad = angle_of_pseudo(hi);
      if (with_integral) {
        f += uniform_sky_primitive(last ? kPi : hi_rad) - uniform_sky_primitive(lo_rad);
        g += std::cos(lo_rad) - (last ? -1.0 : std::cos(hi_rad));
      }
      const float a0 = static_cast<float>(lo_rad);
      const float a1 = static_cast<float>(hi_rad);
      if (a1 > a0) pl.visible.push_back({a0, a1});
    };
    for (const Span& s : pl.occluded) {
      if (s.lo > prev) gap(prev, s.lo, false);
      prev = std::max(prev, s.hi);
    }
    if (prev < 2) gap(prev, 2, true);
    pl.line_integral = f;
    pl.exposure_integral = g;
  }

  void visible_intervals(const Plane& pl, std::vector<VisibleInterval>& out) const {
    out.insert(out.end(), pl.visible.begin(), pl.visible.end());
  }

  static double pseudo_of_delta(double d) { return pseudo_angle(std::cos(d), std::sin(d)); }

  double narrowest_band_pseudo(const std::vector<BandState>& bands) const {
    double w = 2;
    for (const BandState& b : bands) w = std::min(w, pseudo_of_delta(b.d1) - pseudo_of_delta(b.d0));
    return w;
  }

  // Is the band against the face's own plane or the horizon (δ − β = ±π/2, or δ = 0 or π)? There
  // the weight of one side vanishes or the lines graze: neighbours' walls coplanar with the face
  // make grazing steps that three lines can miss, and a low skyline far away shows on the line at
  // the horizon only — the lines above pass over it.
  bool against_a_plane(const BandState& b) const {
    const double edge = 1e-9 + 1e-9 * (frame.delta_max_rad - frame.delta_min_rad);
    return b.d1 >= frame.delta_max_rad - edge || b.d0 <= frame.delta_min_rad + edge;
  }

  // SVF: |rule − midpoint|/π, the midpoint value's error where f is smooth, and a generous bound
  // on the three-node value the cache carries (a step inside the band is located exactly
  // instead, split_at_breakpoints); against a plane at least the full variation of its lines.
  // The band's rule values: ∫ f cos(δ − β) dδ (three-node rule) and ∫ g dδ (Simpson).
  double band_q(const BandState& b) const {
    const BandRule r = band_rule(b.d0, b.d1, frame.beta_rad);
    return r.w0 * planes[b.e0].line_integral + r.wm * planes[b.c].line_integral + r.w1 * planes[b.e1].line_integral;
  }
  double band_qe(const BandState& b) const {
    return (b.d1 - b.d0) * (planes[b.e0].exposure_integral + 4 * planes[b.c].exposure_integral + planes[b.e1].exposure_integral) /
           6;
  }

  double band_error(const BandState& b) const {
    if (b.e0 < 0) return 0;
    const BandRule r = band_rule(b.d0, b.d1, frame.beta_rad);
    double e = std::abs(band_q(b) - r.m0 * planes[b.c].line_integral) / kPi;
    if (against_a_plane(b)) {
      const double f0 = planes[b.e0].line_integral, fc = planes[b.c].line_integral, f1 = planes[b.e1].line_integral;
      e = std::max(e, r.m0 * (std::max({f0, fc, f1}) - std::min({f0, fc, f1})) / kPi);
    }
    return e;
  }

  // Sky exposure (solid angle / 2π), the same way for g(δ) = ∫_visible sin α dα with the weight
  // dδ: |Simpson − midpoint|/2π, and the full variation against a plane.
  double band_exposure_error(const BandState& b) const {
    if (b.e0 < 0) return 0;
    const double w = b.d1 - b.d0;
    const double g0 = planes[b.e0].exposure_integral, gc = planes[b.c].exposure_integral, g1 = planes[b.e1].exposure_integral;
    double e = std::abs(band_qe(b) - w * gc) / (2 * kPi);
    if (against_a_plane(b)) e = std::max(e, w * (std::max({g0, gc, g1}) - std::min({g0, gc, g1})) / (2 * kPi));
    return e;
  }

  double s_of(double d) const { return std::sin(d - frame.beta_rad); }

  // Per band, a bound of what the geometry no line meets can hide (Impl::unseen): a node or
  // triangle whose pencil span lies between two neighbouring lines, both clear of occlusion over
  // its α-range, hides at most the directions of that span and that α-range, ∫∫ sin²α cos(δ − β)
  // dα dδ / π of the SVF and ∫∫ sin α dα dδ / 2π of the exposure. A building floating just above
  // the point's horizontal, seen between the horizon's line (which passes under it) and the next
  // (which passes over it), is the case. Records a later line meets are dropped: they were
  // traversed with it. Each band's bounds are capped at everything it holds.
  static bool clear(const std::vector<Span>& v, double lo, double hi) {
    const auto it = std::lower_bound(v.begin(), v.end(), lo, [](const Span& s, double x) { return s.hi < x; });
    return it == v.end() || it->lo > hi;
  }
  std::vector<std::pair<double, int>> plane_keys;  // scratch: (pdelta, plane) of every plane, sorted
  std::vector<int> band_by_d0;                     // scratch
  void unseen_bounds(std::vector<BandState>& bands) {
    for (BandState& b : bands) b.unseen_error = b.unseen_exposure_error = 0, b.unseen_cut = -1, b.unseen_largest = 0;
    if (unseen.empty()) return;
    // A node skipped in one pass is skipped again in the next (with the same box): once each.
    std::sort(unseen.begin(), unseen.end(), [](const Unseen& a, const Unseen& b) {
      return std::tie(a.plo, a.phi, a.alo, a.ahi) < std::tie(b.plo, b.phi, b.alo, b.ahi);
    });
    unseen.erase(std::unique(unseen.begin(), unseen.end(),
                             [](const Unseen& a, const Unseen& b) {
                               return a.plo == b.plo && a.phi == b.phi && a.alo == b.alo && a.ahi == b.ahi;
                             }),
                 unseen.end());
    constexpr double kMargin = 1e-9;  // as plane_range
    plane_keys.clear();
    for (std::size_t i = 0; i < plane_count; ++i) plane_keys.emplace_back(planes[i].pdelta, static_cast<int>(i));
    std::sort(plane_keys.begin(), plane_keys.end());
    band_by_d0.resize(bands.size());
    for (std::size_t i = 0; i < bands.size(); ++i) band_by_d0[i] = static_cast<int>(i);
    std::sort(band_by_d0.begin(), band_by_d0.end(), [&](int a, int b) { return bands[a].d0 < bands[b].d0; });
    std::size_t kept = 0;
    for (const Unseen& u : unseen) {
      const auto above = std::lower_bound(plane_keys.begin(), plane_keys.end(), std::make_pair(u.plo - kMargin, -1));
      if (above != plane_keys.end() && above->first <= u.phi + kMargin) continue;  // a line meets it now
      unseen[kept++] = u;
      // Counted only where both neighbouring lines are clear over its α-range: where either meets
      // something there, the lines see the change (a roof between two lines rises from a wall
      // the lower one meets) and their variation estimates it.
      if (above == plane_keys.begin() || above == plane_keys.end() ||
          !clear(planes[(above - 1)->second].occluded, u.alo, u.ahi) || !clear(planes[above->second].occluded, u.alo, u.ahi))
        continue;
      const double d_lo = angle_of_pseudo(u.plo), d_hi = angle_of_pseudo(u.phi);
      const double d_mid = 0.5 * (d_lo + d_hi);
      const auto it =
          std::upper_bound(band_by_d0.begin(), band_by_d0.end(), d_mid, [&](double d, int b) { return d < bands[b].d0; });
      if (it == band_by_d0.begin()) continue;
      BandState& b = bands[*(it - 1)];
      const double lo = std::max(d_lo, b.d0), hi = std::min(d_hi, b.d1);
      if (!(hi > lo)) continue;
      const double a0 = angle_of_pseudo(u.alo), a1 = angle_of_pseudo(u.ahi);
      const double svf = (s_of(hi) - s_of(lo)) * (uniform_sky_primitive(a1) - uniform_sky_primitive(a0)) / kPi;
      const double exposure = (hi - lo) * (std::cos(a0) - std::cos(a1)) / (2 * kPi);
      b.unseen_error += svf;
      b.unseen_exposure_error += exposure;
      if (std::max(svf, exposure) > b.unseen_largest) b.unseen_largest = std::max(svf, exposure), b.unseen_cut = 0.5 * (lo + hi);
    }
    unseen.resize(kept);
    for (BandState& b : bands) {
      b.unseen_error = std::min(b.unseen_error, (s_of(b.d1) - s_of(b.d0)) * 0.5);  // ∫ sin²α dα over [0, π] = π/2
      b.unseen_exposure_error = std::min(b.unseen_exposure_error, (b.d1 - b.d0) / kPi);
    }
  }

  void compute(const QueryPoint& q, VisibilityCache::PointResult& out) {
    begin_point(q);
    out.normal = q.normal;
    out.bands.clear();
    out.intervals.clear();
    const std::vector<Band>& initial = memo_initial;
    if (initial.empty()) return;
    const bool refine = opt.tolerance > 0;
    if (!refine) {
      // The paper's bands: one sample plane at each band's weight median (seed eq. 1, d_l = 1/N).
      const std::size_t first_plane = plane_count;
      if (memo_centre_delta.empty())
        for (const Band& b : initial) memo_centre_delta.push_back(frame.delta_at(b.s_centre()));
      for (std::size_t i = 0; i < initial.size(); ++i) add_plane(initial[i].s_centre(), memo_centre_delta[i]);
      run_pass(0);
      for (std::size_t i = 0; i < initial.size(); ++i)
        emit_record(out, initial[i].s0, initial[i].s1, static_cast<int>(first_plane + i),
                    frame.delta_at(initial[i].s1) - frame.delta_at(initial[i].s0));
      return;
    }
    if (!memo_states_ready) {
      for (const Band& b : initial) memo_states.push_back(BandState{frame.delta_at(b.s0), frame.delta_at(b.s1), -1, -1, -1});
      memo_states.front().d0 = frame.delta_min_rad;
      memo_states.back().d1 = frame.delta_max_rad;
      memo_states_ready = true;
    }
    std::vector<BandState> bands;
    bands.reserve(initial.size() * 2);
    bands.assign(memo_states.begin(), memo_states.end());
    // The outermost edge lines are sampled just inside the face's sky: exactly at δ_min/δ_max lie
    // the horizon plane and the face's own plane, where coplanar ground or neighbouring walls
    // give f a value that is the limit of neither side.
    const double eta = 1e-9 * (frame.delta_max_rad - frame.delta_min_rad);
    int prev_edge = add_plane_at(bands.front().d0 + eta);
    for (std::size_t i = 0; i < bands.size(); ++i) {
      BandState& b = bands[i];
      b.e0 = prev_edge;
      b.c = add_plane_at(0.5 * (b.d0 + b.d1));
      b.e1 = add_plane_at(i + 1 == bands.size() ? b.d1 - eta : b.d1);
      prev_edge = b.e1;
    }
    breakpoints.clear();
    // An edge counts as parallel to the axis when its pencil span is below 1/8 of the narrowest
    // initial band's: then f(δ) changes within a small part of one band, like a step.
    breakpoint_span = 0.125 * narrowest_band_pseudo(bands);
    unseen.clear();
    record_unseen = true;
    run_pass(0);
    refine_bands(bands);
    std::sort(bands.begin(), bands.end(), [](const BandState& a, const BandState& b) { return a.d0 < b.d0; });
    // Each band's three lines carry the rule's weights, written as consecutive records whose
    // widths in s are the weights (so Σ widths = W and each record's s-range stays inside its
    // band); an edge line shared with the next band becomes one record. A band whose rule has a
    // negative weight (possible only for wide bands against the face's own plane) falls back to
    // its midpoint line.
    // The exposure weights are Simpson's in δ (Δδ/6, 4Δδ/6, Δδ/6): the solid angle's weight is dδ.
    int open_plane = -1;
    double open_s0 = 0, open_s1 = 0, open_w = 0;
    for (const BandState& b : bands) {
      const BandRule r = band_rule(b.d0, b.d1, frame.beta_rad);
      const double s0 = s_of(b.d0), s1 = s_of(b.d1), dd = b.d1 - b.d0;
      const bool rule_ok = r.w0 >= 0 && r.wm >= 0 && r.w1 >= 0;
      if (open_plane >= 0 && !(rule_ok && open_plane == b.e0)) {
        emit_record(out, open_s0, open_s1, open_plane, open_w);
        open_plane = -1;
      }
      if (!rule_ok) {
        emit_record(out, s0, s1, b.c, dd);
        continue;
      }
      const double a = s0 + r.w0, c = a + r.wm;
      if (open_plane == b.e0) {
        emit_record(out, open_s0, a, b.e0, open_w + dd / 6);
      } else {
        emit_record(out, s0, a, b.e0, dd / 6);
      }
      emit_record(out, a, c, b.c, 4 * dd / 6);
      open_plane = b.e1;
      open_s0 = c;
      open_s1 = s1;
      open_w = dd / 6;
    }
    if (open_plane >= 0) emit_record(out, open_s0, open_s1, open_plane, open_w);
  }

  int add_plane_at(double delta) { return add_plane(s_of(delta), delta); }

  void emit_record(VisibilityCache::PointResult& out, double s0, double s1, int plane, double exposure_weight) const {
    BandRecord r;
    r.s0 = static_cast<float>(s0);
    r.s1 = static_cast<float>(s1);
    r.exposure_weight = static_cast<float>(exposure_weight);
    r.delta_rad = static_cast<float>(planes[plane].delta);
    r.first_interval = static_cast<std::uint32_t>(out.intervals.size());
    out.bands.push_back(r);
    visible_intervals(planes[plane], out.intervals);
  }

  // Adaptive refinement: split the bands whose estimated error is largest until the estimated
  // total is below the tolerance — at located steps when the band shows one, else at the
  // δ-midpoint (whose line becomes an edge of both halves: two new planes per split).
  void refine_bands(std::vector<BandState>& bands) {
    // The estimates are estimates: refinement goes on to half the tolerance, so that the errors
    // themselves stay within it (measured on city, terrain and low-skyline points against the
    // exact union: with the full tolerance as the criterion the largest error is 1.15× the
    // estimated total).
    constexpr double kSafety = 0.5;
    // Each half of a bisected band takes at least this share of the error its parent's rule made,
    // measured by the halves (adaptive quadrature's check of the whole against its halves, as in
    // adaptive Simpson [Lyness69]).
    constexpr double kHalfShare = 0.5;
    for (int pass = 0; pass < opt.max_refine_depth; ++pass) {
      // Both estimated totals, the SVF's and the exposure's, must be within the tolerance; a
      // band's error for the choice of splits is the larger share of either.
      double total_svf = 0, total_exposure = 0;
      unseen_bounds(bands);
      for (BandState& b : bands) {
        if (b.cached_error < 0) {
          b.cached_error = band_error(b);
          b.cached_exposure_error = band_exposure_error(b);
          if (b.sibling >= 0) {
            // The halves against the whole: the error the parent's rule actually made, measured.
            // Where f steps more than once inside a band, its three lines can agree with a smooth
            // f (estimate ~0) while the halves disagree with it; each half takes a share.
            const BandState& s = bands[b.sibling];
            b.cached_error = std::max(b.cached_error, kHalfShare * std::abs(band_q(b) + band_q(s) - b.parent_q) / kPi);
            b.cached_exposure_error =
                std::max(b.cached_exposure_error, kHalfShare * std::abs(band_qe(b) + band_qe(s) - b.parent_qe) / (2 * kPi));
          }
        }
        total_svf += b.cached_error + b.unseen_error;
        total_exposure += b.cached_exposure_error + b.unseen_exposure_error;
      }
      if (total_svf <= kSafety * opt.tolerance && total_exposure <= kSafety * opt.tolerance) return;
      const double total = std::max(total_svf, total_exposure);
      for (BandState& b : bands)
        b.error = std::max(b.cached_error + b.unseen_error, b.cached_exposure_error + b.unseen_exposure_error);
      std::vector<int> order(bands.size());
      for (std::size_t i = 0; i < bands.size(); ++i) order[i] = static_cast<int>(i);
      std::sort(order.begin(), order.end(),
                [&](int a, int b) { return bands[a].error > bands[b].error || (bands[a].error == bands[b].error && a < b); });
      std::sort(breakpoints.begin(), breakpoints.end());
      breakpoints.erase(std::unique(breakpoints.begin(), breakpoints.end()), breakpoints.end());
      const std::size_t first_new = plane_count;
      double remaining = total;
      std::vector<BandState> added;
      for (int i : order) {
        // Split the largest errors first until the rest (and the halves, assumed ≤ half each)
        // would fit the budget.
        if (remaining <= 0.5 * kSafety * opt.tolerance) break;
        BandState& b = bands[i];
        if (b.error <= 0 || b.depth >= opt.max_refine_depth) continue;
        if (b.unseen_cut > b.d0 && b.unseen_cut < b.d1 &&
            std::max(b.unseen_error, b.unseen_exposure_error) > std::max(b.cached_error, b.cached_exposure_error)) {
          // What no line meets dominates: cut the band through the largest of it (a line there
          // meets it, or its ancestors' boxes give way to tighter ones).
          remaining -= std::max(b.unseen_error, b.unseen_exposure_error);
          split_in_two(bands, i, b.unseen_cut, add_plane_at(b.unseen_cut), added);
          continue;
        }
        remaining -= 0.5 * b.error;
        if (split_at_breakpoints(b, added)) continue;
        split_in_two(bands, i, 0.5 * (b.d0 + b.d1), b.c, added);  // its centre line becomes an edge
      }
      if (plane_count == first_new) return;
      bands.insert(bands.end(), added.begin(), added.end());
      run_pass(first_new);
    }
  }

  // Splits band i at δ = d, whose line is plane `cut`: bands[i] becomes the lower half, the upper
  // one is appended to `added` (after `bands` in the next pass). Each half gets a centre line and
  // remembers the whole's rule values for the halves check.
  void split_in_two(std::vector<BandState>& bands, int i, double d, int cut, std::vector<BandState>& added) {
    BandState& b = bands[i];
    BandState left{b.d0, d, b.e0, -1, cut, 0, b.depth + 1};
    BandState right{d, b.d1, cut, -1, b.e1, 0, b.depth + 1};
    left.c = add_plane_at(0.5 * (left.d0 + left.d1));
    right.c = add_plane_at(0.5 * (right.d0 + right.d1));
    left.parent_q = right.parent_q = band_q(b);
    left.parent_qe = right.parent_qe = band_qe(b);
    left.sibling = static_cast<int>(bands.size() + added.size());
    right.sibling = i;
    b = left;
    added.push_back(right);
  }

  // Splits band b at the recorded breakpoints inside the half where its lines show a step (at
  // most 4). Each piece gets one-sided edge planes just beside the breakpoint (f jumps there, so
  // its value exactly on it says nothing about either side) and a centre plane.
  bool split_at_breakpoints(BandState& b, std::vector<BandState>& added) {
    if (b.from_breakpoints || b.e0 < 0) return false;
    // Step signature: the centre line agrees with one edge line, so the change is in the other
    // half; a smooth band (centre between the edges) is bisected instead.
    const double f0 = planes[b.e0].line_integral, fc = planes[b.c].line_integral, f1 = planes[b.e1].line_integral;
    if (!(std::abs(f1 - f0) > 1e-12)) return false;
    const double r = (fc - f0) / (f1 - f0);
    if (r > 0.1 && r < 0.9) return false;
    const double dm = 0.5 * (b.d0 + b.d1);
    const double lo_d = r <= 0.1 ? dm : b.d0, hi_d = r <= 0.1 ? b.d1 : dm;
    const double p0 = pseudo_of_delta(lo_d), p1 = pseudo_of_delta(hi_d);
    const double margin = 1e-6 * (p1 - p0);
    auto first = std::upper_bound(breakpoints.begin(), breakpoints.end(), p0 + margin);
    auto last = std::lower_bound(breakpoints.begin(), breakpoints.end(), p1 - margin);
    if (first >= last) return false;
    double cuts[4];
    int n = 0;
    for (auto it = first; it != last && n < 4; ++it) {
      const double d = angle_of_pseudo(*it);
      if (d <= b.d0 || d >= b.d1 || (n > 0 && d <= cuts[n - 1])) continue;
      cuts[n++] = d;
    }
    if (n == 0) return false;
    const double eta = 1e-9 * (b.d1 - b.d0);
    double lo = b.d0;
    int lo_edge = b.e0;
    BandState pieces[5];
    for (int k = 0; k <= n; ++k) {
      const double hi = k < n ? cuts[k] : b.d1;
      BandState& piece = pieces[k];
      piece = BandState{lo, hi, lo_edge, -1, -1, 0, b.depth + 1, true};
      piece.c = add_plane_at(0.5 * (lo + hi));
      if (k < n) {
        piece.e1 = add_plane_at(hi - eta);
        lo_edge = add_plane_at(hi + eta);
      } else {
        piece.e1 = b.e1;
      }
      lo = hi;
    }
    b = pieces[0];
    added.insert(added.end(), pieces + 1, pieces + n + 1);
    return true;
  }

  // Is pseudo-angle pa of plane 0's line hidden? The union the full pass would build contains pa
  // exactly when one inserted span does (closed spans), so this tests the same triangles with
  // the same predicates and constructions as process_triangle/add_segment, culling nodes and
  // triangles whose α-range cannot contain pa, and stops at the first span that contains it.
  bool plane_blocked_at(double pa) {
    const Plane& pl0 = planes[0];
    const ActivePlane pl{pl0.m, pl0.cosd, pl0.sind, nullptr};
    constexpr double kMargin = 1e-9;  // as plane_range
    const auto& order = scene.bvh_triangle_order();
    // The sample plane inside the conservative pencil span [plo, phi], and pa inside the
    // α-range of the box before its axis-tail clip (false: cannot hide pa, or only in a tail).
    auto may_hide = [&](const LocalBox& b, double plo, double phi) {
      if (pl0.pdelta < plo - kMargin || pl0.pdelta > phi + kMargin) return false;
      double alo, ahi, rlo, rhi;
      return alpha_range(b, alo, ahi, &rlo, &rhi) && pa >= rlo && pa <= rhi;
    };
    return walk_bvh([&](const BvhNode& node, const LocalBox& b, double plo, double phi) {
      if (!may_hide(b, plo, phi)) return Visit::kSkip;
      if (node.count == 0) return Visit::kDescend;
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        PointTriangle tr;
        if (!point_triangle(order[i], tr)) continue;
        LocalBox tb;
        triangle_hz(tr.L, tb);
        triangle_x(tr.L, tb);
        double tlo, thi;
        if (!pencil_span(tb.h_lo, tb.h_hi, tb.z_lo, tb.z_hi, tlo, thi) || !may_hide(tb, tlo, thi)) continue;
        if (exact_orientation(*tr.v[0], *tr.v[1], *tr.v[2], p) == 0) continue;
        double ea[2], eb[2], lo, hi;
        if (!crossing_segment(pl, tr, ea, eb)) continue;
        if (segment_span(ea[0], eb[0], ea[1], eb[1], lo, hi) && lo <= pa && pa <= hi) return Visit::kStop;
      }
      return Visit::kSkip;
    });
  }

  void single_plane(const QueryPoint& q, double delta) {
    begin_point(q);
    const double s = std::sin(delta - frame.beta_rad);
    add_plane(s, delta);
    run_pass(0);
  }
};

BandVisibility::BandVisibility(const Scene& scene, const VisibilityOptions& options) : impl_(new Impl(scene, options)) {}
BandVisibility::~BandVisibility() {
  delete impl_;
}

void BandVisibility::compute(const QueryPoint& q, VisibilityCache::PointResult& out) {
  impl_->compute(q, out);
}

void BandVisibility::visible_on_plane(const QueryPoint& q, double delta_rad, std::vector<VisibleInterval>& out) {
  out.clear();
  impl_->single_plane(q, delta_rad);
  impl_->visible_intervals(impl_->planes[0], out);
}

bool BandVisibility::direction_visible(const QueryPoint& q, const Vec3& direction) {
  const BandFrame frame = BandFrame::make(q.normal);
  if (direction.dot(frame.normal) <= 0 || direction.z() < 0) return false;
  double alpha, delta;
  frame.angles_of(direction, alpha, delta);
  const double pa = pseudo_angle(std::cos(alpha), std::sin(alpha));
  if (!impl_->opt.accelerate) {  // the reference: the whole line, then the look-up
    impl_->single_plane(q, delta);
    for (const Span& s : impl_->planes[0].occluded)
      if (s.lo <= pa && pa <= s.hi) return false;
    return true;
  }
  impl_->begin_point(q);
  impl_->add_plane(std::sin(delta - impl_->frame.beta_rad), delta);
  return !impl_->plane_blocked_at(pa);
}

std::size_t BandVisibility::last_triangle_tests() const {
  return impl_->triangle_tests;
}
std::size_t BandVisibility::last_plane_count() const {
  return impl_->plane_count;
}

}  // namespace skyband
