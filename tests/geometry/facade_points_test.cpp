#define BOOST_TEST_MODULE facade_points
#include <boost/test/unit_test.hpp>

// Facade points (geometry/points/facade_points.h) on hand-made boxes whose extents are multiples of the
// spacing, so that every count is a closed form: a W × H wall at spacing S holds (W/S)·(H/S)
// cell centres, none on its border (centres sit at half-integers of S, the edges at integers).
// Normals are compared exactly: the boxes are axis-aligned, so every normal is ±1 on one axis.
// The segment–triangle predicate (geometry/mesh/segment_crossing.h) is checked on constructed cases.

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "geometry/core/input_error.h"
#include "geometry/mesh/scene.h"
#include "geometry/mesh/segment_crossing.h"
#include "geometry/points/facade_points.h"

using namespace skyband;

namespace {

// A quad abcd as two triangles (a, b, c), (a, c, d); `flip` reverses both.
void add_quad(TriangleSoup& s, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, std::uint32_t material, bool flip) {
  const auto base = std::uint32_t(s.vertices.size());
  s.vertices.insert(s.vertices.end(), {a, b, c, d});
  if (flip) {
    s.triangles.push_back({base, base + 2, base + 1});
    s.triangles.push_back({base, base + 3, base + 2});
  } else {
    s.triangles.push_back({base, base + 1, base + 2});
    s.triangles.push_back({base, base + 2, base + 3});
  }
  if (!s.material_names.empty()) s.triangle_material.insert(s.triangle_material.end(), {material, material});
}

struct BoxFaces {
  bool floor = true, roof = true;
  unsigned flip_mask = 0;  // bit k: reverse the winding of face k (0 floor, 1 roof, 2–5 walls)
};

// The box [x0, x1] × [y0, y1] × [z0, z1], faces wound outward unless flipped; each face has
// its own vertices (no sharing), as a polygon-soup reader writes them, except where noted.
void add_box(TriangleSoup& s, double x0, double y0, double z0, double x1, double y1, double z1, BoxFaces f = {},
             std::uint32_t material = 0) {
  const Vec3 c[8] = {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0},
                     {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}};
  if (f.floor) add_quad(s, c[0], c[3], c[2], c[1], material, f.flip_mask & 1u);
  if (f.roof) add_quad(s, c[4], c[5], c[6], c[7], material, f.flip_mask & 2u);
  for (int k = 0; k < 4; ++k) add_quad(s, c[k], c[(k + 1) % 4], c[4 + (k + 1) % 4], c[4 + k], material, f.flip_mask & (4u << k));
}

// The expected outward normal of a point of box [x0, x1] × [y0, y1] × [z0, z1] moved D out of
// its face: the axis along which it lies outside the box.
Vec3 outward_of_box(const Vec3& x, double x0, double y0, double z0, double x1, double y1, double z1) {
  if (x.x() < x0) return {-1, 0, 0};
  if (x.x() > x1) return {1, 0, 0};
  if (x.y() < y0) return {0, -1, 0};
  if (x.y() > y1) return {0, 1, 0};
  if (x.z() < z0) return {0, 0, -1};
  return {0, 0, 1};
}

bool strictly_inside(const Vec3& x, double x0, double y0, double z0, double x1, double y1, double z1) {
  return x.x() > x0 && x.x() < x1 && x.y() > y0 && x.y() < y1 && x.z() > z0 && x.z() < z1;
}

void check_box_points(const FacadePoints& fp, double x0, double y0, double z0, double x1, double y1, double z1, double offset) {
  for (const FacadePoint& p : fp.points) {
    const Vec3 n = outward_of_box(p.position, x0, y0, z0, x1, y1, z1);
    BOOST_TEST(p.normal == n);
    // The point is `offset` out of the face: its distance to the face's plane.
    const double d = n.x() > 0   ? p.position.x() - x1
                     : n.x() < 0 ? x0 - p.position.x()
                     : n.y() > 0 ? p.position.y() - y1
                     : n.y() < 0 ? y0 - p.position.y()
                     : n.z() > 0 ? p.position.z() - z1
                                 : z0 - p.position.z();
    BOOST_TEST(d == offset, boost::test_tools::tolerance(1e-12));  // rounding of the point and its offset (coordinates ≤ 20 m)
    BOOST_TEST(!strictly_inside(p.position, x0, y0, z0, x1, y1, z1));
  }
}

}  // namespace

// A closed 10 × 10 × 6 box at spacing 1: each wall holds 10 · 6 centres, so 4 · 10 · 6 = 240
// points, each D = 0.1 out of its wall with the wall's outward normal; no roof point by default.
BOOST_AUTO_TEST_CASE(closed_box_walls) {
  TriangleSoup s;
  add_box(s, 0, 0, 0, 10, 10, 6);
  const Scene scene(s);
  FacadePointsOptions o;
  const FacadePoints fp = make_facade_points(scene, o);
  BOOST_TEST(fp.points.size() == 4u * 10u * 6u);
  BOOST_TEST(fp.centres == 240u);
  BOOST_TEST(fp.faces == 8u);  // 4 walls × 2 triangles
  BOOST_TEST(fp.covered + fp.inside + fp.enclosed + fp.undecided + fp.from_winding == 0u);
  check_box_points(fp, 0, 0, 0, 10, 10, 6, 0.1);
  // Heights: the centres of the rows, (j + ½)·1 m.
  std::set<double> z;
  for (const FacadePoint& p : fp.points) z.insert(p.position.z());
  BOOST_TEST(z.size() == 6u);
  BOOST_TEST(*z.begin() == 0.5);
  // No centre twice (the two triangles of a wall share its diagonal, which passes centres).
  std::set<std::tuple<double, double, double>> positions;
  for (const FacadePoint& p : fp.points) positions.insert({p.position.x(), p.position.y(), p.position.z()});
  BOOST_TEST(positions.size() == 240u);
}

// The same box with the windings of the roof and of two walls reversed (and, second, every
// face reversed): the same 240 points with the same outward normals — orientation comes from
// ray parity, not from the winding.
BOOST_AUTO_TEST_CASE(outward_whatever_the_winding) {
  for (const unsigned mask : {0b101010u, 0b111111u, 0b010100u}) {
    TriangleSoup s;
    add_box(s, 0, 0, 0, 10, 10, 6, BoxFaces{true, true, mask});
    const Scene scene(s);
    FacadePointsOptions o;
    o.roofs = true;
    const FacadePoints fp = make_facade_points(scene, o);
    // Walls 4 · 10 · 6 plus the roof's 10 · 10.
    BOOST_TEST(fp.points.size() == 240u + 100u, "flip mask " << mask);
    BOOST_TEST(fp.from_winding == 0u);
    check_box_points(fp, 0, 0, 0, 10, 10, 6, 0.1);
    std::size_t roofs = 0;
    for (const FacadePoint& p : fp.points) roofs += p.surface == FacadeSurface::roof;
    BOOST_TEST(roofs == 100u);
  }
}

// Two boxes sharing the wall x = 10, each with its own copy of it (party walls modelled twice),
// in a model without objects: the boxes share the positions of that wall's corners, so they
// are one connected component (welding exactly equal positions), and each copy's 10 · 6
// centres are enclosed on both sides by it; the other 6 walls' 6 · 60 = 360 points remain.
BOOST_AUTO_TEST_CASE(party_wall_between_two_boxes) {
  TriangleSoup s;
  add_box(s, 0, 0, 0, 10, 10, 6);
  add_box(s, 10, 0, 0, 20, 10, 6, BoxFaces{true, true, 0b001000u});
  const Scene scene(s);
  const FacadePoints fp = make_facade_points(scene, FacadePointsOptions{});
  BOOST_TEST(fp.group_names.size() == 1u);
  BOOST_TEST(!fp.groups_are_objects);
  BOOST_TEST(fp.centres == 480u);
  BOOST_TEST(fp.enclosed == 120u);
  BOOST_TEST(fp.points.size() == 360u);
  for (const FacadePoint& p : fp.points) {
    BOOST_TEST(std::abs(p.position.x() - 10) > 0.2, p.position.transpose());  // none off the shared wall
    BOOST_TEST(!strictly_inside(p.position, 0, 0, 0, 10, 10, 6));
    BOOST_TEST(!strictly_inside(p.position, 10, 0, 0, 20, 10, 6));
  }
}

// The same two boxes as two city objects (the second's copy of the shared wall wound inward):
// each copy is outward by its own object's parity, and covered by the other object's coplanar
// copy: 2 · 60 = 120 covered, the same 360 points.
BOOST_AUTO_TEST_CASE(party_wall_between_two_objects) {
  TriangleSoup s;
  add_box(s, 0, 0, 0, 10, 10, 6);
  add_box(s, 10, 0, 0, 20, 10, 6, BoxFaces{true, true, 0b100000u});
  s.object_names = {"A", "B"};
  s.triangle_object.assign(s.triangles.size(), 0);
  std::fill(s.triangle_object.begin() + 12, s.triangle_object.end(), 1u);
  const Scene scene(s);
  const FacadePoints fp = make_facade_points(scene, FacadePointsOptions{});
  BOOST_TEST(fp.groups_are_objects);
  BOOST_TEST(fp.covered == 120u);
  BOOST_TEST(fp.points.size() == 360u);
  std::size_t in_a = 0;
  for (const FacadePoint& p : fp.points) in_a += p.group == 0;
  BOOST_TEST(in_a == 180u);  // A's south, west and north walls: 10·6 each
}

// A box whose neighbour overlaps it by 0.05 m (the neighbour's west wall at x = 9.95, inside
// the first box; no shared positions: two components): the first box's east wall points, 0.1 m
// out at x = 10.1, are inside the neighbour, and the neighbour's west wall points, at x = 9.85,
// inside the first box: 2 · 60 = 120 inside a building; 360 remain. (Each wall still holds
// 10 · 6 centres: the neighbour's south wall spans x ∈ [9.95, 19.95], centres at 10.5 … 19.5.)
BOOST_AUTO_TEST_CASE(overlapping_neighbour) {
  TriangleSoup s;
  add_box(s, 0, 0, 0, 10, 10, 6);
  add_box(s, 9.95, 0, 0, 19.95, 10, 6);
  const Scene scene(s);
  const FacadePoints fp = make_facade_points(scene, FacadePointsOptions{});
  BOOST_TEST(fp.centres == 480u);
  BOOST_TEST(fp.inside == 120u);
  BOOST_TEST(fp.points.size() == 360u);
}

// The same overlap within one connected component (a zero-area sliver joins a corner of each
// box, as fan-triangulated slivers do in real models): the component's parity is that of the
// boxes' symmetric difference, so the two walls inside the overlap look outward into it, where
// each finds the other 0.05 m in front: 120 covered, 360 points as before.
BOOST_AUTO_TEST_CASE(overlapping_neighbour_in_one_component) {
  TriangleSoup s;
  add_box(s, 0, 0, 0, 10, 10, 6);
  add_box(s, 9.95, 0, 0, 19.95, 10, 6);
  const auto base = std::uint32_t(s.vertices.size());
  s.vertices.insert(s.vertices.end(), {{10, 0, 6}, {9.95, 0, 6}});
  s.triangles.push_back({base, base + 1, base});
  const Scene scene(s);
  const FacadePoints fp = make_facade_points(scene, FacadePointsOptions{});
  BOOST_TEST(fp.group_names.size() == 1u);
  BOOST_TEST(fp.centres == 480u);
  BOOST_TEST(fp.covered == 120u);
  BOOST_TEST(fp.points.size() == 360u);
  for (const FacadePoint& p : fp.points) {
    BOOST_TEST(!strictly_inside(p.position, 0, 0, 0, 10, 10, 6));
    BOOST_TEST(!strictly_inside(p.position, 9.95, 0, 0, 19.95, 10, 6));
  }
}

// An open box without floor: the walls still get their 240 points, outward (horizontal rays
// find the enclosure), and the roof its 100, up.
BOOST_AUTO_TEST_CASE(open_box_without_floor) {
  TriangleSoup s;
  add_box(s, 0, 0, 0, 10, 10, 6, BoxFaces{false, true, 0b010110u});
  const Scene scene(s);
  FacadePointsOptions o;
  o.roofs = true;
  const FacadePoints fp = make_facade_points(scene, o);
  BOOST_TEST(fp.points.size() == 340u);
  BOOST_TEST(fp.from_winding == 0u);
  check_box_points(fp, 0, 0, 0, 10, 10, 6, 0.1);
}

// Two boxes sharing their vertices along the wall x = 10, the wall modelled once: one
// connected component with an interior wall, enclosed on both sides — its 60 centres are left
// out, the other 6 walls' 360 remain.
BOOST_AUTO_TEST_CASE(interior_wall_modelled_once) {
  TriangleSoup s;
  add_box(s, 0, 0, 0, 10, 10, 6);
  BoxFaces f;
  add_box(s, 10, 0, 0, 20, 10, 6, f);
  // Remove the second box's west wall (faces 2–5 are south, east, north, west: the last quad).
  s.triangles.erase(s.triangles.end() - 2, s.triangles.end());
  const Scene scene(s);
  const FacadePoints fp = make_facade_points(scene, FacadePointsOptions{});
  BOOST_TEST(fp.centres == 420u);
  BOOST_TEST(fp.enclosed == 60u);
  BOOST_TEST(fp.points.size() == 360u);
}

// Terrain above a wall's lowest row (a TINRelief sheet at z = 1 south of the box): the south
// wall's 10 centres at z = 0.5 are under it (underground), and the terrain gets no points.
BOOST_AUTO_TEST_CASE(terrain_covers_the_lowest_row) {
  TriangleSoup s;
  s.material_names = {"Building", "TINRelief"};
  add_box(s, 0, 0, 0, 10, 10, 6, BoxFaces{}, 0);
  add_quad(s, {-5, -5, 1}, {15, -5, 1}, {15, 0, 1}, {-5, 0, 1}, 1, false);  // south of the box only
  const Scene scene(s);
  const FacadePoints fp = make_facade_points(scene, FacadePointsOptions{});
  BOOST_TEST(fp.underground == 10u);
  BOOST_TEST(fp.covered == 0u);
  BOOST_TEST(fp.points.size() == 230u);
}

// Semantic materials decide the class whatever the normal: a "RoofSurface" box face gets roof
// points only with roofs asked for; "GroundSurface" and terrain none.
BOOST_AUTO_TEST_CASE(semantic_classes) {
  TriangleSoup s;
  s.material_names = {"WallSurface", "RoofSurface", "GroundSurface"};
  add_box(s, 0, 0, 0, 10, 10, 6, BoxFaces{}, 0);
  s.triangle_material[0] = s.triangle_material[1] = 2;  // floor
  s.triangle_material[2] = s.triangle_material[3] = 1;  // roof
  const Scene scene(s);
  FacadePointsOptions o;
  o.walls = false;
  o.roofs = true;
  const FacadePoints fp = make_facade_points(scene, o);
  BOOST_TEST(fp.points.size() == 100u);
  for (const FacadePoint& p : fp.points) BOOST_TEST(p.normal == Vec3(0, 0, 1));
}

// Every face of the 10 × 10 × 6 box labelled WallSurface: the floor and the roof lie flat, so
// they go by their normals — the floor's 100 centres face down (no point, counted), the roof's
// 100 are roof points, written only when roofs are asked for; the walls keep their 240.
BOOST_AUTO_TEST_CASE(flat_wall_surfaces_go_by_their_normal) {
  TriangleSoup s;
  s.material_names = {"WallSurface"};
  add_box(s, 0, 0, 0, 10, 10, 6, BoxFaces{}, 0);
  const Scene scene(s);
  FacadePointsOptions o;
  const FacadePoints walls = make_facade_points(scene, o);
  BOOST_TEST(walls.points.size() == 240u);
  BOOST_TEST(walls.facing_down == 0u);  // the floor is not a candidate when only walls are asked for
  for (const FacadePoint& p : walls.points) BOOST_TEST(p.normal.z() == 0.0);
  o.roofs = true;
  const FacadePoints both = make_facade_points(scene, o);
  BOOST_TEST(both.points.size() == 340u);
  BOOST_TEST(both.facing_down == 100u);
  BOOST_TEST(std::count_if(both.points.begin(), both.points.end(), [](const FacadePoint& p) { return p.normal.z() == 1.0; }) ==
             100);
}

// A triangle smaller than a cell: a centre in it gives it one point, none otherwise; a wall
// cut into many triangles (a fan from one corner) still gets each centre once.
BOOST_AUTO_TEST_CASE(small_and_fanned_triangles) {
  TriangleSoup s;
  // A lone 4 × 2 wall in the plane y = 0 as a fan of 4 triangles from (0, 0, 0) to its right
  // and top edges; spacing 1: 4 · 2 = 8 centres at x ∈ {0.5 … 3.5}, z ∈ {0.5, 1.5}. The fan's
  // edge to (2, 0, 2) (z = x) passes the centres (0.5, 0.5) and (1.5, 1.5): each owned once.
  const Vec3 o(0, 0, 0);
  const std::vector<Vec3> rim = {{4, 0, 0}, {4, 0, 1}, {4, 0, 2}, {2, 0, 2}, {0, 0, 2}};
  for (std::size_t k = 0; k + 1 < rim.size(); ++k) {
    const auto base = std::uint32_t(s.vertices.size());
    s.vertices.insert(s.vertices.end(), {o, rim[k], rim[k + 1]});
    s.triangles.push_back({base, base + 1, base + 2});
  }
  const Scene scene(s);
  const FacadePoints fp = make_facade_points(scene, FacadePointsOptions{});
  BOOST_TEST(fp.centres == 8u);
  // An open lone wall: outward from the winding (−y: (4,0,0) − o × (4,0,1) − o points −y).
  BOOST_TEST(fp.from_winding == 8u);
  for (const FacadePoint& p : fp.points) BOOST_TEST(p.normal == Vec3(0, -1, 0));
  // A 0.2 m triangle around the centre (0.5, 0, 0.5) and one beside it holding none.
  TriangleSoup t;
  t.vertices = {{0.4, 0, 0.4}, {0.7, 0, 0.4}, {0.4, 0, 0.7}, {0.6, 0, 0.6}, {0.9, 0, 0.6}, {0.6, 0, 0.9}};
  t.triangles = {{0, 1, 2}, {3, 4, 5}};
  const FacadePoints small = make_facade_points(Scene(t), FacadePointsOptions{});
  BOOST_TEST(small.centres == 1u);
  BOOST_TEST(small.points.size() == 1u);
  BOOST_TEST(small.points[0].triangle == 0u);
}

BOOST_AUTO_TEST_CASE(bad_parameters) {
  TriangleSoup s;
  add_box(s, 0, 0, 0, 10, 10, 6);
  const Scene scene(s);
  const auto message = [&](FacadePointsOptions o) {
    try {
      (void)make_facade_points(scene, o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  FacadePointsOptions o;
  o.spacing_m = 0;
  BOOST_TEST(message(o).starts_with("--spacing 0"));
  o.spacing_m = std::nan("");
  BOOST_TEST(message(o).starts_with("--spacing"));
  o.spacing_m = 1;
  o.offset_m = -0.1;
  BOOST_TEST(message(o).starts_with("--offset -0.1"));
  o.offset_m = std::numeric_limits<double>::infinity();
  BOOST_TEST(message(o).starts_with("--offset"));
  o.offset_m = 0.1;
  o.walls = false;
  BOOST_TEST(message(o).starts_with("--surfaces"));
  o.walls = true;
  o.spacing_m = 1e-3;  // 4 walls · 10⁴ · 6·10³ cells (in their boxes: twice that) > 2·10⁷
  BOOST_TEST(message(o).find("grid cells over the model's faces") != std::string::npos);
}

// The segment–triangle predicate on the triangle (0,0,0), (1,0,0), (0,1,0).
BOOST_AUTO_TEST_CASE(segment_triangle_cases) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const auto k = [&](const Vec3& p, const Vec3& q) { return segment_triangle_crossing(p, q, a, b, c); };
  BOOST_TEST((k({0.2, 0.2, -1}, {0.2, 0.2, 1}) == SegmentCrossing::proper));
  BOOST_TEST((k({0.2, 0.2, 1}, {0.2, 0.2, 2}) == SegmentCrossing::none));
  BOOST_TEST((k({0.6, 0.6, -1}, {0.6, 0.6, 1}) == SegmentCrossing::none));
  BOOST_TEST((k({0.5, 0.5, -1}, {0.5, 0.5, 1}) == SegmentCrossing::touch));  // through the edge bc
  BOOST_TEST((k({0, 0, -1}, {0, 0, 1}) == SegmentCrossing::touch));          // through a vertex
  BOOST_TEST((k({0.2, 0.2, 0}, {0.2, 0.2, 1}) == SegmentCrossing::touch));   // endpoint on it
  BOOST_TEST((k({2, 2, 0}, {2, 2, 1}) == SegmentCrossing::none));            // endpoint in the plane, outside
  BOOST_TEST((k({-1, 0.3, 0}, {2, 0.3, 0}) == SegmentCrossing::touch));      // in the plane, across it
  BOOST_TEST((k({-1, 3, 0}, {3, -1, 0}) == SegmentCrossing::none));          // in the plane, beside it (x + y = 2)
  BOOST_TEST(triangle_is_degenerate({0, 0, 0}, {1, 1, 1}, {2, 2, 2}));
  BOOST_TEST(!triangle_is_degenerate(a, b, c));
}
