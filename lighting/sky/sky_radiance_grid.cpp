#include "lighting/sky/sky_radiance_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "geometry/core/thread_arena.h"

namespace skyband {

namespace {

constexpr int kNodes = SkyRadianceGrid::kCells + 1;

}  // namespace

Vec3 sky_grid_disk_direction(double px, double py) {
  constexpr double kRimRadius = 1.0 - 1e-6;
  const double r2 = px * px + py * py;
  if (r2 > kRimRadius * kRimRadius) {
    const double k = kRimRadius / std::sqrt(r2);
    px *= k;
    py *= k;
  }
  const double q = px * px + py * py;
  return Vec3(2.0 * px, 2.0 * py, 1.0 - q) / (1.0 + q);
}

bool sky_grid_cell(const Vec3& dir, int cells, int& ix, int& iy, double& fx, double& fy) {
  // Non-finite components first: an ordered comparison with a NaN raises FE_INVALID.
  if (!std::isfinite(dir.x()) || !std::isfinite(dir.y()) || !std::isfinite(dir.z()) || !(dir.z() > 0.0)) return false;
  const double len = dir.norm();
  if (!(len > 0.0) || !std::isfinite(len)) return false;
  const double k = 1.0 / (len + dir.z());  // p = (x, y)/(|ω| + z): the projection of ω/|ω|
  const double u = (dir.x() * k + 1.0) * 0.5 * cells, v = (dir.y() * k + 1.0) * 0.5 * cells;
  ix = std::clamp(static_cast<int>(u), 0, cells - 1);
  iy = std::clamp(static_cast<int>(v), 0, cells - 1);
  fx = std::clamp(u - ix, 0.0, 1.0);
  fy = std::clamp(v - iy, 0.0, 1.0);
  return true;
}

SkyRadianceGrid::SkyRadianceGrid(const std::function<void(const Vec3&, Spectrum&)>& sky, int threads)
    : data_(static_cast<std::size_t>(kNodes) * kNodes * kSpectrumSamples) {
  run_with_threads(threads, [&] {
    tbb::parallel_for(0, kNodes, [&](int iy) {
      Spectrum l, inner;
      const double h = 2.0 / kCells;
      for (int ix = 0; ix < kNodes; ++ix) {
        const double px = -1.0 + ix * h, py = -1.0 + iy * h;
        const double r = std::sqrt(px * px + py * py);
        if (r <= 1.0) {
          sky(sky_grid_disk_direction(px, py), l);
        } else {
          // Outside the disk: the linear extension across the rim, 2·L(rim) − L(mirror point at
          // radius 2 − r), so that cells cut by the horizon interpolate a C¹ function (second-
          // order error) instead of a clamped one (first order). Clamped at 0: radiance.
          sky(sky_grid_disk_direction(px, py), l);
          const double k = (2.0 - r) / r;
          sky(sky_grid_disk_direction(px * k, py * k), inner);
          for (int i = 0; i < kSpectrumSamples; ++i) l[i] = std::max(0.0, 2.0 * l[i] - inner[i]);
        }
        float* d = &data_[(static_cast<std::size_t>(iy) * kNodes + static_cast<std::size_t>(ix)) * kSpectrumSamples];
        for (int k = 0; k < kSpectrumSamples; ++k) d[k] = static_cast<float>(l[k]);
      }
    });
  });
}

void SkyRadianceGrid::operator()(const Vec3& dir, Spectrum& out) const {
  sky_grid_interpolate(data_.data(), kSpectrumSamples, dir, out.v.data());
}

ProjectedSkyGrid SkyRadianceGrid::project(std::span<const Spectrum> weights) const {
  if (weights.empty() || weights.size() > static_cast<std::size_t>(ProjectedSkyGrid::kMaxChannels))
    throw std::invalid_argument("SkyRadianceGrid::project: 1 to 12 channels, got " + std::to_string(weights.size()));
  ProjectedSkyGrid g;
  g.channels_ = static_cast<int>(weights.size());
  const std::size_t kC = weights.size();
  const std::size_t nodes = static_cast<std::size_t>(kNodes) * kNodes;
  g.data_.assign(nodes * kC, 0.0f);
  tbb::parallel_for(std::size_t{0}, nodes, std::size_t{4096}, [&](std::size_t n0) {
    const std::size_t n1 = std::min(n0 + 4096, nodes);
    for (std::size_t n = n0; n < n1; ++n) {
      const float* l = &data_[n * kSpectrumSamples];
      for (std::size_t k = 0; k < weights.size(); ++k) {
        double s = 0;
        for (int i = 0; i < kSpectrumSamples; ++i) s += weights[k][i] * l[i];
        g.data_[n * kC + k] = static_cast<float>(s);
      }
    }
  });
  return g;
}

void ProjectedSkyGrid::add_scaled(const ProjectedSkyGrid& other, double k) {
  if (channels_ == 0) {
    channels_ = other.channels_;
    data_.assign(other.data_.size(), 0.0f);
  }
  if (other.channels_ != channels_ || other.data_.size() != data_.size())
    throw std::invalid_argument("ProjectedSkyGrid::add_scaled: " + std::to_string(other.channels_) + " channels added to " +
                                std::to_string(channels_));
  for (std::size_t i = 0; i < data_.size(); ++i)
    data_[i] = static_cast<float>(static_cast<double>(data_[i]) + k * static_cast<double>(other.data_[i]));
}

ProjectedSkyGrid ProjectedSkyGrid::sample(int channels, const std::function<void(const Vec3&, double*)>& f, int threads) {
  if (channels < 1 || channels > kMaxChannels)
    throw std::invalid_argument("ProjectedSkyGrid::sample: 1 to 12 channels, got " + std::to_string(channels));
  ProjectedSkyGrid g;
  g.channels_ = channels;
  const std::size_t kC = static_cast<std::size_t>(channels);
  g.data_.assign(static_cast<std::size_t>(kNodes) * kNodes * kC, 0.0f);
  run_with_threads(threads, [&] {
    tbb::parallel_for(0, kNodes, [&](int iy) {
      double l[kMaxChannels], inner[kMaxChannels];
      const double h = 2.0 / SkyRadianceGrid::kCells;
      for (int ix = 0; ix < kNodes; ++ix) {
        const double px = -1.0 + ix * h, py = -1.0 + iy * h;
        const double r = std::sqrt(px * px + py * py);
        f(sky_grid_disk_direction(px, py), l);
        if (r > 1.0) {  // the linear extension across the rim (SkyRadianceGrid), clamped at 0
          const double k = (2.0 - r) / r;
          f(sky_grid_disk_direction(px * k, py * k), inner);
          for (std::size_t c = 0; c < kC; ++c) l[c] = std::max(0.0, 2.0 * l[c] - inner[c]);
        }
        float* d = &g.data_[(static_cast<std::size_t>(iy) * kNodes + static_cast<std::size_t>(ix)) * kC];
        for (std::size_t c = 0; c < kC; ++c) d[c] = static_cast<float>(l[c]);
      }
    });
  });
  return g;
}

void ProjectedSkyGrid::lookup(const Vec3& dir, double* out) const {
  sky_grid_interpolate(data_.data(), static_cast<std::size_t>(channels_), dir, out);
}

}  // namespace skyband
