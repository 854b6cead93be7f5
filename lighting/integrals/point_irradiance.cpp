// Irradiance at calculation points: sky through the visibility cache, sun with the exact shadow
// test (point_irradiance.h has the formulas).
#include "lighting/integrals/point_irradiance.h"

#include <array>
#include <cmath>
#include <memory>
#include <optional>

#include "geometry/bands/sky_integral.h"
#include "geometry/core/input_error.h"
#include "geometry/exact/sky_fan.h"
#include "geometry/visibility/sky_visibility.h"
#include "lighting/integrals/sky_column_table.h"
#include "lighting/integrals/visible_sky_integral.h"
#include "lighting/sky/sky_radiance_grid.h"
#include "lighting/spectrum/colour.h"

namespace skyband {

namespace {

// Projection weights of the two channels: trapezoid weights of the grid (nm), so that
// Σ_i w_i·E(λ_i) = Spectrum::integral_nm() (W·m⁻²), and K_m·ȳ times the same weights (lx).
std::array<Spectrum, 2> channel_weights() {
  Spectrum trapezoid = Spectrum::constant(kLambdaStepNm);
  trapezoid[0] = trapezoid[kSpectrumSamples - 1] = 0.5 * kLambdaStepNm;
  return {trapezoid, kMaxLuminousEfficacy_lm_W * xyz_weights(1)};
}

// The sky model resampled on the stereographic grid and projected to the two channels.
ProjectedSkyGrid project_sky(const SkyModel& sky, int threads) {
  const std::array<Spectrum, 2> weights = channel_weights();
  return SkyRadianceGrid([&](const Vec3& d, Spectrum& out) { sky.radiance_into(d, out); }, threads).project(weights);
}

void check_step(double max_step_rad) {
  if (!(max_step_rad > 0) || !std::isfinite(max_step_rad))
    throw InputError("irradiance: quadrature step " + std::to_string(max_step_rad) + " rad must be finite and > 0");
}

// Every point's visible sky (geometry/visibility/sky_visibility.h): fills svf, sky_exposure and method of
// out[i] and hands (the sky, the point, its worker — for the sun's look-ups —, out[i]) to `fill`.
template <class Result, class Fill>
std::vector<Result> for_each_point(const Scene& scene, std::span<const QueryPoint> points, const PointIrradianceOptions& options,
                                   const std::function<void(std::size_t, std::size_t)>& progress, Fill&& fill) {
  std::vector<Result> out(points.size());
  for_each_visible_sky(scene, points, options.visibility, options.method, options.threads, progress, true,
                       [&](std::size_t i, const VisibleSky& sky, SkyVisibility& worker) {
                         Result& r = out[i];
                         r.svf = sky.factors.svf;
                         r.sky_exposure = sky.factors.sky_exposure;
                         r.method = sky.method;
                         fill(sky, points[i], worker, r);
                       });
  return out;
}

}  // namespace

std::vector<PointIrradiance> compute_point_irradiance(const Scene& scene, std::span<const QueryPoint> points, const SkyModel& sky,
                                                      const PointIrradianceOptions& options,
                                                      const std::function<void(std::size_t, std::size_t)>& progress) {
  check_step(options.max_step_rad);
  const ProjectedSkyGrid projected = project_sky(sky, options.threads);
  const SkyTables grid(projected, options.threads);
  const Spectrum& dn = sky.sun_direct_normal();
  const double sun_W_m2 = dn.integral_nm(), sun_lx = luminous(dn);
  const Vec3 s = sky.sun_direction();

  const OpenSky open(grid, options.visibility, options.max_step_rad);
  return for_each_point<PointIrradiance>(
      scene, points, options, progress,
      [&](const VisibleSky& sky_seen, const QueryPoint& q, SkyVisibility& worker, PointIrradiance& r) {
        thread_local std::vector<SkyFanTriangle> fan;
        double e[2];
        sky_channels(sky_seen, grid, options.max_step_rad, fan, e);
        r.sky_W_m2 = e[0];
        r.sky_lx = e[1];
        const double open_lx = open.of(sky_seen)[1];
        r.sky_ratio = open_lx > 0 ? e[1] / open_lx : 0.0;
        r.cos_incidence = q.normal.dot(s);
        // direction_visible is false for a sun below the horizon or behind the face.
        r.sun_visible = sun_W_m2 > 0 && r.cos_incidence > 0 && worker.direction_visible(q, s);
        if (r.sun_visible) {
          r.sun_W_m2 = sun_W_m2 * r.cos_incidence;
          r.sun_lx = sun_lx * r.cos_incidence;
        }
      });
}

std::vector<PointIrradiation> compute_point_irradiation(const Scene& scene, std::span<const QueryPoint> points,
                                                        const AtmosphereParams& atmosphere, const SkyModelSpec& spec,
                                                        std::span<const SunMoment> moments, const PointIrradianceOptions& options,
                                                        const std::function<void(std::size_t, std::size_t)>& progress,
                                                        const std::function<void(std::size_t, std::size_t)>& sky_progress) {
  check_step(options.max_step_rad);
  struct SunTerm {
    Vec3 dir;
    double hours, W_m2, lx;  // direct-normal irradiance and illuminance
  };
  std::vector<SunTerm> suns;
  ProjectedSkyGrid sky_hours;  // Σ_t hours_t·L_t in the two channels (W·h·m⁻²·sr⁻¹ and cd·h·m⁻²)
  for (std::size_t t = 0; t < moments.size(); ++t) {
    const SunMoment& m = moments[t];
    if (!(m.hours >= 0) || !std::isfinite(m.hours))
      throw InputError("irradiation: moment " + std::to_string(t + 1) + ": hours " + std::to_string(m.hours) +
                       " must be finite and >= 0");
    const SkyModel sky(atmosphere, m.sun_dir, spec);
    sky_hours.add_scaled(project_sky(sky, options.threads), m.hours);
    const Spectrum& dn = sky.sun_direct_normal();
    if (dn.integral_nm() > 0 && m.hours > 0) suns.push_back({sky.sun_direction(), m.hours, dn.integral_nm(), luminous(dn)});
    if (sky_progress) sky_progress(t + 1, moments.size());
  }

  std::optional<SkyTables> sky_hours_tables;  // none without moments (an empty grid)
  if (!moments.empty()) sky_hours_tables.emplace(sky_hours, options.threads);
  return for_each_point<PointIrradiation>(
      scene, points, options, progress,
      [&](const VisibleSky& sky_seen, const QueryPoint& q, SkyVisibility& worker, PointIrradiation& r) {
        if (!moments.empty()) {
          thread_local std::vector<SkyFanTriangle> fan;
          double e[2];
          sky_channels(sky_seen, *sky_hours_tables, options.max_step_rad, fan, e);
          r.sky_Wh_m2 = e[0];
          r.sky_lxh = e[1];
        }
        for (const SunTerm& sun : suns) {
          const double c = q.normal.dot(sun.dir);
          if (c > 0 && worker.direction_visible(q, sun.dir)) {
            r.sun_hours += sun.hours;
            r.sun_Wh_m2 += sun.hours * sun.W_m2 * c;
            r.sun_lxh += sun.hours * sun.lx * c;
          }
        }
      });
}

std::vector<PointIrradiation> compute_point_sun_hours(const Scene& scene, std::span<const QueryPoint> points,
                                                      std::span<const SunMoment> moments, const PointIrradianceOptions& options,
                                                      const std::function<void(std::size_t, std::size_t)>& progress) {
  std::vector<SunMoment> up;
  for (std::size_t t = 0; t < moments.size(); ++t) {
    const SunMoment& m = moments[t];
    if (!(m.hours >= 0) || !std::isfinite(m.hours))
      throw InputError("sun hours: moment " + std::to_string(t + 1) + ": hours " + std::to_string(m.hours) +
                       " must be finite and >= 0");
    if (m.sun_dir.z() > 0 && m.hours > 0) up.push_back({m.sun_dir.normalized(), m.hours});
  }
  return for_each_point<PointIrradiation>(
      scene, points, options, progress, [&](const VisibleSky&, const QueryPoint& q, SkyVisibility& worker, PointIrradiation& r) {
        for (const SunMoment& m : up)
          if (q.normal.dot(m.sun_dir) > 0 && worker.direction_visible(q, m.sun_dir)) r.sun_hours += m.hours;
      });
}

}  // namespace skyband
