// Irradiance at calculation points: sky through the visibility cache, sun with the exact shadow
// test (point_irradiance.h has the formulas).
#include "lighting/point_irradiance.h"

#include <array>
#include <cmath>
#include <memory>
#include <optional>

#include "geometry/horizon_svf.h"
#include "geometry/input_error.h"
#include "geometry/parallel_chunks.h"
#include "geometry/point_order.h"
#include "geometry/sky_fan.h"
#include "geometry/sky_integral.h"
#include "lighting/colour.h"
#include "lighting/sky_column_table.h"
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

// A sky ready for both methods: the projected grid (for the band method's lines) and its column
// tables (for the exact horizon: sky_column_table.h).
struct SkyTables {
  const ProjectedSkyGrid& grid;
  SkyColumnTable columns;
  SkyTables(const ProjectedSkyGrid& g, int threads) : grid(g), columns(g, threads) {}
};

// The visible sky of one point, by whichever method computed it: the band method's cache view
// (exact α-intervals) or the exact horizon's fan of spherical triangles.
struct VisibleSky {
  const PointVisibilityView* bands = nullptr;  // set: the band method
  std::span<const SkyFanTriangle> fan;          // otherwise: the exact horizon
  Vec3 normal{0, 0, 1};
  bool by_horizon() const { return bands == nullptr; }
  // Both channels of the sky integrated over the visible sky: along the band lines (Gauss–Legendre
  // pieces ≤ max_step_rad), or in azimuth over the fan with the column tables (pieces ≤ a quarter
  // of it: the one-dimensional quadrature is cheap, and the arcs' elevation e₀(φ) can be steep).
  void channels(const SkyTables& sky, double max_step_rad, double out[2]) const {
    if (bands)
      integrate_irradiance_channels<2>(*bands, [&](const Vec3& d, double* c) { sky.grid.lookup_unit_n<2>(d, c); }, out,
                                       max_step_rad);
    else
      sky.columns.integrate_fan(fan, normal, out, 0.25 * max_step_rad);
  }
};

// Every point's visible sky: fills svf and sky_exposure of out[i] and hands (its VisibleSky, the
// point, a BandVisibility for the exact sun-shadow tests, out[i]) to `fill` for the rest. With the
// automatic method the exact horizon goes first (geometry/sky_factors.h); the points it declines,
// and all points with the band method, go through the visibility cache chunk by chunk.
template <class Result, class Fill>
std::vector<Result> for_each_point(const Scene& scene, std::span<const QueryPoint> points, const PointIrradianceOptions& options,
                                   const std::function<void(std::size_t, std::size_t)>& progress, Fill&& fill) {
  std::vector<Result> out(points.size());
  std::vector<char> done(points.size(), 0);
  if (options.method == SkyFactorsMethod::automatic && !points.empty()) {
    const ColumnScene& columns = scene.column_scene();
    struct Worker {
      HorizonSvf horizon;
      BandVisibility bands;
      std::vector<SkyFanTriangle> fan;
      Worker(const Scene& s, const ColumnScene& c, const VisibilityOptions& o) : horizon(s, c, o.surface_offset_m), bands(s, o) {}
    };
    const std::vector<std::uint32_t> order = xy_morton_order(points);  // cache locality; no result changes
    for_each_in_chunks(
        points.size(), 32, options.threads, progress,
        [&] { return std::make_unique<Worker>(scene, columns, options.visibility); },
        [&](Worker& w, std::size_t k) {
          const std::size_t i = order[k];
          SkyFactors f;
          if (!w.horizon.compute(points[i], f)) return;
          w.horizon.visible_fan(w.fan);
          Result& r = out[i];
          r.svf = f.svf;
          r.sky_exposure = f.sky_exposure;
          r.exact_horizon = true;
          fill(VisibleSky{nullptr, w.fan, points[i].normal}, points[i], w.bands, r);
          done[i] = 1;
        });
  }
  const PointSubset rest = points_not_done(points, done);
  const auto rest_progress = [&](std::size_t d, std::size_t) {
    if (progress) progress(points.size() - rest.points.size() + d, points.size());
  };
  for_each_visibility_chunk(scene, rest.points, options.visibility, options.threads, progress ? rest_progress : std::function<void(std::size_t, std::size_t)>{},
                            [&](std::size_t first, VisibilityCache& chunk, BandVisibility& worker) {
                              for (std::size_t i = 0; i < chunk.size(); ++i) {
                                const PointVisibilityView v = chunk.view(i);
                                const std::size_t k = rest.index[first + i];
                                Result& r = out[k];
                                r.svf = sky_view_factor(v);
                                r.sky_exposure = sky_exposure(v);
                                fill(VisibleSky{&v, {}, points[k].normal}, points[k], worker, r);
                              }
                            });
  return out;
}

}  // namespace

std::vector<PointIrradiance> compute_point_irradiance(const Scene& scene, std::span<const QueryPoint> points,
                                                      const SkyModel& sky, const PointIrradianceOptions& options,
                                                      const std::function<void(std::size_t, std::size_t)>& progress) {
  check_step(options.max_step_rad);
  const ProjectedSkyGrid projected = project_sky(sky, options.threads);
  const SkyTables grid(projected, options.threads);
  const Spectrum& dn = sky.sun_direct_normal();
  const double sun_W_m2 = dn.integral_nm(), sun_lx = luminous(dn);
  const Vec3 s = sky.sun_direction();

  // The denominator of sky_ratio: an unobstructed horizontal point, same method and quadrature
  // (so an open horizontal point gives exactly 1 by either method).
  double open_bands[2], open_fan[2];
  {
    const Scene empty{TriangleSoup{}};
    const QueryPoint up{Vec3(0, 0, 0), Vec3(0, 0, 1)};
    const VisibilityCache open = compute_visibility(empty, std::span<const QueryPoint>(&up, 1), options.visibility, 1);
    const PointVisibilityView open_view = open.view(0);
    VisibleSky{&open_view, {}, up.normal}.channels(grid, options.max_step_rad, open_bands);
    HorizonSvf horizon(empty, empty.column_scene(), options.visibility.surface_offset_m);
    SkyFactors f;
    std::vector<SkyFanTriangle> fan;
    horizon.compute(up, f);
    horizon.visible_fan(fan);
    VisibleSky{nullptr, fan, up.normal}.channels(grid, options.max_step_rad, open_fan);
  }

  return for_each_point<PointIrradiance>(
      scene, points, options, progress,
      [&](const VisibleSky& sky_seen, const QueryPoint& q, BandVisibility& worker, PointIrradiance& r) {
        double e[2];
        sky_seen.channels(grid, options.max_step_rad, e);
        r.sky_W_m2 = e[0];
        r.sky_lx = e[1];
        const double open_lx = sky_seen.by_horizon() ? open_fan[1] : open_bands[1];
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

  std::optional<SkyTables> sky_hours_tables;  // none without moments (an empty grid)
  if (!moments.empty()) sky_hours_tables.emplace(sky_hours, options.threads);
  return for_each_point<PointIrradiation>(
      scene, points, options, progress,
      [&](const VisibleSky& sky_seen, const QueryPoint& q, BandVisibility& worker, PointIrradiation& r) {
        if (!moments.empty()) {
          double e[2];
          sky_seen.channels(*sky_hours_tables, options.max_step_rad, e);
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
