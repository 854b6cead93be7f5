#include "lighting/atmosphere/sky_table.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

#include "geometry/core/gauss_legendre.h"
#include "geometry/core/input_error.h"
#include "lighting/atmosphere/phase_functions.h"

namespace skyband {

namespace {

constexpr double kHalfPi = 0.5 * kPi;

// Catmull–Rom weights for the 4 nodes around a fractional position t ∈ [0, 1) between nodes 1
// and 2 (cubic Hermite with central-difference tangents; exact for quadratics).
inline void catmull_rom_weights(double t, double w[4]) {
  const double t2 = t * t, t3 = t2 * t;
  w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
  w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
  w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
  w[3] = 0.5 * (t3 - t2);
}

// Relative azimuth index folded into [0, N−1] by the mirror symmetry about the sun's vertical
// plane (φ → −φ at 0 and φ → 2π − φ at π).
inline int fold_azimuth(int j, int n) {
  if (j < 0) return -j;
  if (j > n - 1) return 2 * (n - 1) - j;
  return j;
}

}  // namespace

SkyTable::SkyTable(const Atmosphere& atmosphere, const Vec3& sun_dir, ScatteringOrders orders) {
  const double n = sun_dir.norm();
  if (!std::isfinite(n) || n == 0.0) throw InputError("SkyTable: sun direction is not a direction");
  sun_dir_ = sun_dir / n;
  // Sun at the zenith: every vertical plane is a symmetry plane; any reference azimuth works.
  const double horiz = std::hypot(sun_dir_.x(), sun_dir_.y());
  sun_azimuth_rad_ = horiz > 0.0 ? std::atan2(sun_dir_.x(), sun_dir_.y()) : 0.0;
  aerosol_g_ = atmosphere.params().aerosol_asymmetry_g;
  has_multiple_ = orders == ScatteringOrders::Multiple;
  nodes_.resize(static_cast<std::size_t>(kAltitudeNodes * kAzimuthNodes));
  // Rows in parallel (each node is written by one task: the table does not depend on the thread
  // count). Atmosphere's queries are const and thread-safe.
  tbb::parallel_for(0, kAltitudeNodes, [&](int i) {
    const double u = static_cast<double>(i) / (kAltitudeNodes - 1);
    const double alt = kHalfPi * u * u;
    for (int j = 0; j < kAzimuthNodes; ++j) {
      const double az = sun_azimuth_rad_ + kPi * j / (kAzimuthNodes - 1);
      const Vec3 v(std::sin(az) * std::cos(alt), std::cos(az) * std::cos(alt), std::sin(alt));
      nodes_[static_cast<std::size_t>(i * kAzimuthNodes + j)] = atmosphere.sky_radiance_parts(v, sun_dir_, orders);
    }
  });
}

const Vec3& SkyTable::sun_direction() const {
  return sun_dir_;
}

Spectrum SkyTable::radiance(const Vec3& view_dir) const {
  Spectrum s;
  radiance_into(view_dir, s);
  return s;
}

void SkyTable::radiance_into(const Vec3& view_dir, Spectrum& out) const {
  const double n = view_dir.norm();
  Vec3 v = (n > 0.0 && std::isfinite(n)) ? Vec3(view_dir / n) : Vec3(0.0, 0.0, 1.0);
  if (v.z() < 0.0) {  // below the horizon: the horizon radiance (Atmosphere's convention)
    v.z() = 0.0;
    const double h = v.norm();
    v = h > 0.0 ? Vec3(v / h) : Vec3(std::sin(sun_azimuth_rad_), std::cos(sun_azimuth_rad_), 0.0);
  }
  const double alt = std::asin(std::clamp(v.z(), 0.0, 1.0));
  const double u = std::sqrt(alt / kHalfPi) * (kAltitudeNodes - 1);
  double dphi = std::atan2(v.x(), v.y()) - sun_azimuth_rad_;
  dphi = std::remainder(dphi, 2.0 * kPi);  // (−π, π]
  const double a = std::abs(dphi) / kPi * (kAzimuthNodes - 1);
  const int i0 = std::min(static_cast<int>(u), kAltitudeNodes - 2);
  const int j0 = std::min(static_cast<int>(a), kAzimuthNodes - 2);
  double wu[4], wa[4];
  catmull_rom_weights(u - i0, wu);
  catmull_rom_weights(a - j0, wa);
  const double cos_gamma = std::clamp(v.dot(sun_dir_), -1.0, 1.0);
  const double pr = rayleigh_phase(cos_gamma), pm = cornette_shanks_phase(cos_gamma, aerosol_g_);
  // Gather the 16 nodes and their weights, then one pass per part (contiguous 41-sample loops
  // the compiler vectorises); the multiple part is skipped for single-scattering tables.
  const SkyRadianceParts* p[16];
  double w[16];
  for (int di = 0; di < 4; ++di) {
    // Altitude ends: the node row is repeated (clamped) beyond the horizon and the zenith.
    const int ii = std::clamp(i0 - 1 + di, 0, kAltitudeNodes - 1);
    for (int dj = 0; dj < 4; ++dj) {
      p[di * 4 + dj] = &node(ii, fold_azimuth(j0 - 1 + dj, kAzimuthNodes));
      w[di * 4 + dj] = wu[di] * wa[dj];
    }
  }
  double* o = out.v.data();
  for (int q = 0; q < kSpectrumSamples; ++q) o[q] = 0.0;
  for (int k = 0; k < 16; ++k) {
    const double wr = w[k] * pr, wm = w[k] * pm;
    const double* r = p[k]->rayleigh.v.data();
    const double* m = p[k]->aerosol.v.data();
    for (int q = 0; q < kSpectrumSamples; ++q) o[q] += wr * r[q] + wm * m[q];
  }
  if (has_multiple_) {
    for (int k = 0; k < 16; ++k) {
      const double wk = w[k];
      const double* ms = p[k]->multiple.v.data();
      for (int q = 0; q < kSpectrumSamples; ++q) o[q] += wk * ms[q];
    }
  }
  // Catmull–Rom can undershoot slightly where the data bend sharply; radiance is never negative.
  for (int q = 0; q < kSpectrumSamples; ++q) out[q] = std::max(0.0, out[q]);
}

Spectrum SkyTable::horizontal_irradiance() const {
  // Gauss–Legendre nodes: 4 panels × 8 in μ = cos θ ∈ [0, 1], 8 panels × 8 in φ ∈ [0, π].
  auto nodes = [](double a, double b, int panels, std::vector<double>& x, std::vector<double>& w) {
    const double h = (b - a) / panels;
    for (int p = 0; p < panels; ++p)
      for (int k = 0; k < 4; ++k)
        for (int sgn = -1; sgn <= 1; sgn += 2) {
          x.push_back(a + (p + 0.5) * h + sgn * 0.5 * h * kGauss8HalfNodes[k]);
          w.push_back(0.5 * h * kGauss8HalfWeights[k]);
        }
  };
  std::vector<double> mu, wmu, phi, wphi;
  nodes(0.0, 1.0, 4, mu, wmu);
  nodes(0.0, kPi, 8, phi, wphi);
  Spectrum e, l;
  for (std::size_t a = 0; a < mu.size(); ++a) {
    const double st = std::sqrt(std::max(0.0, 1.0 - mu[a] * mu[a]));
    for (std::size_t b = 0; b < phi.size(); ++b) {
      const double az = sun_azimuth_rad_ + phi[b];
      radiance_into(Vec3(std::sin(az) * st, std::cos(az) * st, mu[a]), l);
      e += l * (2.0 * mu[a] * wmu[a] * wphi[b]);  // ×2: the mirror half φ ∈ [π, 2π]
    }
  }
  return e;
}

}  // namespace skyband
