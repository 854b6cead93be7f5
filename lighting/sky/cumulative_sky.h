#pragma once
// The sky of a period of weather as one radiance distribution: the time-integrated Perez
// all-weather sky (lighting/sky/perez_sky.h)
//     L_Σ(ω) = Σ_h Δt_h · L_h(ω),    L_h = k_h · l_h(θ, γ),  k_h = DHI_h / ∫ l_h cos θ dω,
// in two channels: broadband shortwave W·h·m⁻²·sr⁻¹ (normalised to the hour's DHI) and
// luminance cd·h·m⁻² (the same distribution normalised to the hour's diffuse horizontal
// illuminance). The irradiation of any face over the period is then one integral of L_Σ over its
// visible sky (the integral is linear in L: a daylight coefficient computed exactly per point, with
// no sky patches), which lighting/climate/climate_irradiation.h takes with the sky column tables.
//
// Sampling: each hour's sky is evaluated on a coarse stereographic grid (kCumulativeSkyCells² cells
// over [−1, 1]², the parametrisation of sky_radiance_grid.h: node spacing 1.8° at the horizon,
// 3.6° at the zenith), summed over the hours, and the sum is interpolated bilinearly onto the
// renderer's fine grid (ProjectedSkyGrid). The Perez distribution is smooth at that scale (its
// circumsolar term exp(dγ) falls by e over ≥ 5°), so the coarse grid costs ~4·10³ evaluations per
// hour instead of 1.6·10⁵: measured on Chicago's year, 48 and 80 cells give annual sky sums within
// 3·10⁻⁴ of each other on horizontal, tilted and vertical planes of every orientation. What the
// interpolation does to the total is also checked per run: `horizontal_*` hold the exact
// open-horizontal values (Σ Δt·DHI and Σ Δt·E_v,diffuse), against which the caller calibrates its
// quadrature (the factor is 1 − 3·10⁻⁵ on Chicago).
#include <span>

#include "geometry/core/vec3.h"
#include "lighting/sky/sky_radiance_grid.h"

namespace skyband {

inline constexpr int kCumulativeSkyCells = 64;

// One interval of weather, ready for lighting: the sun at its middle and its mean irradiances.
struct WeatherHour {
  Vec3 sun_dir{0, 0, 1};                            // unit, world frame (x east, y north, z up); may be below the horizon
  double hours = 1;                                 // length of the interval (h)
  int day_of_year = 1;                              // 1..366, for the extraterrestrial irradiance of the sky's brightness
  double ghi_W_m2 = 0, dni_W_m2 = 0, dhi_W_m2 = 0;  // means over the interval
  double ghi_lx = 0, dni_lx = 0, dhi_lx = 0;        // illuminances (the file's, or Perez 1990)
  double albedo = 0.2;                              // ground reflectance, [0, 1]
};

struct CumulativeSky {
  ProjectedSkyGrid grid;        // channels: W·h·m⁻²·sr⁻¹, cd·h·m⁻²
  double horizontal_Wh_m2 = 0;  // Σ Δt·DHI: the open horizontal face's sky irradiation
  double horizontal_lxh = 0;    // Σ Δt·E_v,diffuse (lx·h)
  std::size_t sky_hours = 0;    // intervals with DHI > 0
};

// Throws InputError (naming the interval's index) for a non-finite or negative irradiance.
CumulativeSky cumulative_perez_sky(std::span<const WeatherHour> hours, int threads = 0);

}  // namespace skyband
