#pragma once
// The sky radiance resampled on a grid for the renderer's many look-ups (the specular march
// takes hundreds of directions per point; the background one per pixel sample).
//
// Parametrisation: the stereographic projection of the upper hemisphere from the nadir,
//     p = (ω_x, ω_y)/(1 + ω_z),   |p| ≤ 1,
// on kCells × kCells equal cells over [−1, 1]². No trigonometry per look-up (one square root
// and one division), smooth everywhere including the zenith (a latitude–longitude grid has a
// pole there); the angular node spacing dθ = 2·dp/(1 + |p|²) is 2·dp at the zenith and dp at
// the horizon: 0.57° to 0.29° for kCells = 400. Nodes outside the unit disk hold the linear
// extension of the sky across the horizon (2·L(rim) − L(mirror point inside), clamped at 0), so
// cells cut by the horizon interpolate a smooth function too. Bilinear interpolation: error
// ≤ (h²/8)·max|∂²L| per axis, h the node spacing in p (0.005).
//
// SkyRadianceGrid holds spectra (41 floats per node, W·m⁻²·sr⁻¹·nm⁻¹). ProjectedSkyGrid holds
// up to kMaxChannels linear functionals of them, c_k(ω) = Σ_i P_k(λ_i)·L(λ_i, ω) (e.g. CIE XYZ
// with P = xyz_weights(), in W·m⁻²·sr⁻¹): the same interpolation commutes with any projection,
// so projecting nodes first is exact.
// Directions at or below the horizon (ω_z ≤ 0) give 0, as SkyModel::radiance_into does.
#include <algorithm>
#include <functional>
#include <span>
#include <vector>

#include "geometry/core/vec3.h"
#include "lighting/spectrum/spectrum.h"

namespace skyband {

class ProjectedSkyGrid;

// Cells per axis of the stereographic grids.
inline constexpr int kSkyGridCells = 400;

// Unit direction of the point p of the unit disk (the inverse stereographic projection); points
// on or beyond the rim are pulled in to just inside it, so the direction lies just above the
// horizon (the sky models are 0 at exactly ω_z = 0 but continuous from above).
Vec3 sky_grid_disk_direction(double px, double py);

// Grid coordinates of a direction: false at or below the horizon; else cell (ix, iy) and the
// fractions (fx, fy) ∈ [0, 1] within it.
bool sky_grid_cell(const Vec3& dir, int cells, int& ix, int& iy, double& fx, double& fy);

// The same for a direction of unit length (up to rounding): p = (ω_x, ω_y)/(1 + ω_z), no square
// root. Inline: the specular march looks up ~10⁸ directions per image.
// (With ω_z > 0 and |ω| = 1 + O(10⁻¹⁶), |p| < 1 + O(10⁻¹⁶): u, v ∈ [0, cells] up to rounding,
// so the cell index needs clamping only at the top end and the fractions stay within
// [−10⁻¹³, 1 + 10⁻¹³], which bilinear weights tolerate; the bounds are still enforced.)
inline bool sky_grid_cell_unit(const Vec3& dir, int cells, int& ix, int& iy, double& fx, double& fy) {
  if (!(dir.z() > 0.0)) return false;  // also NaN
  const double half = 0.5 * cells;
  const double k = half / (1.0 + dir.z());
  const double u = std::max(dir.x() * k + half, 0.0), v = std::max(dir.y() * k + half, 0.0);
  ix = std::min(static_cast<int>(u), cells - 1);
  iy = std::min(static_cast<int>(v), cells - 1);
  fx = u - ix;
  fy = v - iy;
  return true;
}

// out[k], k < n: bilinear interpolation in cell (ix, iy) at fractions (fx, fy) of a grid
// storing n values per node ([row][column][value]).
inline void sky_grid_bilinear(const float* data, std::size_t n, int ix, int iy, double fx, double fy, double* out) {
  const std::size_t row = static_cast<std::size_t>(kSkyGridCells + 1) * n;
  const float* a = data + static_cast<std::size_t>(iy) * row + static_cast<std::size_t>(ix) * n;  // (ix, iy)
  const float* b = a + n;                                                                         // (ix + 1, iy)
  const float* c = a + row;                                                                       // (ix, iy + 1)
  const float* d = c + n;
  const double w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy, w11 = fx * fy;
  for (std::size_t k = 0; k < n; ++k) out[k] = w00 * a[k] + w10 * b[k] + w01 * c[k] + w11 * d[k];
}

// out[k], k < n: bilinear interpolation at `dir` (any non-zero length); zeros at or below the
// horizon. Inline so that a constant n unrolls.
inline void sky_grid_interpolate(const float* data, std::size_t n, const Vec3& dir, double* out) {
  int ix, iy;
  double fx, fy;
  if (!sky_grid_cell(dir, kSkyGridCells, ix, iy, fx, fy)) {
    for (std::size_t k = 0; k < n; ++k) out[k] = 0.0;
    return;
  }
  sky_grid_bilinear(data, n, ix, iy, fx, fy, out);
}

class SkyRadianceGrid {
 public:
  static constexpr int kCells = kSkyGridCells;
  // `sky(unit world direction, out)`: W·m⁻²·sr⁻¹·nm⁻¹. Evaluated at (kCells + 1)² directions,
  // in parallel (`threads` = 0: all cores).
  SkyRadianceGrid(const std::function<void(const Vec3&, Spectrum&)>& sky, int threads = 0);

  void operator()(const Vec3& dir, Spectrum& out) const;  // any non-zero length
  ProjectedSkyGrid project(std::span<const Spectrum> weights) const;

 private:
  std::vector<float> data_;  // [row iy][column ix][wavelength]
};

class ProjectedSkyGrid {
 public:
  static constexpr int kMaxChannels = 12;
  int channels() const { return channels_; }
  // out[k] = c_k(dir), k < channels().
  void lookup(const Vec3& dir, double* out) const;
  // this += k·other, node by node (same channel count, else std::invalid_argument): by the
  // linearity of the interpolation, the look-ups of the sum are the sums of the look-ups. A
  // time-integrated sky (Σ_t hours_t·L_t) for cumulative irradiation is built this way. An empty
  // grid (default-constructed) takes other's shape.
  void add_scaled(const ProjectedSkyGrid& other, double k);
  // The grid of `channels` (1..kMaxChannels) functions of direction sampled directly at the
  // nodes, with the same horizon extension as SkyRadianceGrid: `f(unit direction above the
  // horizon, out[channels])`, evaluated in parallel (`threads` = 0: all cores).
  static ProjectedSkyGrid sample(int channels, const std::function<void(const Vec3&, double*)>& f, int threads = 0);
  // The same for a compile-time channel count N == channels() (the renderer's hot loop).
  template <int N>
  void lookup_n(const Vec3& dir, double* out) const {
    sky_grid_interpolate(data_.data(), N, dir, out);
  }
  // out[k], k < N == channels(): the bilinear interpolation in cell (ix, iy) at fractions (fx, fy)
  // (from sky_grid_cell_unit or the same arithmetic done elsewhere).
  template <int N>
  void lookup_cell_n(int ix, int iy, double fx, double fy, double* out) const {
    sky_grid_bilinear(data_.data(), N, ix, iy, fx, fy, out);
  }
  // The same for a unit `dir` (sky_grid_cell_unit): the specular march's look-up.
  template <int N>
  void lookup_unit_n(const Vec3& dir, double* out) const {
    int ix, iy;
    double fx, fy;
    if (!sky_grid_cell_unit(dir, kSkyGridCells, ix, iy, fx, fy)) {
      for (int k = 0; k < N; ++k) out[k] = 0.0;
      return;
    }
    sky_grid_bilinear(data_.data(), N, ix, iy, fx, fy, out);
  }

 private:
  friend class SkyRadianceGrid;
  int channels_ = 0;
  std::vector<float> data_;  // [row][column][channel]
};

}  // namespace skyband
