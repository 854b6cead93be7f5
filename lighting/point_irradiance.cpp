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

}  // namespace

std::vector<PointIrradiance> compute_point_irradiance(const Scene& scene, std::span<const QueryPoint> points,
                                                      const SkyModel& sky, const PointIrradianceOptions& options,
                                                      const std::function<void(std::size_t, std::size_t)>& progress) {
  if (!(options.max_step_rad > 0) || !std::isfinite(options.max_step_rad))
    throw InputError("irradiance: quadrature step " + std::to_string(options.max_step_rad) + " rad must be finite and > 0");
  const std::array<Spectrum, 2> weights = channel_weights();
  const ProjectedSkyGrid grid =
      SkyRadianceGrid([&](const Vec3& d, Spectrum& out) { sky.radiance_into(d, out); }, options.threads)
          .project(weights);
  const Spectrum& dn = sky.sun_direct_normal();
  const double sun_W_m2 = dn.integral_nm(), sun_lx = luminous(dn);
  const Vec3 s = sky.sun_direction();

  // The denominator of sky_ratio: an unobstructed horizontal point, same bands and quadrature.
  double open_sky[2];
  {
    const Scene empty{TriangleSoup{}};
    const QueryPoint up{Vec3(0, 0, 0), Vec3(0, 0, 1)};
    const VisibilityCache open = compute_visibility(empty, std::span<const QueryPoint>(&up, 1), options.visibility, 1);
    integrate_irradiance_channels<2>(open.view(0), [&](const Vec3& d, double* c) { grid.lookup_unit_n<2>(d, c); },
                                     open_sky, options.max_step_rad);
  }

  std::vector<PointIrradiance> out(points.size());
  for_each_visibility_chunk(
      scene, points, options.visibility, options.threads, progress,
      [&](std::size_t first, VisibilityCache& chunk, BandVisibility& worker) {
        for (std::size_t i = 0; i < chunk.size(); ++i) {
          const PointVisibilityView v = chunk.view(i);
          PointIrradiance& r = out[first + i];
          r.svf = sky_view_factor(v);
          r.sky_exposure = sky_exposure(v);
          double e[2];
          integrate_irradiance_channels<2>(v, [&](const Vec3& d, double* c) { grid.lookup_unit_n<2>(d, c); }, e,
                                           options.max_step_rad);
          r.sky_W_m2 = e[0];
          r.sky_lx = e[1];
          r.sky_ratio = open_sky[1] > 0 ? e[1] / open_sky[1] : 0.0;
          const QueryPoint& q = points[first + i];
          r.cos_incidence = q.normal.dot(s);
          // direction_visible is false for a sun below the horizon or behind the face.
          r.sun_visible = sun_W_m2 > 0 && r.cos_incidence > 0 && worker.direction_visible(q, s);
          if (r.sun_visible) {
            r.sun_W_m2 = sun_W_m2 * r.cos_incidence;
            r.sun_lx = sun_lx * r.cos_incidence;
          }
        }
      });
  return out;
}

}  // namespace skyband
