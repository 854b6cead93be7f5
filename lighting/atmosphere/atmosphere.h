#pragma once
// Spectral clear-sky atmosphere: sun spectrum at the ground and sky radiance, single scattering
// (Nishita et al. 1993 family) with optional multiple scattering (Hillaire 2020 isotropic
// multiple-scattering transfer, see below).
//
// Model (reference-notes §2.1, method.md §6):
//   * spherical shell: ground radius 6360 km (sea level), top 6420 km; the observer stands on a
//     plateau at ground_elevation_m (the ground sphere has radius 6360 km + elevation; the air
//     density profile stays anchored at sea level, so a high site has less air above it);
//   * air: exponential density, scale height 8000 m, Rayleigh scattering whose sea-level
//     coefficient is chosen so that the vertical optical depth from sea level equals Bucholtz
//     (1995) σ(λ) × the standard column 2.148e25 cm⁻² (the real atmosphere's effective scale
//     height is 8.43 km, so β(sea level) = τ/H_R, not Bucholtz σ·N_s — reference-notes §2.3);
//   * aerosol: exponential density anchored at the ground, scale height aerosol_scale_height_m,
//     extinction scaled so that the vertical optical depth from the ground is
//     aod550·(λ/550 nm)^−α (Ångström law); scattering = single-scattering albedo × extinction;
//     Cornette–Shanks phase function;
//   * ozone: tent profile (0 at 10 km, 1 at 25 km, 0 at 40 km), column ozone_du Dobson units
//     (1 DU = 2.687e20 molecules·m⁻²), absorption cross sections of Bruneton/Bremen (233 K);
//   * sun: ASTM G173 extraterrestrial spectrum (10-nm means), treated as a point source for the
//     scattering integrals (the 0.27° disc is in lighting/sun/sun.h).
//
// Spectral quantities are on the 41-sample grid of lighting/spectrum/spectrum.h.
// Directions: world frame x east, y north, z up; unit vectors.
#include <memory>
#include <mutex>
#include <vector>

#include "geometry/core/vec3.h"
#include "lighting/spectrum/spectrum.h"

namespace skyband {

struct AtmosphereParams {         // parameters a user knows; documented defaults
  double aod550 = 0.1;            // aerosol optical depth at 550 nm (vertical, from ground elevation)
  double angstrom_alpha = 1.3;    // Ångström exponent: τ_a(λ) = aod550·(λ/550 nm)^−α
  double ozone_du = 300;          // ozone column, Dobson units
  double ground_elevation_m = 0;  // metres above sea level
  double aerosol_scale_height_m = 1200;
  double aerosol_single_scattering_albedo = 0.9;
  double aerosol_asymmetry_g = 0.76;  // Cornette–Shanks g
  double ground_albedo = 0.1;         // used by multiple scattering
  void validate() const;              // throws InputError naming the field and value
};

enum class ScatteringOrders { Single, Multiple };

// Shell geometry and fixed constants (metres).
inline constexpr double kGroundRadius_m = 6360e3;
inline constexpr double kTopRadius_m = 6420e3;
inline constexpr double kRayleighScaleHeight_m = 8000.0;
inline constexpr double kDobsonUnit_molecules_m2 = 2.687e20;

// Density-weighted path lengths (metres) of one ray, one per absorber/scatterer profile:
// ∫ρ_R ds, ∫ρ_M ds, ∫ρ_O3 ds with ρ the dimensionless profiles (1 at their reference level).
// Optical depth τ(λ) = β_R(λ)·rayleigh + β_M,ext(λ)·aerosol + β_O3(λ)·ozone, so one set of three
// scalars serves every wavelength.
struct ColumnLengths {
  double rayleigh_m = 0;
  double aerosol_m = 0;
  double ozone_m = 0;
};

// The radiance of one sky direction split by phase function, so that a table can interpolate
// the smooth parts and apply the sharp phase functions exactly (Bruneton & Neyret 2008 §4):
// L = p_R(cos γ)·rayleigh + p_CS(cos γ)·aerosol + multiple, γ the angle view–sun.
// rayleigh and aerosol in W·m⁻²·nm⁻¹ (radiance × sr), multiple in W·m⁻²·sr⁻¹·nm⁻¹.
struct SkyRadianceParts {
  Spectrum rayleigh;
  Spectrum aerosol;
  Spectrum multiple;
};

class Atmosphere {
 public:
  explicit Atmosphere(const AtmosphereParams& p);
  const AtmosphereParams& params() const;
  Spectrum rayleigh_optical_depth() const;  // vertical, ground to top (dimensionless)
  Spectrum aerosol_optical_depth() const;
  Spectrum ozone_optical_depth() const;
  // Transmittance from ground along apparent altitude (radians, may be slightly negative near the horizon)
  Spectrum transmittance_to_space(double altitude_rad) const;
  // Extraterrestrial solar spectral irradiance, W·m⁻²·nm⁻¹ (ASTM G173 ETR, 10-nm means)
  static Spectrum extraterrestrial_irradiance();
  // Direct-normal spectral irradiance at the ground, W·m⁻²·nm⁻¹, sun at `altitude_rad` (apparent)
  Spectrum sun_direct_normal(double altitude_rad) const;
  // Sky spectral radiance W·m⁻²·sr⁻¹·nm⁻¹ seen from the ground looking along unit `view_dir`
  // (world frame: x east, y north, z up), sun along unit `sun_dir`. view_dir below the horizon:
  // radiance of the sky at the horizon (clamped) — callers only ask for sky directions.
  Spectrum sky_radiance(const Vec3& view_dir, const Vec3& sun_dir, ScatteringOrders orders) const;

  // --- the model's parts, used by the sky tables and the tests -----------------------------
  // The same integral split by phase function (see SkyRadianceParts); `multiple` is zero for
  // ScatteringOrders::Single.
  SkyRadianceParts sky_radiance_parts(const Vec3& view_dir, const Vec3& sun_dir, ScatteringOrders orders) const;
  // Coefficients at the profiles' reference levels, m⁻¹: Rayleigh at sea level, aerosol at the
  // ground, ozone at the tent peak (25 km).
  const Spectrum& rayleigh_scattering_per_m() const { return beta_rayleigh_; }
  const Spectrum& aerosol_extinction_per_m() const { return beta_aerosol_ext_; }
  const Spectrum& aerosol_scattering_per_m() const { return beta_aerosol_sca_; }
  const Spectrum& ozone_absorption_per_m() const { return beta_ozone_; }
  // Observer radius (m) = ground radius + elevation.
  double observer_radius_m() const { return r_ground_; }
  // Column lengths of the ray from radius r_m with direction cosine mu (to the local vertical)
  // up to the top of the atmosphere, by adaptive-free high-order quadrature (accurate to ~1e-7
  // relative); valid for rays that do not hit the ground (mu ≥ ground_horizon_mu(r_m)).
  ColumnLengths column_to_top(double r_m, double mu) const;
  // Same, from the precomputed table (bilinear in Bruneton's (r, μ) parametrisation), used in
  // the scattering integrals. Rays hitting the ground return `hits_ground = true`.
  ColumnLengths column_to_top_table(double r_m, double mu, bool& hits_ground) const;
  // cos of the zenith angle of the ground horizon seen from radius r_m (≤ 0).
  double ground_horizon_mu(double r_m) const;
  // exp(−τ) for the given column lengths.
  Spectrum transmittance(const ColumnLengths& c) const;
  // Multiple-scattering transfer Ψ_ms, W·m⁻²·sr⁻¹·nm⁻¹ (Hillaire 2020 eq. 9): β_s(x)·Ψ_ms is the
  // radiance of scattering orders ≥ 2 added per metre of view ray, taken isotropic; at radius
  // r_m for a sun at cos-zenith mu_sun (local vertical at that point). Bilinear in the table.
  void multiple_scattering_transfer(double r_m, double mu_sun, Spectrum& out) const;

 private:
  void build_column_table();
  // The multiple-scattering table is built on first use (thread-safe), so single-scattering
  // users do not pay for it; copies of an Atmosphere share it.
  void ensure_multiple_scattering_table() const;
  void build_multiple_scattering_table() const;
  // Local scattering coefficients (m⁻¹) at radius r.
  double rayleigh_density(double r_m) const;
  double aerosol_density(double r_m) const;
  double ozone_density(double r_m) const;

  AtmosphereParams p_;
  double r_ground_ = kGroundRadius_m;
  Spectrum beta_rayleigh_, beta_aerosol_ext_, beta_aerosol_sca_, beta_ozone_;
  Spectrum e0_;
  // Column-length table: kColR × kColMu entries of (rayleigh, aerosol, ozone).
  static constexpr int kColR = 64, kColMu = 256;
  std::vector<ColumnLengths> column_table_;
  // Multiple-scattering table Ψ_ms: kMsR × kMsMu spectra.
  static constexpr int kMsR = 16, kMsMu = 32;
  struct MultipleScatteringCache {
    std::once_flag once;
    std::vector<Spectrum> table;
  };
  // Shared by every Atmosphere built from equal parameters (shared_multiple_scattering_cache in
  // atmosphere.cpp): the table depends only on them, and each relit variant builds a new SkyModel.
  std::shared_ptr<MultipleScatteringCache> ms_;
  static std::shared_ptr<MultipleScatteringCache> shared_multiple_scattering_cache(const AtmosphereParams& p);
};

}  // namespace skyband
