#include "geometry/mesh/segment_crossing.h"

#include "geometry/core/exact_sign.h"

namespace skyband {

namespace {

// v without its coordinate k, as a point of the plane z = 0 (dropping a coordinate is exact).
Vec3 drop_axis(const Vec3& v, int k) {
  if (k == 0) return Vec3(v.y(), v.z(), 0);
  if (k == 1) return Vec3(v.z(), v.x(), 0);
  return Vec3(v.x(), v.y(), 0);
}

// An axis whose projection keeps the triangle non-degenerate (the one of the largest normal
// component first), or −1 for a degenerate triangle.
int projection_axis(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a).cwiseAbs();
  const int first = n.x() >= n.y() ? (n.x() >= n.z() ? 0 : 2) : (n.y() >= n.z() ? 1 : 2);
  for (const int k : {first, (first + 1) % 3, (first + 2) % 3})
    if (exact_orient2d_sign(drop_axis(a, k), drop_axis(b, k), drop_axis(c, k)) != 0) return k;
  return -1;
}

// 2D (z = 0): x in the closed triangle abc of orientation o (±1).
bool in_closed_triangle(const Vec3& a, const Vec3& b, const Vec3& c, int o, const Vec3& x) {
  return exact_orient2d_sign(a, b, x) * o >= 0 && exact_orient2d_sign(b, c, x) * o >= 0 && exact_orient2d_sign(c, a, x) * o >= 0;
}

bool in_box_2d(const Vec3& p, const Vec3& q, const Vec3& x) {
  return std::min(p.x(), q.x()) <= x.x() && x.x() <= std::max(p.x(), q.x()) && std::min(p.y(), q.y()) <= x.y() &&
         x.y() <= std::max(p.y(), q.y());
}

// 2D: the closed segments pq and rs meet.
bool segments_meet_2d(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
  const int d1 = exact_orient2d_sign(p, q, r), d2 = exact_orient2d_sign(p, q, s);
  const int d3 = exact_orient2d_sign(r, s, p), d4 = exact_orient2d_sign(r, s, q);
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;
  return (d1 == 0 && in_box_2d(p, q, r)) || (d2 == 0 && in_box_2d(p, q, s)) || (d3 == 0 && in_box_2d(r, s, p)) ||
         (d4 == 0 && in_box_2d(r, s, q));
}

// The segment pq lies in the plane of abc: whether it meets the closed triangle.
bool coplanar_segment_meets(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, int k) {
  const Vec3 P = drop_axis(p, k), Q = drop_axis(q, k), A = drop_axis(a, k), B = drop_axis(b, k), C = drop_axis(c, k);
  const int o = exact_orient2d_sign(A, B, C);
  return in_closed_triangle(A, B, C, o, P) || in_closed_triangle(A, B, C, o, Q) || segments_meet_2d(P, Q, A, B) ||
         segments_meet_2d(P, Q, B, C) || segments_meet_2d(P, Q, C, A);
}

}  // namespace

bool triangle_is_degenerate(const Vec3& a, const Vec3& b, const Vec3& c) {
  return projection_axis(a, b, c) < 0;
}

SegmentCrossing segment_triangle_crossing(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Boxes apart (exact comparisons: the segment lies in the box of its endpoints): no contact.
  for (int k = 0; k < 3; ++k)
    if (std::max(p[k], q[k]) < std::min({a[k], b[k], c[k]}) || std::min(p[k], q[k]) > std::max({a[k], b[k], c[k]}))
      return SegmentCrossing::none;
  const int sp = exact_orientation(a, b, c, p), sq = exact_orientation(a, b, c, q);
  if (sp == sq && sp != 0) return SegmentCrossing::none;
  if (sp == 0 || sq == 0) {
    // An endpoint (or the whole segment) in the triangle's plane.
    const int k = projection_axis(a, b, c);
    if (k < 0) return SegmentCrossing::none;
    if (sp == 0 && sq == 0) return coplanar_segment_meets(p, q, a, b, c, k) ? SegmentCrossing::touch : SegmentCrossing::none;
    const Vec3& x = sp == 0 ? p : q;
    const Vec3 A = drop_axis(a, k), B = drop_axis(b, k), C = drop_axis(c, k);
    return in_closed_triangle(A, B, C, exact_orient2d_sign(A, B, C), drop_axis(x, k)) ? SegmentCrossing::touch
                                                                                      : SegmentCrossing::none;
  }
  // p and q strictly on either side (so the triangle is not degenerate): pq meets its interior
  // when the signed volumes of p, q with each edge agree, an edge or a vertex when some vanish.
  const int o1 = exact_orientation(p, q, a, b), o2 = exact_orientation(p, q, b, c), o3 = exact_orientation(p, q, c, a);
  if ((o1 > 0 || o2 > 0 || o3 > 0) && (o1 < 0 || o2 < 0 || o3 < 0)) return SegmentCrossing::none;
  if (o1 == 0 || o2 == 0 || o3 == 0) return SegmentCrossing::touch;
  return SegmentCrossing::proper;
}

}  // namespace skyband
