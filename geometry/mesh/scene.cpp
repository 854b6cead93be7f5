#include "geometry/mesh/scene.h"

#include "geometry/exact/occluder_set.h"
#include "geometry/horizon/column_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace skyband {

namespace {

constexpr std::uint32_t kLeafSize = 4;
constexpr int kBins = 12;

Aabb triangle_box(const TriangleSoup& s, std::uint32_t t) {
  Aabb b;
  for (int k = 0; k < 3; ++k) b.extend(s.vertices[s.triangles[t][k]]);
  return b;
}

double area(const Aabb& b) {
  if (b.empty()) return 0;
  const Vec3 d = b.hi - b.lo;
  return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
}

}  // namespace

Scene::Scene(TriangleSoup soup) : soup_(std::move(soup)) {
  build();
}

const ColumnScene& Scene::column_scene() const {
  std::call_once(column_once_, [&] { column_scene_ = std::make_shared<const ColumnScene>(classify_column_scene(soup_)); });
  return *column_scene_;
}

const OccluderSet& Scene::occluders() const {
  std::call_once(occluders_once_, [&] { occluders_ = std::make_shared<const OccluderSet>(build_occluder_set(soup_)); });
  return *occluders_;
}

Vec3 Scene::triangle_normal(std::uint32_t t) const {
  const auto& tri = soup_.triangles[t];
  const Vec3& a = soup_.vertices[tri[0]];
  return (soup_.vertices[tri[1]] - a).cross(soup_.vertices[tri[2]] - a);
}

// Top-down binned-SAH build (Wald 2007): deterministic, O(n log n).
void Scene::build() {
  const auto n = static_cast<std::uint32_t>(soup_.triangles.size());
  order_.resize(n);
  if (n == 0) return;
  std::vector<Aabb> boxes(n);
  std::vector<Vec3> centres(n);
  for (std::uint32_t t = 0; t < n; ++t) {
    order_[t] = t;
    boxes[t] = triangle_box(soup_, t);
    centres[t] = boxes[t].centre();
  }
  nodes_.reserve(2 * n / kLeafSize + 2);
  nodes_.push_back({});
  struct Task {
    std::uint32_t node, first, count;
  };
  std::vector<Task> stack{{0, 0, n}};
  while (!stack.empty()) {
    const Task task = stack.back();
    stack.pop_back();
    BvhNode& node = nodes_[task.node];
    Aabb box, cbox;
    for (std::uint32_t i = task.first; i < task.first + task.count; ++i) {
      box.extend(boxes[order_[i]]);
      cbox.extend(centres[order_[i]]);
    }
    node.box = box;
    if (task.count <= kLeafSize) {
      node.first = task.first;
      node.count = task.count;
      continue;
    }
    // Choose the split (axis, bin) minimising the surface-area heuristic.
    double best_cost = 1e300;
    int best_axis = -1, best_bin = -1;
    for (int axis = 0; axis < 3; ++axis) {
      const double lo = cbox.lo[axis], extent = cbox.hi[axis] - cbox.lo[axis];
      if (!(extent > 0)) continue;
      std::array<Aabb, kBins> bin_box;
      std::array<std::uint32_t, kBins> bin_count{};
      for (std::uint32_t i = task.first; i < task.first + task.count; ++i) {
        const std::uint32_t t = order_[i];
        int b = static_cast<int>(kBins * (centres[t][axis] - lo) / extent);
        b = std::clamp(b, 0, kBins - 1);
        bin_box[b].extend(boxes[t]);
        ++bin_count[b];
      }
      std::array<double, kBins> right_cost{};
      Aabb acc;
      std::uint32_t cnt = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.extend(bin_box[b]);
        cnt += bin_count[b];
        right_cost[b] = area(acc) * cnt;
      }
      acc = Aabb();
      cnt = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        acc.extend(bin_box[b]);
        cnt += bin_count[b];
        const double cost = area(acc) * cnt + right_cost[b + 1];
        if (cnt > 0 && cnt < task.count && cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_bin = b;
        }
      }
    }
    std::uint32_t mid;
    if (best_axis < 0) {
      mid = task.first + task.count / 2;  // all centres coincide: split by count
    } else {
      const double lo = cbox.lo[best_axis], extent = cbox.hi[best_axis] - cbox.lo[best_axis];
      auto* begin = order_.data() + task.first;
      auto* end = begin + task.count;
      auto* split = std::stable_partition(begin, end, [&](std::uint32_t t) {
        int b = static_cast<int>(kBins * (centres[t][best_axis] - lo) / extent);
        return std::clamp(b, 0, kBins - 1) <= best_bin;
      });
      mid = static_cast<std::uint32_t>(split - order_.data());
    }
    const auto left = static_cast<std::uint32_t>(nodes_.size());
    nodes_[task.node].first = left;
    nodes_[task.node].count = 0;
    nodes_.push_back({});
    nodes_.push_back({});
    stack.push_back({left + 1, mid, task.first + task.count - mid});
    stack.push_back({left, task.first, mid - task.first});
  }
}

namespace {

// Slab test; returns false when the box cannot hold a hit in [t0, t1].
bool hit_box(const Aabb& b, const Vec3& o, const Vec3& inv_d, double t0, double t1) {
  for (int a = 0; a < 3; ++a) {
    if (std::isinf(inv_d[a])) {  // the ray is parallel to the slab: inside it or never in it
      if (o[a] < b.lo[a] || o[a] > b.hi[a]) return false;
      continue;
    }
    double tn = (b.lo[a] - o[a]) * inv_d[a];
    double tf = (b.hi[a] - o[a]) * inv_d[a];
    if (tn > tf) std::swap(tn, tf);
    t0 = std::max(t0, tn);
    t1 = std::min(t1, tf * (1 + 4e-16));  // conservative widening
    if (t0 > t1) return false;
  }
  return true;
}

// Watertight ray/triangle intersection (Woop, Benthin, Wald, JCGT 2013): no ray slips through a
// shared edge. Returns t and barycentrics.
bool hit_triangle(const Vec3& o, const Vec3& d, int kz, int kx, int ky, const Vec3& shear, const Vec3& a0, const Vec3& b0,
                  const Vec3& c0, double& t, double& u, double& v) {
  const Vec3 A = a0 - o, B = b0 - o, C = c0 - o;
  const double Ax = A[kx] - shear.x() * A[kz], Ay = A[ky] - shear.y() * A[kz];
  const double Bx = B[kx] - shear.x() * B[kz], By = B[ky] - shear.y() * B[kz];
  const double Cx = C[kx] - shear.x() * C[kz], Cy = C[ky] - shear.y() * C[kz];
  const double U = Cx * By - Cy * Bx;
  const double V = Ax * Cy - Ay * Cx;
  const double W = Bx * Ay - By * Ax;
  if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0)) return false;
  const double det = U + V + W;
  if (det == 0) return false;
  const double Az = shear.z() * A[kz], Bz = shear.z() * B[kz], Cz = shear.z() * C[kz];
  const double T = U * Az + V * Bz + W * Cz;
  t = T / det;
  u = V / det;
  v = W / det;
  (void)d;
  return true;
}

}  // namespace

std::optional<SurfaceHit> Scene::surface_hit(const Ray& ray) const {
  const std::optional<RayHit> h = intersect(ray);
  if (!h) return std::nullopt;
  Vec3 n = triangle_normal(h->triangle);
  const double len = n.norm();
  if (!(len > 0) || !std::isfinite(len)) return std::nullopt;  // zero-area: a watertight test cannot hit it; be safe
  n /= len;
  if (n.dot(ray.direction) > 0) n = -n;
  const auto& tri = soup_.triangles[h->triangle];
  const Vec3& a = soup_.vertices[tri[0]];
  const Vec3& b = soup_.vertices[tri[1]];
  const Vec3& c = soup_.vertices[tri[2]];
  return SurfaceHit{a + h->u * (b - a) + h->v * (c - a), n, h->triangle};
}

std::optional<RayHit> Scene::intersect(const Ray& ray) const {
  if (nodes_.empty()) return std::nullopt;
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  // 1/d per axis, +∞ for a zero component (set, not divided: no division-by-zero flag; 1/d of a
  // subnormal overflows to ∞ and counts as parallel, as its slab lies beyond any finite t_max).
  const auto inverse = [](double x) { return x == 0 ? std::numeric_limits<double>::infinity() : 1.0 / x; };
  const Vec3 inv_d(inverse(d.x()), inverse(d.y()), inverse(d.z()));
  int kz = 0;
  d.cwiseAbs().maxCoeff(&kz);
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (d[kz] < 0) std::swap(kx, ky);
  const Vec3 shear(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]);

  std::optional<RayHit> best;
  double t_max = ray.t_max;
  std::uint32_t stack[128];
  int sp = 0;
  stack[sp++] = 0;
  while (sp > 0) {
    const BvhNode& node = nodes_[stack[--sp]];
    if (!hit_box(node.box, o, inv_d, ray.t_min, t_max)) continue;
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        const std::uint32_t tri = order_[i];
        const auto& ix = soup_.triangles[tri];
        double t, u, v;
        if (hit_triangle(o, d, kz, kx, ky, shear, soup_.vertices[ix[0]], soup_.vertices[ix[1]], soup_.vertices[ix[2]], t, u, v) &&
            t > ray.t_min && t < t_max) {
          t_max = t;
          best = RayHit{t, tri, u, v};
        }
      }
    } else if (sp + 2 <= 128) {
      // Visit the nearer child first.
      const std::uint32_t l = node.first, r = node.first + 1;
      const double dl = (nodes_[l].box.centre() - o).squaredNorm();
      const double dr = (nodes_[r].box.centre() - o).squaredNorm();
      if (dl < dr) {
        stack[sp++] = r;
        stack[sp++] = l;
      } else {
        stack[sp++] = l;
        stack[sp++] = r;
      }
    }
  }
  return best;
}

}  // namespace skyband
