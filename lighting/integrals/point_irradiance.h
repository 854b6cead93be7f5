#pragma once
// Irradiance on the surface of calculation points — the data product of `skyband irradiance`
// for daylight and urban-climate analysts: per point, on the plane of its normal n,
//
//   sky  E_sky = ∫_visible L(ω) (n·ω) dω over the point's visible sky (geometry/visibility/visible_sky.h,
//        computed as geometry/visibility/sky_visibility.h decides; method automatic, the default, is exact at
//        every point). Over an exact region (a signed fan of spherical triangles,
//        geometry/exact/sky_fan.h) with the sky's column tables (sky_column_table.h: the elevation
//        integrals tabulated once per sky, a Gauss–Legendre quadrature in azimuth per point,
//        pieces ≤ max_step_rad/4); svf and sky_exposure are then exact. With the band method
//        = Σ_b w_b Σ_visible ∫ L(ω(α, δ_b)) sin²α dα   (seed eq. 1)
//        over the point's band lines (exact occluded α-intervals, refined bands), with the
//        Gauss–Legendre quadrature of geometry/bands/sky_integral.h (integrate_irradiance_channels)
//        instead of per-band tables (sky_lut.h): a refined band layout differs from point to point,
//        so per-layout tables would not be shared. L is the sky model resampled on the
//        stereographic grid (sky_radiance_grid.h) and projected to two channels.
//   sun  E_sun = E_n · (n·s) · V  where n·s > 0, else 0; E_n the direct-normal irradiance of the
//        sun (SkyModel::sun_direct_normal) and V = 1 when the direction of the sun's centre is
//        unoccluded: a look-up in the point's visible sky, the exact sample-plane test near its
//        boundary (SkyVisibility::direction_visible; the sun is a point).
//
// Channels: radiometric W·m⁻² over the model's 380–780 nm grid (trapezoid rule, as
// Spectrum::integral_nm) and photometric lx (K_m·∫ E ȳ dλ, as colour.h luminous()).
// Not included: light reflected by the ground and the buildings (the band method models the sky
// and the sun only), and the sky below the horizon (SkyModel gives it zero radiance).
#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "geometry/bands/band_visibility.h"
#include "geometry/visibility/sky_factors.h"
#include "geometry/visibility/visible_sky.h"
#include "lighting/sky/sky_model.h"

namespace skyband {

struct PointIrradiance {
  double svf = 0;            // cosine-weighted sky view factor (geometry/bands/sky_integral.h)
  double sky_exposure = 0;   // visible sky solid angle in front of the face / 2π
  double cos_incidence = 0;  // n·s, the cosine of the sun's incidence angle (< 0: sun behind the face)
  bool sun_visible = false;  // sun above the horizon, in front of the face and not hidden
  double sky_W_m2 = 0;       // diffuse sky irradiance, W·m⁻² (380–780 nm)
  double sun_W_m2 = 0;       // direct sun irradiance, W·m⁻² (380–780 nm)
  double sky_lx = 0;         // diffuse sky illuminance, lx
  double sun_lx = 0;         // direct sun illuminance, lx
  // sky_lx over the sky illuminance of an unobstructed horizontal face under the same sky
  // (computed the same way, so an open horizontal point gives exactly 1). Under the CIE standard
  // overcast sky this is the vertical sky component of a vertical face (BRE 209, BS 8206-2:
  // 39.6 % unobstructed) and the sky factor of a horizontal one.
  double sky_ratio = 0;
  SkyMethod method = SkyMethod::exact_union;  // how the visible sky was computed
};

struct PointIrradianceOptions {
  VisibilityOptions visibility;
  // Longest Gauss–Legendre piece along a visible interval (radians; a quarter of it in azimuth for
  // the exact horizon); see integrate_irradiance_channels. Measured against 0.0125 rad
  // (bench_irradiance, physical sky with its aureole, city points): band method relative error
  // 4e-6 at 0.05, 1e-5 at 0.2, 8e-5 at 0.4; exact horizon ≤ 1e-5 at every step from 0.05 to 0.4.
  double max_step_rad = 0.2;
  int threads = 0;  // 0 = all cores; the results do not depend on it
  // automatic: the exact horizon where valid, the band method (`visibility`) elsewhere; bands:
  // the band method everywhere (geometry/visibility/sky_factors.h).
  SkyFactorsMethod method = SkyFactorsMethod::automatic;
};

// Irradiance at every point under one sky and sun. Memory O(points): the visibility cache is
// consumed chunk by chunk (for_each_visibility_chunk). `progress(done, total)` from one thread.
std::vector<PointIrradiance> compute_point_irradiance(const Scene& scene, std::span<const QueryPoint> points, const SkyModel& sky,
                                                      const PointIrradianceOptions& options,
                                                      const std::function<void(std::size_t, std::size_t)>& progress = {});

// A sun position and the hours it stands for (e.g. 0.5 for half-hourly steps).
struct SunMoment {
  Vec3 sun_dir;        // unit, world frame (the sky model's sun; may be below the horizon)
  double hours = 1.0;  // ≥ 0
};

// Irradiation over many moments under one atmosphere and sky model, per point: Σ_t hours_t·E_t.
// The sky part is one quadrature of the time-integrated sky Σ_t hours_t·L_t (the moments' sky
// grids summed, ProjectedSkyGrid::add_scaled: the quadrature is linear in L, so this is the sum
// of the per-moment sky terms up to the grid's float storage); the sun part is one exact shadow
// test per moment and point.
struct PointIrradiation {
  double svf = 0;
  double sky_exposure = 0;
  double sun_hours = 0;                       // Σ hours_t over the moments whose sun is visible (see sun_visible)
  double sky_Wh_m2 = 0;                       // diffuse sky irradiation, W·h·m⁻² (380–780 nm)
  double sun_Wh_m2 = 0;                       // direct sun irradiation, W·h·m⁻² (380–780 nm)
  double sky_lxh = 0;                         // diffuse sky light exposure, lx·h
  double sun_lxh = 0;                         // direct sun light exposure, lx·h
  SkyMethod method = SkyMethod::exact_union;  // how the visible sky was computed
};

// Builds each moment's SkyModel in turn (InputError for invalid parameters or hours, naming the
// moment's index), so memory does not grow with the number of moments. `sky_progress(done,
// total)` after each moment's sky, then `progress(done, total)` over the points.
std::vector<PointIrradiation> compute_point_irradiation(const Scene& scene, std::span<const QueryPoint> points,
                                                        const AtmosphereParams& atmosphere, const SkyModelSpec& spec,
                                                        std::span<const SunMoment> moments, const PointIrradianceOptions& options,
                                                        const std::function<void(std::size_t, std::size_t)>& progress = {},
                                                        const std::function<void(std::size_t, std::size_t)>& sky_progress = {});

// The sun alone over many moments (no sky model is built: a sun-hours study needs none): svf,
// sky_exposure, sun_hours and method of each point; the irradiation fields stay 0. A moment
// counts where its sun is above the horizon, in front of the face and not hidden.
std::vector<PointIrradiation> compute_point_sun_hours(const Scene& scene, std::span<const QueryPoint> points,
                                                      std::span<const SunMoment> moments, const PointIrradianceOptions& options,
                                                      const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace skyband
