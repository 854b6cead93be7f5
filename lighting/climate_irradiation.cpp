#include "lighting/climate_irradiation.h"

#include <cctype>

#include "geometry/sky_visibility.h"
#include "lighting/visible_sky_integral.h"

namespace skyband {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The model's non-ground triangles mirrored in z = 0: a point's lower hemisphere in the model is
// the upper hemisphere of the mirrored point in this scene.
TriangleSoup mirrored_non_ground(const TriangleSoup& soup, const std::vector<std::string>& ground, std::size_t& ground_count) {
  std::vector<bool> is_ground(soup.material_names.size(), false);
  for (std::size_t m = 0; m < soup.material_names.size(); ++m)
    for (const std::string& g : ground) is_ground[m] = is_ground[m] || lower(soup.material_names[m]) == lower(g);
  TriangleSoup out;
  out.vertices.reserve(soup.vertices.size());
  for (const Vec3& v : soup.vertices) out.vertices.push_back(Vec3(v.x(), v.y(), -v.z()));
  ground_count = 0;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    const std::uint32_t m = soup.triangle_material.empty() ? 0 : soup.triangle_material[t];
    if (m < is_ground.size() && is_ground[m]) {
      ++ground_count;
      continue;
    }
    out.triangles.push_back(soup.triangles[t]);
  }
  return out;
}

}  // namespace

std::vector<std::string> default_ground_materials() {
  return {"ground", "terrain", "road", "water", "forest", "grass", "landuse", "plantcover", "tinrelief", "relieffeature",
          "waterbody", "transportation", "trafficarea"};
}

ClimateRun compute_point_climate(const Scene& scene, std::span<const QueryPoint> points, std::span<const WeatherHour> hours,
                                 const ClimateIrradiationOptions& options,
                                 const std::function<void(std::size_t, std::size_t)>& progress) {
  ClimateRun run;
  run.points.resize(points.size());
  // The period's sky, sun and ground sources.
  const CumulativeSky cumulative = cumulative_perez_sky(hours, options.threads);
  run.sky_intervals = cumulative.sky_hours;
  struct SunTerm {
    Vec3 dir;
    double hours, Wh, lxh;  // Δt, Δt·DNI, Δt·E_v,direct
  };
  std::vector<SunTerm> suns;
  double ground_Wh = 0, ground_lxh = 0;  // Σ Δt ρ GHI, Σ Δt ρ E_v,global
  for (const WeatherHour& h : hours) {
    ground_Wh += h.hours * h.albedo * h.ghi_W_m2;
    ground_lxh += h.hours * h.albedo * h.ghi_lx;
    if (h.sun_dir.z() > 0 && h.hours > 0) suns.push_back({h.sun_dir, h.hours, h.hours * h.dni_W_m2, h.hours * h.dni_lx});
  }
  run.sun_intervals = suns.size();
  const SkyTables tables(cumulative.grid, options.threads);
  const OpenSky open(tables, options.visibility, options.max_step_rad);
  double calibration[2][2] = {{1, 1}, {1, 1}};  // [exact, bands][channel]
  const double horizontal[2] = {cumulative.horizontal_Wh_m2, cumulative.horizontal_lxh};
  for (int c = 0; c < 2; ++c) {
    if (open.exact[c] > 0) calibration[0][c] = horizontal[c] / open.exact[c];
    if (open.bands[c] > 0) calibration[1][c] = horizontal[c] / open.bands[c];
    run.sky_calibration[c] = calibration[0][c];
  }

  const std::size_t n = points.size();
  const auto both = [&](std::size_t offset) {
    return [&, offset](std::size_t done, std::size_t) {
      if (progress) progress(offset + done, 2 * n);
    };
  };
  run.counts = for_each_visible_sky(
      scene, points, options.visibility, options.method, options.threads, both(0), true,
      [&](std::size_t i, const VisibleSky& sky, SkyVisibility& worker) {
        PointClimate& r = run.points[i];
        r.svf = sky.factors.svf;
        r.sky_exposure = sky.factors.sky_exposure;
        r.method = sky.method;
        if (cumulative.sky_hours > 0) {
          thread_local std::vector<SkyFanTriangle> fan;
          double e[2];
          sky_channels(sky, tables, options.max_step_rad, fan, e);
          const double* k = calibration[sky.exact() ? 0 : 1];
          r.sky_Wh_m2 = e[0] * k[0];
          r.sky_lxh = e[1] * k[1];
        }
        const QueryPoint& q = points[i];
        for (const SunTerm& s : suns) {
          const double c = q.normal.dot(s.dir);
          if (c > 0 && worker.direction_visible(q, s.dir)) {
            r.sun_hours += s.hours;
            r.sun_Wh_m2 += s.Wh * c;
            r.sun_lxh += s.lxh * c;
          }
        }
      });

  // The ground seen below the horizon: the mirrored points in the mirrored non-ground triangles.
  const Scene mirrored(mirrored_non_ground(scene.soup(), options.ground_materials, run.ground_triangles));
  std::vector<QueryPoint> down(points.begin(), points.end());
  for (QueryPoint& q : down) {
    q.position = Vec3(q.position.x(), q.position.y(), -q.position.z());
    q.normal = Vec3(q.normal.x(), q.normal.y(), -q.normal.z());
  }
  for_each_visible_sky(mirrored, down, options.visibility, options.method, options.threads, both(n), false,
                       [&](std::size_t i, const VisibleSky& sky, SkyVisibility&) {
                         PointClimate& r = run.points[i];
                         r.ground_view = sky.factors.svf;
                         r.ground_Wh_m2 = ground_Wh * r.ground_view;
                         r.ground_lxh = ground_lxh * r.ground_view;
                       });
  if (progress) progress(2 * n, 2 * n);
  return run;
}

}  // namespace skyband
