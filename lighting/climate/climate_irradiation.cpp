#include "lighting/climate/climate_irradiation.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>

#include "geometry/core/parallel_chunks.h"
#include "geometry/visibility/sky_visibility.h"
#include "lighting/integrals/daylight_coefficients.h"
#include "lighting/integrals/visible_sky_integral.h"
#include "lighting/sky/perez_sky.h"

namespace skyband {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

std::vector<bool> ground_triangle_mask(const TriangleSoup& soup, const std::vector<std::string>& ground_materials) {
  std::vector<bool> is_ground_material(soup.material_names.size(), false);
  for (std::size_t m = 0; m < soup.material_names.size(); ++m)
    for (const std::string& g : ground_materials)
      is_ground_material[m] = is_ground_material[m] || lower(soup.material_names[m]) == lower(g);
  std::vector<bool> mask(soup.triangles.size(), false);
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    const std::uint32_t m = t < soup.triangle_material.size() ? soup.triangle_material[t] : 0;
    mask[t] = m < is_ground_material.size() && is_ground_material[m];
  }
  return mask;
}

namespace {

// The model's non-ground triangles mirrored in z = 0: a point's lower hemisphere in the model is
// the upper hemisphere of the mirrored point in this scene.
TriangleSoup mirrored_non_ground(const TriangleSoup& soup, const std::vector<std::string>& ground, std::size_t& ground_count) {
  const std::vector<bool> is_ground = ground_triangle_mask(soup, ground);
  TriangleSoup out;
  out.vertices.reserve(soup.vertices.size());
  for (const Vec3& v : soup.vertices) out.vertices.push_back(Vec3(v.x(), v.y(), -v.z()));
  ground_count = 0;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    if (is_ground[t]) {
      ++ground_count;
      continue;
    }
    out.triangles.push_back(soup.triangles[t]);
  }
  return out;
}

}  // namespace

std::vector<std::string> default_ground_materials() {
  return {"ground",    "terrain",       "road",      "water",          "forest",      "grass",           "landuse", "plantcover",
          "tinrelief", "relieffeature", "waterbody", "transportation", "trafficarea", "transportsquare", "railway"};
}

namespace {

// Each hour's sky at the daylight-coefficient nodes, normalised so that the open horizontal
// face's coefficients give exactly the hour's DHI: [hour][node], W·m⁻²·sr⁻¹ (0 without sky).
std::vector<float> hourly_node_skies(std::span<const WeatherHour> hours, const VisibilityOptions& visibility, int threads) {
  const std::vector<DaylightNode>& nodes = daylight_nodes();
  std::vector<float> open(nodes.size());
  {
    const Scene empty{TriangleSoup{}};
    SkyVisibility up(empty, visibility, SkyFactorsMethod::exact);
    daylight_coefficients(up.compute(QueryPoint{Vec3(0, 0, 0), Vec3(0, 0, 1)}), visibility, open);
  }
  std::vector<float> out(hours.size() * nodes.size(), 0.0f);
  // Each hour alone (its own row of `out`): the result does not depend on the thread count.
  for_each_in_chunks(
      hours.size(), 64, threads, {}, [&] { return std::make_unique<std::vector<double>>(nodes.size()); },
      [&](std::vector<double>& l, std::size_t h) {
        const WeatherHour& w = hours[h];
        if (!(w.dhi_W_m2 > 0)) return;
        const double zenith = std::acos(std::clamp(w.sun_dir.z(), -1.0, 1.0));
        const PerezSky sky =
            make_perez_sky(perez_sky_condition(w.dhi_W_m2, w.dni_W_m2, zenith, w.day_of_year), w.sun_dir, w.dhi_W_m2);
        double e = 0;
        for (std::size_t j = 0; j < nodes.size(); ++j) {
          l[j] = std::max(0.0, nodes[j].a * sky.radiance(nodes[j].da) + nodes[j].b * sky.radiance(nodes[j].db));
          e += open[j] * l[j];
        }
        const double k = e > 0 ? w.dhi_W_m2 / e : 0.0;
        for (std::size_t j = 0; j < nodes.size(); ++j) out[h * nodes.size() + j] = static_cast<float>(k * l[j]);
      });
  return out;
}

}  // namespace

ClimateRun compute_point_climate(const Scene& scene, std::span<const QueryPoint> points, std::span<const WeatherHour> hours,
                                 const ClimateIrradiationOptions& options,
                                 const std::function<void(std::size_t, std::size_t)>& progress, const ClimateHourlySink& hourly) {
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
  // The ground seen below the horizon: the mirrored points in the mirrored non-ground triangles.
  const Scene mirrored(mirrored_non_ground(scene.soup(), options.ground_materials, run.ground_triangles));
  std::vector<QueryPoint> down(points.begin(), points.end());
  for (QueryPoint& q : down) {
    q.position = Vec3(q.position.x(), q.position.y(), -q.position.z());
    q.normal = Vec3(q.normal.x(), q.normal.y(), -q.normal.z());
  }
  for_each_visible_sky(mirrored, down, options.visibility, options.method, options.threads, both(0), false,
                       [&](std::size_t i, const VisibleSky& sky, SkyVisibility&) {
                         PointClimate& r = run.points[i];
                         r.ground_view = sky.factors.svf;
                         r.ground_Wh_m2 = ground_Wh * r.ground_view;
                         r.ground_lxh = ground_lxh * r.ground_view;
                       });
  // Hourly: the hours' skies at the daylight-coefficient nodes, once.
  const std::vector<float> node_skies =
      hourly ? hourly_node_skies(hours, options.visibility, options.threads) : std::vector<float>{};
  run.counts = for_each_visible_sky(
      scene, points, options.visibility, options.method, options.threads, both(n), true,
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
        if (hourly) {
          thread_local std::vector<float> dc, sky_h, sun_h, ground_h, lx_h;
          dc.resize(kDaylightCoefficientNodes);
          daylight_coefficients(sky, options.visibility, dc);
          sky_h.assign(hours.size(), 0.0f);
          sun_h.assign(hours.size(), 0.0f);
          ground_h.assign(hours.size(), 0.0f);
          lx_h.assign(hours.size(), 0.0f);
          for (std::size_t h = 0; h < hours.size(); ++h) {
            const WeatherHour& w = hours[h];
            double lx = w.albedo * w.ghi_lx * r.ground_view;
            if (w.dhi_W_m2 > 0) {
              const float* l = &node_skies[h * dc.size()];
              double e = 0;
              for (std::size_t j = 0; j < dc.size(); ++j) e += double(dc[j]) * double(l[j]);
              sky_h[h] = static_cast<float>(e);
              lx += e * (w.dhi_lx / w.dhi_W_m2);
            }
            const double c = q.normal.dot(w.sun_dir);
            if (w.sun_dir.z() > 0 && c > 0 && (w.dni_W_m2 > 0 || w.dni_lx > 0) && worker.direction_visible(q, w.sun_dir)) {
              sun_h[h] = static_cast<float>(w.dni_W_m2 * c);
              lx += w.dni_lx * c;
            }
            ground_h[h] = static_cast<float>(w.albedo * w.ghi_W_m2 * r.ground_view);
            lx_h[h] = static_cast<float>(lx);
          }
          hourly(i, sky_h, sun_h, ground_h, lx_h);
        }
      });

  if (progress) progress(2 * n, 2 * n);
  return run;
}

}  // namespace skyband
