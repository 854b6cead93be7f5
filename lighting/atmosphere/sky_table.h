#pragma once
// Precomputed sky radiance for one sun position, for fast look-ups (sky integrals, images).
//
// The table stores the three smooth parts of the radiance (SkyRadianceParts: Rayleigh and aerosol
// in-scattering without their phase functions, and the multiple-scattering term) on a grid of
// (view altitude, azimuth relative to the sun) and applies the Rayleigh and Cornette–Shanks phase
// functions exactly at look-up time, so the sharp aureole around the sun is not interpolated
// (Bruneton & Neyret 2008 §4 store Rayleigh and Mie separately for the same reason).
// Only relative azimuth 0..π is stored: the sky is symmetric about the sun's vertical plane.
// The altitude axis is quadratic (altitude = π/2·u²) so that the steep brightening of the last
// degrees above the horizon is resolved. Interpolation: bicubic Catmull–Rom in (u, azimuth).
// The measured interpolation error against Atmosphere::sky_radiance is in sky_table_test.cpp:
// ≤ 0.31% relative for sun altitudes ≥ 4° (single and multiple scattering, including the
// aureole). Limitation: with the sun below the horizon (twilight), the Earth's-shadow edge makes
// the single-scattering table err by up to ~5% (of max(L, 1% of the sky maximum)); multiple
// scattering (smooth) stays within 0.5%.
#include <vector>

#include "geometry/core/vec3.h"
#include "lighting/atmosphere/atmosphere.h"
#include "lighting/spectrum/spectrum.h"

namespace skyband {

class SkyTable {
 public:
  SkyTable(const Atmosphere& atmosphere, const Vec3& sun_dir, ScatteringOrders orders);
  Spectrum radiance(const Vec3& view_dir) const;                  // interpolated
  void radiance_into(const Vec3& view_dir, Spectrum& out) const;  // no allocation, hot path
  const Vec3& sun_direction() const;
  // Diffuse (sky-only) spectral irradiance on an unobstructed horizontal plane, W·m⁻²·nm⁻¹:
  // E = ∫_{upper hemisphere} L(ω) cos θ dω, by Gauss–Legendre quadrature of the table
  // (32 nodes in cos θ × 64 in relative azimuth on [0, π], doubled by symmetry).
  Spectrum horizontal_irradiance() const;

  static constexpr int kAltitudeNodes = 48;  // u = 0..1 (horizon..zenith)
  static constexpr int kAzimuthNodes = 48;   // relative azimuth 0..π

 private:
  const SkyRadianceParts& node(int i_alt, int i_az) const {
    return nodes_[static_cast<std::size_t>(i_alt * kAzimuthNodes + i_az)];
  }
  Vec3 sun_dir_;
  double sun_azimuth_rad_ = 0;
  double aerosol_g_ = 0;
  bool has_multiple_ = false;
  std::vector<SkyRadianceParts> nodes_;
};

}  // namespace skyband
