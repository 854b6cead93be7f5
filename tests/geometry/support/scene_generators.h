#pragma once
// Deterministic scene and query-point generators for the oracle tests and the SVF benchmark.
// Everything is a pure function of its parameters and seed (std::mt19937_64 with values drawn
// through our own uniform mapping, so results do not depend on the standard library's
// distribution implementations).
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "geometry/bands/band_visibility.h"
#include "geometry/mesh/height_field.h"
#include "geometry/mesh/triangle_soup.h"
#include "geometry/support/lambert_oracle.h"

namespace skyband::gen {

using oracle::OrientedBox;

// Small deterministic RNG: std::mt19937_64 (its output sequence is fixed by the standard) with
// bits mapped to [0, 1) by the top 53 bits.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }    // [lo, hi)
  std::uint64_t below(std::uint64_t n) { return static_cast<std::uint64_t>(uniform() * static_cast<double>(n)) % n; }
  // A unit vector of tilt (from +z) then azimuth (from +x) drawn in that order.
  Vec3 unit_normal(double tilt_lo, double tilt_hi, double az_lo, double az_hi) {
    const double tilt = uniform(tilt_lo, tilt_hi);
    const double az = uniform(az_lo, az_hi);
    return Vec3(std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt));
  }
  // Callers draw several values in one expression only inside braces (Vec3{rng.uniform(),
  // rng.uniform(), ...}: evaluated left to right), never as a function's arguments, whose order
  // is unspecified (GCC and clang differ): the scenes would depend on the compiler.
 private:
  std::mt19937_64 engine_;
};

// Closed box (8 vertices, 12 triangles, outward winding) appended to the soup.
void append_box(TriangleSoup& soup, const OrientedBox& box);
TriangleSoup boxes_to_soup(const std::vector<OrientedBox>& boxes);

// `count` boxes standing on z = 0 with centres uniform in [−extent, extent]², sizes uniform in
// [size_lo, size_hi] (each axis; the height independently in [height_lo, height_hi]) and a
// uniform yaw in [0, π).
struct RandomBoxParams {
  int count = 1;
  double extent_m = 10;
  double size_lo_m = 1, size_hi_m = 6;
  double height_lo_m = 1, height_hi_m = 12;
};
std::vector<OrientedBox> random_boxes(const RandomBoxParams& params, std::uint64_t seed);

// A street canyon along x: two walls of length L (x ∈ [−L/2, L/2]), height H, thickness t,
// inner faces at y = 0 and y = W.
std::vector<OrientedBox> street_canyon(double width_m, double height_m, double length_m, double thickness_m = 1.0);

// Procedural city: a grid of blocks × blocks city blocks separated by streets; each block holds
// lots × lots box buildings with random (seeded) heights and set-backs, on a ground plane made of
// a grid of triangles covering the city plus a margin of one block.
struct CityParams {
  int blocks = 8;        // per side
  int lots = 2;          // buildings per block, per side
  double block_m = 60;   // block side (buildings inside), metres
  double street_m = 18;  // street width, metres
  double height_lo_m = 8, height_hi_m = 60;
  double setback_max_m = 3;  // each building footprint is inset by up to this much per side
  int ground_cells = 8;      // ground grid cells per side (2 triangles each)
  std::uint64_t seed = 1;
};
struct City {
  CityParams params;
  std::vector<OrientedBox> buildings;
  TriangleSoup soup;  // buildings (12 triangles each) then the ground grid
  double pitch_m() const { return params.block_m + params.street_m; }
  double size_m() const { return params.blocks * pitch_m(); }  // city spans [0, size] (streets at edges)
};
City make_city(const CityParams& params);
// Parameters giving about `triangles` triangles (12 per building + ground), 2×2 lots per block.
CityParams city_params_for_triangles(std::size_t triangles, std::uint64_t seed);

// Query points on the ground in the streets (normal +z, z = 0 exactly).
std::vector<QueryPoint> street_points(const City& city, std::size_t count, std::uint64_t seed);
// Query points on building facades: normal outward, `offset_m` off the wall (0 = exactly on it),
// heights in [5 %, 95 %] of the building, along the wall within [5 %, 95 %] of its length.
std::vector<QueryPoint> facade_points(const std::vector<OrientedBox>& buildings, std::size_t count, double offset_m,
                                      std::uint64_t seed);

// Translation to projected coordinates (UTM-like magnitudes): x + 4·10⁵ m, y + 6·10⁶ m.
inline const Vec3 kProjectedOffset{4.0e5, 6.0e6, 0.0};
void translate(TriangleSoup& soup, const Vec3& offset);
void translate(std::vector<QueryPoint>& points, const Vec3& offset);

}  // namespace skyband::gen

namespace skyband::gen {

// The synthetic city most tools are tried on: `per_side` × `per_side` axis-aligned boxes on a
// `pitch_m` grid, footprints uniform in [footprint_lo_m, footprint_hi_m] per axis, heights uniform
// in [height_lo_m, height_hi_m], each box four walls and a roof — no floor — standing on one ground
// quad (2 triangles) reaching `margin_m` beyond the city. Every face is split into `splits` ×
// `splits` cells of 2 triangles from one lattice per box, so neighbouring faces share their edge
// vertices exactly (splits = 1: 10 triangles a box, 9,002 in all for 30 × 30; splits = 11:
// 1,089,002).
struct OpenBoxCityParams {
  int per_side = 30;
  double pitch_m = 40;
  double footprint_lo_m = 14, footprint_hi_m = 30;
  double height_lo_m = 8, height_hi_m = 80;
  int splits = 1;
  double margin_m = 200;
  std::uint64_t seed = 1;
};
struct OpenBoxCity {
  OpenBoxCityParams params;
  std::vector<std::array<Vec3, 2>> boxes;                             // lo, hi corners
  TriangleSoup soup;                                                  // boxes, then the ground quad at z = 0
  double size_m() const { return params.per_side * params.pitch_m; }  // the city spans [0, size]²
};
OpenBoxCity make_open_box_city(const OpenBoxCityParams& params);

// Points 5 cm above the ground (normal up) in the streets — outside every footprint by at least
// 0.5 m — uniform over the city, or (`beyond_m` > 0) on the open ground within beyond_m outside
// the city's edge.
std::vector<QueryPoint> open_city_street_points(const OpenBoxCity& city, std::size_t count, std::uint64_t seed,
                                                double beyond_m = 0);
// Points 5 cm in front of wall triangles (outward normal), uniform over the walls' area.
std::vector<QueryPoint> open_city_facade_points(const OpenBoxCity& city, std::size_t count, std::uint64_t seed);

// A synthetic DSM of n × n 1 m pixels (north up, corner (85000, 447000 + n)): n²/650 blocks 5–40 m
// high with 5–20 m sides on ground at 0, or (`rough`) on a terrain rough by up to 0.3 m — the kind
// of raster a LiDAR survey of a dense district gives.
HeightField synthetic_city_dsm(std::size_t n, std::uint64_t seed, bool rough);

}  // namespace skyband::gen
