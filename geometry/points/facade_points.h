#pragma once
// Calculation points on the walls (and roofs) of a city model, D metres in front of them along
// their outward normal: what `skyband points facades` writes, as Ladybug/Honeybee facade grids.
//
// Which faces. By the triangle's material name (any case):
//   - semantic surfaces (CityJSON/CityGML types, 3dfier's classes): WallSurface, Window, Door,
//     BuildingWall, wall → wall; RoofSurface, roof → roof; GroundSurface, ClosureSurface,
//     FloorSurface, OuterFloorSurface, OuterCeilingSurface, CeilingSurface,
//     InteriorWallSurface → no points;
//   - terrain classes (ground, terrain, road, water, forest, grass, LandUse, PlantCover,
//     TINRelief, ReliefFeature, WaterBody, Transportation, TrafficArea, TransportSquare,
//     Railway, and 3dfier's "<class>Wall" of these) → no points, and not part of any building;
//   - other non-building objects (Bridge…, Tunnel…, GenericCityObject, CityFurniture,
//     SolitaryVegetationObject, 3dfier's Separation, and their "…Wall") → no points;
//   - any other name (Building, BuildingPart, an OBJ `usemtl`, no material) → by the outward
//     normal: a wall when it is within 30° of horizontal (|n_z| ≤ ½), a roof when it points up
//     more steeply (n_z > ½, Honeybee's default roof angle of 60° from the zenith), else
//     (floors, undersides) no points. A semantic roof whose outward normal (below) points
//     down gets no point either: roofs face the sky, so the shell there is defective. A wall
//     surface lying flatter than a wall (|n_z| > ½: a floor or a flat roof labelled as wall) goes
//     by its normal as the other names do.
//
// The grid. Each triangle carries a square grid in its own plane: u horizontal along the face,
// v up the face (v = z on a vertical wall), both measured from the world origin, cell centres
// at u = (i + ½)·S, v = (j + ½)·S — so the grid of a plane does not depend on how it was cut
// into triangles, nor on the winding (the centres are symmetric under u → −u). A centre belongs
// to the triangle when it lies inside its (u, v) projection, decided by exact orient2d; a centre
// on an edge or a vertex belongs to exactly one of the triangles around it (the rule of a point
// moved up, then left, by infinitesimals: symbolic perturbation), so a wall cut into triangles
// gets each centre once. A triangle smaller than a cell gets a point only if a centre falls in
// it (0 or 1 point, never one outside the face). Zero-area triangles get none.
//
// Outward, per point (whatever the winding). The groups: the CityObjects where the model has
// them, else the connected components after welding exactly equal positions (geometry/mesh/welding.h);
// terrain triangles belong to none. From the centre p (on the face, unit winding normal n) the
// points p ± 1 mm·n are classified by ray parity against the face's own group: the number of
// the group's triangles crossed by a segment from each, away from the face, to beyond the
// group's box (exact segment–triangle predicates, geometry/mesh/segment_crossing.h). Even in front,
// odd behind: n is outward; the reverse: −n. A ray touching an edge or a vertex is retried in
// the next of a fixed list of tilted directions. Both sides enclosed (odd, odd): an interior or
// party wall modelled once, or back to back within one group — no point. Both open (even,
// even: an open shell seen through its opening, a lone surface): 12 fixed directions around
// the face vote, each casting rays from both points (a floorless box's roof: straight down
// escapes, sideways meets a wall); on a tie (a lone surface) the winding is taken (up for a
// roof) and the point counted. Every direction degenerate: no point, counted.
//
// Dropped and counted (exact predicates for every decision):
//   - covered: another surface meets the segment from 1 mm behind p to D + 1 cm in front of it
//     (a coincident or adjacent wall of another building, terrain above the point, an acute
//     concave corner). Triangles of the own group exactly coplanar with the face (the rest of its
//     polygon, duplicates) do not count; another group's triangle exactly coplanar with it
//     covers the point when the point's (u, v) lies in it (closed). Every other triangle counts
//     when the segment meets it (geometry/mesh/segment_crossing.h: proper or touch).
//   - underground: a terrain triangle lies over the offset point p + D·n (the vertical segment
//     up from it meets one): a wall's lowest rows below the terrain around it;
//   - inside: the offset point p + D·n lies inside a building — a group (other or its own) whose
//     box holds it and which each of four horizontal rays from it (two opposite pairs) crosses an
//     odd number of times (so that one open wall in front does not count as a building, while a
//     floorless or roofless one does), the point's own face counting as part of every group (a
//     neighbour whose party wall is modelled only here is closed by it); or the first surface
//     straight above the offset point faces up, away from it, by the outward test of that
//     surface's own group at the hit (under a roof seen from inside; the surface is found by
//     the scene's floating-point closest-hit query, the side by the exact parity test).
// Limitation: without objects, buildings overlapping one another within one connected
// component are seen through the parity of the component (their symmetric difference); the
// roof-above test catches such a point under the neighbour's roof, not every case. City
// models with objects do not have this limit.
// Floating-point constructions: the (u, v) frame, the projected corners, the centres, the 3D
// point (from the frame) and the offset — no decision depends on them beyond the inputs
// of the exact predicates.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/mesh/scene.h"

namespace skyband {

enum class FacadeSurface : std::uint8_t { wall, roof };

struct FacadePointsOptions {
  double spacing_m = 1;   // S, > 0
  double offset_m = 0.1;  // D, in (0, 100]
  bool walls = true, roofs = false;
  std::size_t max_cells = 20'000'000;  // grid cells over the candidate faces; InputError beyond
  int threads = 0;                     // 0 = all cores; the output does not depend on it
};

struct FacadePoint {
  Vec3 position;  // metres: the centre moved offset_m along the normal
  Vec3 normal;    // unit, outward
  std::uint32_t triangle = 0;
  std::uint32_t group = 0;  // index into FacadePoints::group_names
  FacadeSurface surface = FacadeSurface::wall;
  std::int64_t iu = 0, iv = 0;  // the cell in the outward frame: u = (iu + ½)·S, v = (iv + ½)·S
};

struct FacadePoints {
  std::vector<FacadePoint> points;
  // The groups: CityObject ids, or "component K" (K from 0, in order of the lowest triangle).
  std::vector<std::string> group_names;
  bool groups_are_objects = false;
  std::size_t faces = 0;         // triangles taking part (wall/roof candidates, non-zero area)
  std::size_t zero_area = 0;     // candidate triangles of zero area: no points
  std::size_t centres = 0;       // cell centres inside the faces
  std::size_t facing_down = 0;   // outward normal down: floors, undersides (by the normal), or a
                                 // semantic roof surface found facing down (a defective shell)
  std::size_t enclosed = 0;      // enclosed on both sides by the own group
  std::size_t covered = 0;       // a surface in front within D + 1 cm (or just behind)
  std::size_t underground = 0;   // offset point under a terrain triangle
  std::size_t inside = 0;        // offset point inside a building
  std::size_t undecided = 0;     // every parity ray degenerate
  std::size_t from_winding = 0;  // kept, outward taken from the winding (open on both sides)
};

// Throws InputError for a spacing or offset out of range or no surface class asked for.
void check_facade_options(const FacadePointsOptions& options);

// Throws InputError as check_facade_options, and for more than max_cells grid cells over the
// faces.
FacadePoints make_facade_points(const Scene& scene, const FacadePointsOptions& options);

}  // namespace skyband
