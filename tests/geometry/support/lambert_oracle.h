#pragma once
// Exact sky-view-factor oracles, independent of the band method (method.md §8,
// reference-notes §5). Uniform sky: SVF = E/π.
//
//  * lambert_form_factor: Lambert's contour formula for a planar polygon seen from a
//    differential element at P with unit normal n,
//        F = (1/2π) |Σ_i γ_i n·(r_i × r_{i+1}) / |r_i × r_{i+1}||,
//    r_i = v_i − P, γ_i = angle between r_i and r_{i+1}. Valid only for polygons that lie
//    entirely in the element's front half-space; callers clip first.
//  * svf_single_convex_box: SVF = (1 + cos θ)/2 − Σ F(front faces clipped to z ≥ z_P and to the
//    element's front half-space). The front faces of one convex body never overlap in
//    projection, so no hidden-surface removal is needed.
//  * svf_union_oracle: any set of planar occluders whose projections overlap (a city). The sky
//    hemisphere seen from P is split by the 5 upper faces of a cube centred on P (top and four
//    sides); on a cube face the central projection maps planar polygons to polygons. Every
//    occluder is clipped to the cube face's pyramid, z ≥ z_P and the front half-space, projected,
//    and the projections are united exactly (CGAL 2D Boolean operations, exact kernel). Lambert's
//    formula is summed over the union's boundary lifted back onto the cube-face plane (holes
//    subtract). The only inexact steps are the float clipping/projection of each polygon's
//    vertices (relative error ~1e-16) and the float evaluation of the contour sum.
//  * Closed forms of reference-notes §5 (canyons, walls, rectangles).
#include <cstddef>
#include <span>
#include <vector>

#include "geometry/core/vec3.h"
#include "geometry/mesh/triangle_soup.h"

namespace skyband::oracle {

using Polygon3 = std::vector<Vec3>;  // planar polygon, vertices in order (either orientation)

// ---- Lambert's contour formula -------------------------------------------------------------

// Signed contour sum (1/2π) Σ_i γ_i n·(r_i × r_{i+1})/|r_i × r_{i+1}| (sign = orientation seen
// from P). Edges collinear with P contribute 0.
double lambert_contour_signed(const Vec3& p, const Vec3& n, std::span<const Vec3> polygon);

// Form factor |lambert_contour_signed|: dimensionless, in [0, 1] for a polygon in front of the
// element (which the caller guarantees, e.g. with clip_to_sky_front).
double lambert_form_factor(const Vec3& p, const Vec3& n, std::span<const Vec3> polygon);

// ---- Clipping (Sutherland–Hodgman in 3D) ---------------------------------------------------

// Keeps the part of `polygon` with plane_normal·(q − origin) ≥ 0. Output may be empty.
Polygon3 clip_to_half_space(std::span<const Vec3> polygon, const Vec3& origin, const Vec3& plane_normal);

// Clips to the sky half-space z ≥ z_P and to the element's front half-space n·(q − P) ≥ 0.
Polygon3 clip_to_sky_front(std::span<const Vec3> polygon, const Vec3& p, const Vec3& n);

// ---- Sky view factors ----------------------------------------------------------------------

// SVF of an unobstructed element with unit normal n: (1 + n_z)/2 = (1 + cos θ)/2 (θ = tilt).
double open_sky_view_factor(const Vec3& n);

// A box standing on z = base_z, rotated by yaw about the vertical through its centre.
struct OrientedBox {
  Vec3 centre{0, 0, 0};  // metres; centre of the box (z = middle height)
  Vec3 size{1, 1, 1};    // metres; full extents along its local x, y and z
  double yaw_rad = 0;    // rotation about +z, counter-clockwise seen from above
  // Corner k (bit 0: +x, bit 1: +y, bit 2: +z side) in the world frame.
  Vec3 corner(int k) const;
  // The 6 faces as quads, each ordered counter-clockwise seen from outside (outward normal).
  std::vector<Polygon3> faces() const;
};

// SVF next to one convex box (front faces only; method.md §8).
double svf_single_convex_box(const Vec3& p, const Vec3& n, const OrientedBox& box);

// Exact SVF with any planar occluders (overlaps resolved by exact 2D union on cube faces).
double svf_union_oracle(const Vec3& p, const Vec3& n, std::span<const Polygon3> occluders);
// The same union's SVF and sky exposure (the visible sky's solid angle in front of the element
// over 2π: the solid angle of each lifted union polygon by Van Oosterom and Strackee's triangle
// formula over a fan, subtracted from the open front sky's 2π(1/2 + β/π), β the normal's elevation).
struct UnionSkyFactors {
  double svf = 0, sky_exposure = 0;
};
UnionSkyFactors sky_union_oracle(const Vec3& p, const Vec3& n, std::span<const Polygon3> occluders);
UnionSkyFactors sky_union_oracle(const Vec3& p, const Vec3& n, const TriangleSoup& soup);
// Same with every triangle of a soup as an occluder.
double svf_union_oracle(const Vec3& p, const Vec3& n, const TriangleSoup& soup);

// Conservatively culled union oracle for large scenes. Triangles whose horizontal bounding-box
// distance from P is ≥ radius_m are dropped. Every point of a dropped triangle is at horizontal
// distance ≥ R and height ≤ z_top (the soup's top), so it is seen at elevation ≤ atan((z_top −
// z_P)/R); all such sky directions are covered by a ring of vertical quads of height z_top − z_P
// inscribed in the circle of radius R around P. Hence
//     SVF(near ∪ ring) ≤ SVF(all) ≤ SVF(near),
// and the oracle returns both bounds (the estimate is their midpoint, error ≤ (hi − lo)/2).
struct SvfBounds {
  double lo = 0, hi = 0;
  std::size_t near_triangles = 0;
  double estimate() const { return 0.5 * (lo + hi); }
  double half_width() const { return 0.5 * (hi - lo); }
};
// Grows the radius from initial_radius_m (×2 per step) until half_width ≤ target_half_width,
// all triangles are near (then lo = hi exactly) or the radius exceeds max_radius_m (then the
// bounds are returned as they are).
//
// front_faces_only: also drop triangles whose winding normal m = (v1 − v0) × (v2 − v0) does not
// face P (m·(P − v0) ≤ 0). Exact only when every surface is the outward-wound boundary of a
// closed solid, or a one-sided sheet seen from its front only (a ground plane under points on or
// above it): every sight line entering a solid then crosses a front face first, so the union of
// the front faces' projections is the union of all faces' projections. The generators of
// scene_generators.h produce such scenes.
SvfBounds svf_union_oracle_culled(const Vec3& p, const Vec3& n, const TriangleSoup& soup, double initial_radius_m,
                                  double target_half_width, bool front_faces_only = false, double max_radius_m = 1e300);

// ---- Closed forms (reference-notes §5; all dimensionless view factors) ----------------------

// Horizontal element on the floor of an infinitely long canyon (width W, wall height H) at
// distance x from one wall: ½[x/√(x²+H²) + (W−x)/√((W−x)²+H²)].
double canyon_floor_svf(double x_m, double width_m, double height_m);
// Wall element (horizontal normal) at height z on one wall of an infinite canyon, facing the
// opposite wall (height H, distance W): ½[1 − (H−z)/√(W²+(H−z)²)].
double canyon_wall_svf(double z_m, double width_m, double height_m);
// Horizontal element at distance d from an infinitely long wall of height H: ½[1 + d/√(d²+H²)].
double wall_ground_svf(double distance_m, double height_m);
// Element to a parallel a×b rectangle at distance c, normal through a corner (Howell):
// (1/2π)[A/√(1+A²)·atan(B/√(1+A²)) + B/√(1+B²)·atan(A/√(1+B²))], A = a/c, B = b/c.
double parallel_rectangle_form_factor(double a_m, double b_m, double c_m);
// Element (normal +z) to a perpendicular rectangle in the plane y = c, x ∈ [0, w], z ∈ [0, h]:
// (1/2π)[atan(1/Y) − Y/√(X²+Y²)·atan(1/√(X²+Y²))], X = h/w, Y = c/w.
double perpendicular_rectangle_form_factor(double w_m, double h_m, double c_m);

}  // namespace skyband::oracle
