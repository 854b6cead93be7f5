#include "geometry/points/facade_points.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <utility>

#include "geometry/core/disjoint_sets.h"
#include "geometry/core/exact_sign.h"
#include "geometry/core/input_error.h"
#include "geometry/core/parallel_chunks.h"
#include "geometry/mesh/segment_crossing.h"
#include "geometry/mesh/welding.h"

namespace skyband {

namespace {

constexpr std::uint32_t kNoGroup = std::numeric_limits<std::uint32_t>::max();
constexpr double kSideStep_m = 1e-3;     // p ± this along n: the two sides of the face
constexpr double kBehind_m = 1e-3;       // the covered test starts this far behind the face
constexpr double kFrontMargin_m = 0.01;  // ... and ends this far beyond the offset point
constexpr double kWallMaxNormalZ = 0.5;  // |n_z| ≤ sin 30°: a wall

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

// ---- Which faces -------------------------------------------------------------------------------

enum class FaceClass : std::uint8_t { none, terrain, wall, roof, by_normal };

bool is_one_of(const std::string& name, std::initializer_list<const char*> names) {
  return std::any_of(names.begin(), names.end(), [&](const char* n) { return name == n; });
}

bool is_terrain_name(const std::string& n) {
  return is_one_of(n, {"ground", "terrain", "road", "water", "forest", "grass", "landuse", "plantcover", "tinrelief",
                       "relieffeature", "waterbody", "transportation", "trafficarea", "transportsquare", "railway"});
}

bool is_other_object_name(const std::string& n) {
  return n.starts_with("bridge") || n.starts_with("tunnel") ||
         is_one_of(n, {"genericcityobject", "cityfurniture", "solitaryvegetationobject", "separation"});
}

// The rule of the header, on the lower-case material name.
FaceClass material_class(std::string name) {
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (is_one_of(name, {"wallsurface", "window", "door", "buildingwall", "wall"})) return FaceClass::wall;
  if (is_one_of(name, {"roofsurface", "roof"})) return FaceClass::roof;
  if (is_one_of(name, {"groundsurface", "closuresurface", "floorsurface", "outerfloorsurface", "outerceilingsurface",
                       "ceilingsurface", "interiorwallsurface"}))
    return FaceClass::none;
  const std::string stem = name.ends_with("wall") ? name.substr(0, name.size() - 4) : name;
  if (is_terrain_name(name) || is_terrain_name(stem)) return FaceClass::terrain;
  if (is_other_object_name(name) || is_other_object_name(stem)) return FaceClass::none;
  return FaceClass::by_normal;
}

std::vector<FaceClass> triangle_classes(const TriangleSoup& soup) {
  std::vector<FaceClass> of_material(std::max<std::size_t>(1, soup.material_names.size()), FaceClass::by_normal);
  for (std::size_t m = 0; m < soup.material_names.size(); ++m) of_material[m] = material_class(soup.material_names[m]);
  std::vector<FaceClass> c(soup.triangles.size());
  for (std::size_t t = 0; t < c.size(); ++t) {
    const std::uint32_t m = t < soup.triangle_material.size() ? soup.triangle_material[t] : 0;
    c[t] = m < of_material.size() ? of_material[m] : FaceClass::by_normal;
    if (c[t] == FaceClass::wall) {
      // A wall surface lying flat (a floor or a flat roof labelled as wall) goes by its normal.
      const auto& tri = soup.triangles[t];
      const Vec3 n = (soup.vertices[tri[1]] - soup.vertices[tri[0]]).cross(soup.vertices[tri[2]] - soup.vertices[tri[0]]);
      if (std::abs(n.z()) > kWallMaxNormalZ * n.norm()) c[t] = FaceClass::by_normal;
    }
  }
  return c;
}

// ---- Groups: CityObjects, else welded connected components ----------------------------------

struct Groups {
  std::vector<std::uint32_t> of_triangle;  // kNoGroup for terrain
  std::vector<std::string> names;
  std::vector<Aabb> box;
  double max_diagonal_m = 0;
  bool objects = false;
  // The groups whose xy box meets each cell of a grid over the groups' boxes (cells_x ×
  // cells_y, cell_m square, from origin): the candidates of the inside test.
  double origin[2] = {0, 0}, cell_m = 1;
  std::size_t cells_x = 0, cells_y = 0;
  std::vector<std::vector<std::uint32_t>> cell_groups;
  const std::vector<std::uint32_t>* groups_near(const Vec3& x) const {
    if (cells_x == 0) return nullptr;
    const double i = std::floor((x.x() - origin[0]) / cell_m), j = std::floor((x.y() - origin[1]) / cell_m);
    if (!(i >= 0 && j >= 0 && i < double(cells_x) && j < double(cells_y))) return nullptr;
    return &cell_groups[std::size_t(j) * cells_x + std::size_t(i)];
  }
};

// Fills the grid of `g` (about 64 × 64 cells over the union of the boxes).
void index_group_boxes(Groups& g) {
  Aabb all;
  for (const Aabb& b : g.box)
    if (!b.empty()) all.extend(b);
  if (all.empty()) return;
  const double w = all.hi.x() - all.lo.x(), h = all.hi.y() - all.lo.y();
  g.cell_m = std::max({w, h, 1.0}) / 64;
  g.origin[0] = all.lo.x(), g.origin[1] = all.lo.y();
  g.cells_x = std::size_t(w / g.cell_m) + 1, g.cells_y = std::size_t(h / g.cell_m) + 1;
  g.cell_groups.assign(g.cells_x * g.cells_y, {});
  for (std::uint32_t k = 0; k < g.box.size(); ++k) {
    const Aabb& b = g.box[k];
    if (b.empty()) continue;
    const auto lo_i = std::size_t((b.lo.x() - g.origin[0]) / g.cell_m),
               hi_i = std::min(g.cells_x - 1, std::size_t((b.hi.x() - g.origin[0]) / g.cell_m));
    const auto lo_j = std::size_t((b.lo.y() - g.origin[1]) / g.cell_m),
               hi_j = std::min(g.cells_y - 1, std::size_t((b.hi.y() - g.origin[1]) / g.cell_m));
    for (std::size_t j = lo_j; j <= hi_j; ++j)
      for (std::size_t i = lo_i; i <= hi_i; ++i) g.cell_groups[j * g.cells_x + i].push_back(k);
  }
}

Groups make_groups(const TriangleSoup& soup, const std::vector<FaceClass>& cls) {
  Groups g;
  const std::size_t n = soup.triangles.size();
  g.of_triangle.assign(n, kNoGroup);
  g.objects = soup.triangle_object.size() == n && n > 0;
  if (g.objects) {
    g.names = soup.object_names;
    for (std::size_t t = 0; t < n; ++t)
      if (cls[t] != FaceClass::terrain) g.of_triangle[t] = soup.triangle_object[t];
  } else {
    const std::vector<std::uint32_t> weld = weld_positions(soup.vertices);
    DisjointSets sets(soup.vertices.size());
    for (std::size_t t = 0; t < n; ++t) {
      if (cls[t] == FaceClass::terrain) continue;
      const auto& tri = soup.triangles[t];
      sets.unite(weld[tri[0]], weld[tri[1]]);
      sets.unite(weld[tri[0]], weld[tri[2]]);
    }
    std::vector<std::uint32_t> number_of_root(soup.vertices.size(), kNoGroup);
    for (std::size_t t = 0; t < n; ++t) {
      if (cls[t] == FaceClass::terrain) continue;
      std::uint32_t& k = number_of_root[sets.find(weld[soup.triangles[t][0]])];
      if (k == kNoGroup) {
        k = static_cast<std::uint32_t>(g.names.size());
        g.names.push_back("component " + std::to_string(k));
      }
      g.of_triangle[t] = k;
    }
  }
  g.box.assign(g.names.size(), Aabb{});
  for (std::size_t t = 0; t < n; ++t) {
    if (g.of_triangle[t] == kNoGroup) continue;
    for (const std::uint32_t v : soup.triangles[t]) g.box[g.of_triangle[t]].extend(soup.vertices[v]);
  }
  for (const Aabb& b : g.box)
    if (!b.empty()) g.max_diagonal_m = std::max(g.max_diagonal_m, (b.hi - b.lo).norm());
  index_group_boxes(g);
  return g;
}

// ---- The grid of a face --------------------------------------------------------------------

// The face's frame: n its unit normal in a canonical direction (first non-zero component
// positive, so that the frame — and the rule for centres on edges — does not depend on the
// winding), u horizontal along the face, s = n × u up the face; (u, s, n) right-handed.
struct FaceFrame {
  Vec3 n, u, s;
};

FaceFrame face_frame(Vec3 n) {
  if (n.x() < 0 || (n.x() == 0 && (n.y() < 0 || (n.y() == 0 && n.z() < 0)))) n = -n;
  FaceFrame f;
  f.n = n;
  const double h = std::hypot(n.x(), n.y());
  f.u = h > 0 ? Vec3(-n.y() / h, n.x() / h, 0) : Vec3(1, 0, 0);
  // On a vertical face s is (0, 0, 1) exactly (n × u rounds its z to within an ulp of 1), so
  // that the rows sit at z = (j + ½)·S to the last digit.
  f.s = n.z() == 0 ? Vec3(0, 0, 1) : Vec3(n.cross(f.u));
  return f;
}

Vec3 in_frame(const FaceFrame& f, const Vec3& x) {
  return Vec3(f.u.dot(x), f.s.dot(x), 0);
}

// One candidate face: its frame, its corners in 3D and in (u, v), counter-clockwise, and the
// range of the cells whose centres its (u, v) box holds.
struct FaceGrid {
  FaceFrame frame;
  std::array<Vec3, 3> corner, corner_uv;
  std::int64_t i0 = 0, i1 = -1, j0 = 0, j1 = -1;
  double cells() const { return double(i1 - i0 + 1) * double(j1 - j0 + 1); }
};

// False for a triangle of zero area (exactly, or in its (u, v) projection).
bool make_face_grid(const Vec3& a, const Vec3& b, const Vec3& c, double spacing_m, FaceGrid& g) {
  if (triangle_is_degenerate(a, b, c)) return false;
  const Vec3 n = (b - a).cross(c - a);
  if (!(n.squaredNorm() > 0)) return false;
  g.frame = face_frame(n.normalized());
  g.corner = {a, b, c};
  g.corner_uv = {in_frame(g.frame, a), in_frame(g.frame, b), in_frame(g.frame, c)};
  const int o = exact_orient2d_sign(g.corner_uv[0], g.corner_uv[1], g.corner_uv[2]);
  if (o == 0) return false;
  if (o < 0) std::swap(g.corner[1], g.corner[2]), std::swap(g.corner_uv[1], g.corner_uv[2]);
  double lo[2] = {+1e300, +1e300}, hi[2] = {-1e300, -1e300};
  for (const Vec3& q : g.corner_uv)
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
  g.i0 = static_cast<std::int64_t>(std::ceil(lo[0] / spacing_m - 0.5));
  g.i1 = static_cast<std::int64_t>(std::floor(hi[0] / spacing_m - 0.5));
  g.j0 = static_cast<std::int64_t>(std::ceil(lo[1] / spacing_m - 0.5));
  g.j1 = static_cast<std::int64_t>(std::floor(hi[1] / spacing_m - 0.5));
  return true;
}

// Whether the centre x (in (u, v)) belongs to the counter-clockwise triangle abc: inside, or on
// an edge whose direction e the point moved up, then left, by infinitesimals falls to the left
// of: e_u > 0, or e_u = 0 and e_v > 0 (the sign of a floating-point difference is exact).
bool owns_centre(const std::array<Vec3, 3>& t, const Vec3& x) {
  for (int k = 0; k < 3; ++k) {
    const Vec3 &a = t[std::size_t(k)], &b = t[std::size_t((k + 1) % 3)];
    const int o = exact_orient2d_sign(a, b, x);
    if (o < 0) return false;
    if (o == 0) {
      const double eu = b.x() - a.x(), ev = b.y() - a.y();
      if (!(eu > 0 || (eu == 0 && ev > 0))) return false;
    }
  }
  return true;
}

// The 3D point of the face's plane at (u, v) = x: x_u·u + x_v·s + (n·corner)·n (on a vertical
// wall z = x_v to rounding, as s = (0, 0, 1) there).
Vec3 point_at(const FaceGrid& g, const Vec3& x) {
  return x.x() * g.frame.u + x.y() * g.frame.s + g.frame.n.dot(g.corner[0]) * g.frame.n;
}

// ---- The tests of a point -------------------------------------------------------------------

enum class Side : std::uint8_t { plus, minus, enclosed, open, undecided };

// Tilts (along u, along s) of the parity rays' directions, tried in turn when a ray touches an
// edge or a vertex: irregular, so that no two are parallel to the same edge.
constexpr std::array<std::array<double, 2>, 6> kTilts{
    {{0, 0}, {0.211, 0.137}, {-0.173, 0.293}, {0.317, -0.191}, {-0.269, -0.223}, {0.097, 0.401}}};

// A worker's scratch (no allocation once grown).
struct Scratch {
  std::vector<std::uint32_t> stack;                              // BVH walks
  std::vector<std::pair<std::uint32_t, std::uint8_t>> parities;  // inside test: group, 4 ray bits
};

class FacadeBuilder {
 public:
  FacadeBuilder(const Scene& scene, const FacadePointsOptions& o)
      : scene_(scene), soup_(scene.soup()), o_(o), cls_(triangle_classes(soup_)), groups_(make_groups(soup_, cls_)) {
    zero_area_.resize(soup_.triangles.size());
    for (std::size_t t = 0; t < zero_area_.size(); ++t)
      zero_area_[t] = triangle_is_degenerate(corner(t, 0), corner(t, 1), corner(t, 2));
    has_terrain_ = std::find(cls_.begin(), cls_.end(), FaceClass::terrain) != cls_.end();
  }

  FacadePoints run(int threads);

 private:
  const Vec3& corner(std::size_t t, int k) const { return soup_.vertices[soup_.triangles[t][std::size_t(k)]]; }
  bool wanted(FaceClass c, const Vec3& n_unit) const;
  void check_cell_count();
  std::vector<std::uint32_t> candidate_faces(std::size_t& zero_area) const;
  void add_face_points(Scratch& sc, std::uint32_t t, const FaceGrid& g, FacadePoints& out);
  int group_parity(Scratch& sc, const Vec3& from, const Vec3& direction, std::uint32_t group);
  Side outward_side(Scratch& sc, const Vec3& p, const FaceFrame& f, std::uint32_t group);
  Side outward_by_vote(Scratch& sc, const Vec3& p, const FaceFrame& f, std::uint32_t group);
  bool covered(Scratch& sc, const Vec3& p, const Vec3& n_out, std::uint32_t face, const FaceGrid& g, const Vec3& centre_uv);
  bool under_terrain(Scratch& sc, const Vec3& x);
  bool under_a_roof_from_inside(Scratch& sc, const Vec3& x);
  bool inside_building(Scratch& sc, const Vec3& x, const FaceFrame& f, std::uint32_t face);

  const Scene& scene_;
  const TriangleSoup& soup_;
  FacadePointsOptions o_;
  std::vector<FaceClass> cls_;
  Groups groups_;
  std::vector<bool> zero_area_;
  bool has_terrain_ = false;
};

// Whether a face of class c and unit normal n can give points of a class asked for.
bool FacadeBuilder::wanted(FaceClass c, const Vec3& n) const {
  if (c == FaceClass::wall) return o_.walls;
  if (c == FaceClass::roof) return o_.roofs;
  if (c != FaceClass::by_normal) return false;
  return std::abs(n.z()) <= kWallMaxNormalZ ? o_.walls : o_.roofs;
}

void FacadeBuilder::check_cell_count() {
  double cells = 0;
  FaceGrid g;
  for (std::size_t t = 0; t < soup_.triangles.size(); ++t) {
    if (zero_area_[t] || !make_face_grid(corner(t, 0), corner(t, 1), corner(t, 2), o_.spacing_m, g)) continue;
    if (wanted(cls_[t], g.frame.n) && g.i1 >= g.i0 && g.j1 >= g.j0) cells += g.cells();
  }
  if (!(cells <= double(o_.max_cells)))
    throw InputError("--spacing " + number(o_.spacing_m) + ": " + number(cells) +
                     " grid cells over the model's faces, more than " + std::to_string(o_.max_cells) + "; use a larger spacing");
}

// Parity (0, 1) of the group's triangles crossed by the segment from `from` along `direction`
// to beyond the group's box, or −1 when it touches one (degenerate: try another direction).
int FacadeBuilder::group_parity(Scratch& sc, const Vec3& from, const Vec3& direction, std::uint32_t group) {
  const Aabb& box = groups_.box[group];
  const double reach_m = (box.hi - box.lo).norm() + (from - box.centre()).norm() + 1.0;
  const Vec3 to = from + (reach_m / direction.norm()) * direction;
  int parity = 0;
  bool degenerate = false;
  for_each_triangle_near_segment(scene_, from, to, sc.stack, [&](std::uint32_t t) {
    if (degenerate || groups_.of_triangle[t] != group || zero_area_[t]) return;
    const SegmentCrossing c = segment_triangle_crossing(from, to, corner(t, 0), corner(t, 1), corner(t, 2));
    if (c == SegmentCrossing::proper) parity ^= 1;
    if (c == SegmentCrossing::touch) degenerate = true;
  });
  return degenerate ? -1 : parity;
}

// Which side of the face at p is outside its group (header: "Outward, per point"): rays
// leaving the face on either side (along ±n, tilted in turn until neither touches an edge).
Side FacadeBuilder::outward_side(Scratch& sc, const Vec3& p, const FaceFrame& f, std::uint32_t group) {
  const Vec3 front = p + kSideStep_m * f.n, back = p - kSideStep_m * f.n;
  int pf = -1, pb = -1;
  for (const auto& tilt : kTilts) {
    const Vec3 across = tilt[0] * f.u + tilt[1] * f.s;
    if (pf < 0) pf = group_parity(sc, front, f.n + across, group);
    if (pb < 0) pb = group_parity(sc, back, -f.n + across, group);
    if (pf >= 0 && pb >= 0) break;
  }
  if (pf < 0 || pb < 0) return Side::undecided;
  if (pf == pb) return pf == 1 ? Side::enclosed : Side::open;
  return pf == 0 ? Side::plus : Side::minus;
}

// Both sides looked open along the normal (a shell open there: a floorless box's roof seen
// straight down, a missing wall): a vote over 12 fixed directions, each casting a ray from
// both p + 1 mm·n and p − 1 mm·n; a direction votes for the side whose ray crosses the group an
// even number of times while the other's crosses it an odd one. Open when the votes tie.
Side FacadeBuilder::outward_by_vote(Scratch& sc, const Vec3& p, const FaceFrame& f, std::uint32_t group) {
  const Vec3 front = p + kSideStep_m * f.n, back = p - kSideStep_m * f.n;
  int plus = 0, minus = 0;
  for (int k = 0; k < 12; ++k) {
    const double azimuth = 0.1234 + k * (2 * kPi / 12), elevation = k % 2 == 0 ? 0.35 : -0.35;
    const Vec3 d = std::cos(elevation) * (std::cos(azimuth) * f.u + std::sin(azimuth) * f.s) + std::sin(elevation) * f.n;
    const int pf = group_parity(sc, front, d, group), pb = group_parity(sc, back, d, group);
    if (pf < 0 || pb < 0 || pf == pb) continue;
    (pf == 0 ? plus : minus) += 1;
  }
  return plus > minus ? Side::plus : minus > plus ? Side::minus : Side::open;
}

// A surface in front of the point within D + 1 cm, or just behind it (header: "covered").
bool FacadeBuilder::covered(Scratch& sc, const Vec3& p, const Vec3& n_out, std::uint32_t face, const FaceGrid& g,
                            const Vec3& centre_uv) {
  const Vec3 from = p - kBehind_m * n_out, to = p + (o_.offset_m + kFrontMargin_m) * n_out;
  const std::uint32_t group = groups_.of_triangle[face];
  const Vec3 &fa = corner(face, 0), &fb = corner(face, 1), &fc = corner(face, 2);
  bool hit = false;
  for_each_triangle_near_segment(scene_, from, to, sc.stack, [&](std::uint32_t t) {
    if (hit || t == face || zero_area_[t]) return;
    const Vec3 &a = corner(t, 0), &b = corner(t, 1), &c = corner(t, 2);
    const bool coplanar =
        exact_orientation(fa, fb, fc, a) == 0 && exact_orientation(fa, fb, fc, b) == 0 && exact_orientation(fa, fb, fc, c) == 0;
    if (coplanar) {
      if (groups_.of_triangle[t] == group) return;
      std::array<Vec3, 3> uv{in_frame(g.frame, a), in_frame(g.frame, b), in_frame(g.frame, c)};
      const int o = exact_orient2d_sign(uv[0], uv[1], uv[2]);
      if (o == 0) return;
      hit = exact_orient2d_sign(uv[0], uv[1], centre_uv) * o >= 0 && exact_orient2d_sign(uv[1], uv[2], centre_uv) * o >= 0 &&
            exact_orient2d_sign(uv[2], uv[0], centre_uv) * o >= 0;
      return;
    }
    hit = segment_triangle_crossing(from, to, a, b, c) != SegmentCrossing::none;
  });
  return hit;
}

// Whether a terrain triangle lies over x (or through it).
bool FacadeBuilder::under_terrain(Scratch& sc, const Vec3& x) {
  const Vec3 top(x.x(), x.y(), std::max(x.z(), scene_.bounds().hi.z()) + 1.0);
  bool hit = false;
  for_each_triangle_near_segment(scene_, x, top, sc.stack, [&](std::uint32_t t) {
    if (hit || cls_[t] != FaceClass::terrain || zero_area_[t]) return;
    hit = segment_triangle_crossing(x, top, corner(t, 0), corner(t, 1), corner(t, 2)) != SegmentCrossing::none;
  });
  return hit;
}

// Whether the first surface straight above x faces up, away from x, by the parity test of its
// own group at the hit: x is then under a roof seen from inside. This catches a neighbour that
// overlaps the face within one connected component, where the component's parity (their
// symmetric difference) hides it from the horizontal rays.
bool FacadeBuilder::under_a_roof_from_inside(Scratch& sc, const Vec3& x) {
  const std::optional<RayHit> hit = scene_.intersect(Ray{x, Vec3(0, 0, 1), 0, 1e300});
  if (!hit) return false;
  const std::uint32_t t = hit->triangle, group = groups_.of_triangle[t];
  if (group == kNoGroup || zero_area_[t]) return false;
  const Vec3 &a = corner(t, 0), &b = corner(t, 1), &c = corner(t, 2);
  const Vec3 n = (b - a).cross(c - a);
  if (!(n.squaredNorm() > 0)) return false;
  const FaceFrame f = face_frame(n.normalized());
  const Vec3 h = a + hit->u * (b - a) + hit->v * (c - a);
  const Side side = outward_side(sc, h, f, group);
  if (side != Side::plus && side != Side::minus) return false;
  return (side == Side::plus ? f.n.z() : -f.n.z()) > 0;
}

// Whether x lies inside a building: a group whose box holds x, crossed an odd number of times
// by each of four horizontal rays from x (±h1, ±h2). The point's own face counts as part of
// every group, so that a neighbour closed by this face (a party wall modelled once, in this
// building only) holds the points in front of it. Rays touching an edge are turned by a fixed
// angle and tried again; if every turn is degenerate the point counts as outside.
bool FacadeBuilder::inside_building(Scratch& sc, const Vec3& x, const FaceFrame& f, std::uint32_t face) {
  // Only groups whose box holds x can hold it; the rays need reach only out of those boxes.
  const std::vector<std::uint32_t>* near = groups_.groups_near(x);
  if (!near) return false;
  double reach_m = 0;
  for (const std::uint32_t g : *near) {
    const Aabb& b = groups_.box[g];
    if ((x.array() >= b.lo.array()).all() && (x.array() <= b.hi.array()).all())
      reach_m = std::max(reach_m, (x - b.lo).cwiseAbs().cwiseMax((b.hi - x).cwiseAbs()).norm());
  }
  if (reach_m == 0) return false;
  reach_m += 1.0;
  constexpr std::array<double, 5> kTurns_rad{0, 0.1173, 0.3391, 0.5927, 0.8219};
  for (const double turn : kTurns_rad) {
    const double c = std::cos(turn), s = std::sin(turn);
    const Vec3 h1(c * f.u.x() - s * f.u.y(), s * f.u.x() + c * f.u.y(), 0);
    const Vec3 h2(-h1.y(), h1.x(), 0);
    sc.parities.clear();
    std::uint8_t face_bits = 0;
    bool degenerate = false;
    for (int pair = 0; pair < 2 && !degenerate; ++pair) {
      const Vec3 h = pair == 0 ? h1 : h2;
      const Vec3 plus = x + reach_m * h, minus = x - reach_m * h;
      for_each_triangle_near_segment(scene_, minus, plus, sc.stack, [&](std::uint32_t t) {
        const std::uint32_t group = groups_.of_triangle[t];
        if (degenerate || group == kNoGroup || zero_area_[t]) return;
        const Vec3 &a = corner(t, 0), &b = corner(t, 1), &cc = corner(t, 2);
        // The rays lie in the plane z = x_z exactly (their directions have z = 0): a triangle
        // wholly above or below it cannot meet them (exact comparisons).
        if (std::min({a.z(), b.z(), cc.z()}) > x.z() || std::max({a.z(), b.z(), cc.z()}) < x.z()) return;
        std::uint8_t bits = 0;
        for (int side = 0; side < 2; ++side) {
          const SegmentCrossing k = segment_triangle_crossing(x, side == 0 ? plus : minus, a, b, cc);
          if (k == SegmentCrossing::touch) degenerate = true;
          if (k == SegmentCrossing::proper) bits |= std::uint8_t(1u << (2 * pair + side));
        }
        if (bits == 0) return;
        if (t == face) face_bits ^= bits;
        auto it = std::find_if(sc.parities.begin(), sc.parities.end(), [&](const auto& e) { return e.first == group; });
        if (it == sc.parities.end())
          sc.parities.emplace_back(group, bits);
        else
          it->second ^= bits;
      });
    }
    if (degenerate) continue;
    for (const auto& [group, bits] : sc.parities) {
      const Aabb& b = groups_.box[group];
      const bool in_box = (x.array() >= b.lo.array()).all() && (x.array() <= b.hi.array()).all();
      const bool own = group == groups_.of_triangle[face];
      if (in_box && (bits == 0xF || (!own && (bits ^ face_bits) == 0xF))) return true;
    }
    return false;
  }
  return false;
}

void FacadeBuilder::add_face_points(Scratch& sc, std::uint32_t t, const FaceGrid& g, FacadePoints& out) {
  const double S = o_.spacing_m;
  const std::uint32_t group = groups_.of_triangle[t];
  for (std::int64_t j = g.j0; j <= g.j1; ++j) {
    for (std::int64_t i = g.i0; i <= g.i1; ++i) {
      const Vec3 centre_uv((double(i) + 0.5) * S, (double(j) + 0.5) * S, 0);
      if (!owns_centre(g.corner_uv, centre_uv)) continue;
      ++out.centres;
      const Vec3 p = point_at(g, centre_uv);
      Side side = outward_side(sc, p, g.frame, group);
      if (side == Side::open) side = outward_by_vote(sc, p, g.frame, group);
      if (side == Side::enclosed) {
        ++out.enclosed;
        continue;
      }
      if (side == Side::undecided) {
        ++out.undecided;
        continue;
      }
      double sign = side == Side::minus ? -1.0 : 1.0;
      FaceClass c = cls_[t];
      if (side == Side::open) {
        ++out.from_winding;
        const Vec3 w = (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0));
        const bool roof_like = c == FaceClass::roof || (c == FaceClass::by_normal && std::abs(g.frame.n.z()) > kWallMaxNormalZ);
        sign = (roof_like ? g.frame.n.z() : w.dot(g.frame.n)) >= 0 ? 1.0 : -1.0;
      }
      const Vec3 n_out = sign * g.frame.n;
      if (c == FaceClass::by_normal) {
        if (std::abs(n_out.z()) <= kWallMaxNormalZ)
          c = FaceClass::wall;
        else if (n_out.z() > 0)
          c = FaceClass::roof;
        else {
          ++out.facing_down;
          continue;
        }
      } else if (c == FaceClass::roof && n_out.z() < 0) {
        ++out.facing_down;  // a roof surface that the parity finds facing down: not trusted
        continue;
      }
      if (covered(sc, p, n_out, t, g, centre_uv)) {
        ++out.covered;
        continue;
      }
      const Vec3 x = p + o_.offset_m * n_out;
      if (has_terrain_ && under_terrain(sc, x)) {
        ++out.underground;
        continue;
      }
      if (inside_building(sc, x, g.frame, t) || under_a_roof_from_inside(sc, x)) {
        ++out.inside;
        continue;
      }
      FacadePoint fp;
      fp.position = x;
      fp.normal = n_out;
      fp.triangle = t;
      fp.group = group;
      fp.surface = c == FaceClass::roof ? FacadeSurface::roof : FacadeSurface::wall;
      fp.iu = sign > 0 ? i : -i - 1;  // u → −u in the outward frame
      fp.iv = j;
      out.points.push_back(fp);
    }
  }
}

// The triangles that can give points, in order; counts the zero-area ones among them.
std::vector<std::uint32_t> FacadeBuilder::candidate_faces(std::size_t& zero_area) const {
  std::vector<std::uint32_t> faces;
  FaceGrid g;
  for (std::uint32_t t = 0; t < soup_.triangles.size(); ++t) {
    const FaceClass c = cls_[t];
    if (c == FaceClass::none || c == FaceClass::terrain) continue;
    if ((c == FaceClass::wall && !o_.walls) || (c == FaceClass::roof && !o_.roofs)) continue;
    if (zero_area_[t] || !make_face_grid(corner(t, 0), corner(t, 1), corner(t, 2), o_.spacing_m, g)) {
      ++zero_area;
      continue;
    }
    if (wanted(c, g.frame.n)) faces.push_back(t);
  }
  return faces;
}

// The faces in chunks on the workers, each chunk's points and counts kept apart and joined in
// the faces' order: the same output whatever the thread count.
FacadePoints FacadeBuilder::run(int threads) {
  check_cell_count();
  FacadePoints out;
  out.group_names = groups_.names;
  out.groups_are_objects = groups_.objects;
  const std::vector<std::uint32_t> faces = candidate_faces(out.zero_area);
  out.faces = faces.size();
  constexpr std::size_t kChunk = 16;
  std::vector<FacadePoints> parts((faces.size() + kChunk - 1) / kChunk);
  for_each_in_chunks(
      parts.size(), 1, threads, {}, [] { return std::make_unique<Scratch>(); },
      [&](Scratch& sc, std::size_t c) {
        FaceGrid g;
        for (std::size_t k = c * kChunk; k < std::min(faces.size(), (c + 1) * kChunk); ++k) {
          const std::uint32_t t = faces[k];
          make_face_grid(corner(t, 0), corner(t, 1), corner(t, 2), o_.spacing_m, g);
          add_face_points(sc, t, g, parts[c]);
        }
      });
  std::size_t total = 0;
  for (const FacadePoints& p : parts) total += p.points.size();
  out.points.reserve(total);
  for (const FacadePoints& p : parts) {
    out.points.insert(out.points.end(), p.points.begin(), p.points.end());
    out.centres += p.centres, out.facing_down += p.facing_down, out.enclosed += p.enclosed, out.covered += p.covered;
    out.underground += p.underground, out.inside += p.inside, out.undecided += p.undecided, out.from_winding += p.from_winding;
  }
  return out;
}

}  // namespace

void check_facade_options(const FacadePointsOptions& options) {
  // Finiteness first: an ordered comparison with a NaN raises FE_INVALID (tests/fp_traps.cpp).
  if (!std::isfinite(options.spacing_m) || !(options.spacing_m > 0))
    throw InputError("--spacing " + number(options.spacing_m) + ": must be a positive distance in metres");
  if (!std::isfinite(options.offset_m) || !(options.offset_m > 0) || options.offset_m > 100)
    throw InputError("--offset " + number(options.offset_m) + ": must be a distance in metres within (0, 100]");
  if (!options.walls && !options.roofs) throw InputError("--surfaces: name at least one of wall, roof");
}

FacadePoints make_facade_points(const Scene& scene, const FacadePointsOptions& options) {
  check_facade_options(options);
  if (scene.soup().triangles.empty()) throw InputError("the model has no triangles: no surfaces to put points on");
  return FacadeBuilder(scene, options).run(options.threads);
}

}  // namespace skyband
