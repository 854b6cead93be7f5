// Irradiance at calculation points: sky through the visibility cache, sun with the exact shadow
// test (point_irradiance.h has the formulas).
#include "lighting/point_irradiance.h"

#include <array>
#include <cmath>

#include "geometry/input_error.h"
#include "geometry/sky_integral.h"
#include "lighting/colour.h"
#include "lighting/sky_radiance_grid.h"

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

// Both channels of the sky term of one cached point through a projected grid.
void sky_channels(const PointVisibilityView& v, const ProjectedSkyGrid& grid, double max_step_rad, double out[2]) {
  integrate_irradiance_channels<2>(v, [&](const Vec3& d, double* c) { grid.lookup_unit_n<2>(d, c); }, out, max_step_rad);
}

// The visibility of every point, chunk by chunk: fills svf and sky_exposure of out[i] and hands
// (view, point, the worker's BandVisibility, out[i]) to `fill` for the rest.
template <class Result, class Fill>
std::vector<Result> for_each_point(const Scene& scene, std::span<const QueryPoint> points, const PointIrradianceOptions& options,
                                   const std::function<void(std::size_t, std::size_t)>& progress, Fill&& fill) {
  std::vector<Result> out(points.size());
  for_each_visibility_chunk(scene, points, options.visibility, options.threads, progress,
                            [&](std::size_t first, VisibilityCache& chunk, BandVisibility& worker) {
                              for (std::size_t i = 0; i < chunk.size(); ++i) {
                                const PointVisibilityView v = chunk.view(i);
                                Result& r = out[first + i];
                                r.svf = sky_view_factor(v);
                                r.sky_exposure = sky_exposure(v);
                                fill(v, points[first + i], worker, r);
                              }
                            });
  return out;
}

}  // namespace

std::vector<PointIrradiance> compute_point_irradiance(const Scene& scene, std::span<const QueryPoint> points,
                                                      const SkyModel& sky, const PointIrradianceOptions& options,
                                                      const std::function<void(std::size_t, std::size_t)>& progress) {
  check_step(options.max_step_rad);
  const ProjectedSkyGrid grid = project_sky(sky, options.threads);
  const Spectrum& dn = sky.sun_direct_normal();
  const double sun_W_m2 = dn.integral_nm(), sun_lx = luminous(dn);
  const Vec3 s = sky.sun_direction();

  // The denominator of sky_ratio: an unobstructed horizontal point, same bands and quadrature.
  double open_sky[2];
  {
    const Scene empty{TriangleSoup{}};
    const QueryPoint up{Vec3(0, 0, 0), Vec3(0, 0, 1)};
    const VisibilityCache open = compute_visibility(empty, std::span<const QueryPoint>(&up, 1), options.visibility, 1);
    sky_channels(open.view(0), grid, options.max_step_rad, open_sky);
  }

  return for_each_point<PointIrradiance>(
      scene, points, options, progress,
      [&](const PointVisibilityView& v, const QueryPoint& q, BandVisibility& worker, PointIrradiance& r) {
        double e[2];
        sky_channels(v, grid, options.max_step_rad, e);
        r.sky_W_m2 = e[0];
        r.sky_lx = e[1];
        r.sky_ratio = open_sky[1] > 0 ? e[1] / open_sky[1] : 0.0;
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
                                                        std::span<const SunMoment> moments,
                                                        const PointIrradianceOptions& options,
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

  return for_each_point<PointIrradiation>(
      scene, points, options, progress,
      [&](const PointVisibilityView& v, const QueryPoint& q, BandVisibility& worker, PointIrradiation& r) {
        if (!moments.empty()) {
          double e[2];
          sky_channels(v, sky_hours, options.max_step_rad, e);
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

}  // namespace skyband
