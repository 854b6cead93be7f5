#pragma once
// Irradiation over a period of real weather at calculation points — the climate-based product of
// `skyband irradiance --weather`: per point, on the plane of its normal n, summed over the
// weather's intervals h (lengths Δt_h, the sun at each interval's middle):
//
//   sky     Σ_h Δt_h ∫_visible L_h(ω) (n·ω) dω = ∫_visible L_Σ(ω) (n·ω) dω, the time-integrated
//           Perez all-weather sky (cumulative_sky.h) integrated once over the point's visible sky
//           (geometry/visibility/visible_sky.h; exact by default). The quadrature of the grid is calibrated
//           so that an unobstructed horizontal face receives exactly Σ Δt·DHI (the calibration
//           factor, reported, is 1 to within the grid's interpolation error, ~10⁻³).
//   sun     Σ_h Δt_h · DNI_h · (n·s_h) · V_h over the intervals with the sun's centre above the
//           horizon (apparent, refracted altitude > 0) and in front of the face, V_h = 1 where the
//           sun is not hidden: a look-up in the point's visible sky (the exact test near its
//           boundary). sun_hours = Σ Δt_h over the same intervals, whatever the DNI.
//   ground  the ground as a Lambertian surface of radiance ρ_h·GHI_h/π below the horizon, seen
//           where no building hides it: Σ_h Δt_h ρ_h GHI_h · G, with the ground view factor
//           G = (1/π) ∫_{visible ground} (n·ω) dω over the part of the lower hemisphere in front of
//           the face that no non-ground triangle hides. G is computed exactly, as the SVF of the
//           point mirrored in its horizontal plane in the model's non-ground triangles mirrored in
//           the same way (one mirrored scene for all points: z → −z). Triangles whose material is
//           a ground material are the ground itself: they hide nothing below the horizon. An
//           unobstructed face of tilt β gets G = (1 − cos β)/2, the isotropic ground term.
//           Light reflected by buildings is not included.
// Channels: broadband shortwave W·h·m⁻² (what a pyranometer and the weather file measure) and
// light exposure lx·h (the file's illuminances, or the Perez 1990 luminous efficacy).
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "geometry/bands/band_visibility.h"
#include "geometry/mesh/scene.h"
#include "geometry/visibility/sky_factors.h"
#include "geometry/visibility/sky_visibility.h"
#include "geometry/visibility/visible_sky.h"
#include "lighting/sky/cumulative_sky.h"

namespace skyband {

// Material names that mark the ground (compared without case): the land-surface classes of
// 3dfier, CityGML and CityJSON and the plain words.
std::vector<std::string> default_ground_materials();

// Per triangle of `soup`, whether its material is one of `ground_materials` (without case).
std::vector<bool> ground_triangle_mask(const TriangleSoup& soup, const std::vector<std::string>& ground_materials);

struct ClimateIrradiationOptions {
  VisibilityOptions visibility;
  SkyFactorsMethod method = SkyFactorsMethod::automatic;
  double max_step_rad = 0.2;  // azimuth quadrature of the sky integral (point_irradiance.h)
  int threads = 0;            // 0 = all cores; the results do not depend on it
  std::vector<std::string> ground_materials = default_ground_materials();
};

struct PointClimate {
  double svf = 0, sky_exposure = 0;
  double ground_view = 0;  // G above
  double sky_Wh_m2 = 0, sun_Wh_m2 = 0, ground_Wh_m2 = 0;
  double sky_lxh = 0, sun_lxh = 0, ground_lxh = 0;
  double sun_hours = 0;
  SkyMethod method = SkyMethod::exact_union;
};

struct ClimateRun {
  std::vector<PointClimate> points;    // in input order
  double sky_calibration[2] = {1, 1};  // factor applied to the sky quadrature per channel (exact methods)
  std::size_t ground_triangles = 0;    // triangles with a ground material
  std::size_t sky_intervals = 0;       // intervals with diffuse light
  std::size_t sun_intervals = 0;       // intervals with the sun above the horizon
  SkyMethodCounts counts;
};

// Hourly results of one point, handed over as soon as the point is done (from the workers,
// concurrently for different points): per interval the mean irradiances in W·m⁻² of the sky, the
// sun and the ground, and the mean global illuminance in lx (each span has one value per interval
// of `hours`). The sky's hourly values come from the point's daylight coefficients
// (daylight_coefficients.h) with each hour's sky normalised so that an open horizontal face
// receives exactly its DHI; their sum over the period agrees with sky_Wh_m2 (the time-integrated
// sky's quadrature) to ~10⁻³. The illuminance is the same three terms in the photometric channel,
// as the sums take it: the sky's radiance scaled by the hour's diffuse efficacy E_v,d/DHI (the sky
// of one hour has one shape in both channels, cumulative_sky.h), the sun by E_v,direct·(n·s), the
// ground by ρ·E_v,global·G.
using ClimateHourlySink = std::function<void(std::size_t point, std::span<const float> sky, std::span<const float> sun,
                                             std::span<const float> ground, std::span<const float> global_lx)>;

// `progress(done, total)` from one thread over both passes (ground, then sky and sun).
ClimateRun compute_point_climate(const Scene& scene, std::span<const QueryPoint> points, std::span<const WeatherHour> hours,
                                 const ClimateIrradiationOptions& options,
                                 const std::function<void(std::size_t, std::size_t)>& progress = {},
                                 const ClimateHourlySink& hourly = {});

}  // namespace skyband
