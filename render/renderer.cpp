#include "render/renderer.h"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "geometry/core/thread_arena.h"
#include "geometry/visibility/sky_visibility.h"
#include "lighting/integrals/sky_lut.h"
#include "lighting/sky/sky_radiance_grid.h"
#include "lighting/spectrum/colour.h"
#include "lighting/sun/sun_shading.h"
#include "render/specular_reuse.h"
#include "render/specular_sky_colour.h"

namespace skyband {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// For each key, the index of its value among the distinct values (appended to `distinct` in
// first-seen order).
template <class T>
std::vector<std::size_t> distinct_index(std::span<const T> keys, std::vector<T>& distinct) {
  std::vector<std::size_t> index;
  for (const T& k : keys) {
    std::size_t i = 0;
    while (i < distinct.size() && distinct[i] != k) ++i;
    if (i == distinct.size()) distinct.push_back(k);
    index.push_back(i);
  }
  return index;
}

// The four shading terms of one surface sample as linear sRGB (unit: see renderer.h).
struct ShadedRgb {
  Vec3 sun_diffuse, sun_specular, sky_diffuse, sky_specular;
};

}  // namespace

GeometryPass trace_geometry(const Scene& scene, const PinholeCamera& camera, const RenderSettings& settings,
                            const std::function<void(std::size_t, std::size_t)>& progress) {
  const std::vector<Vec2> offsets = pixel_sample_offsets(settings.samples_per_pixel);
  GeometryPass pass;
  pass.width = camera.width();
  pass.height = camera.height();
  pass.samples = settings.samples_per_pixel;
  pass.material_slots = scene.soup().material_names;
  if (pass.material_slots.empty()) pass.material_slots.push_back("default");
  const std::size_t n_pixels = static_cast<std::size_t>(pass.width) * static_cast<std::size_t>(pass.height);
  const std::size_t n_samples = n_pixels * offsets.size();
  const std::size_t spp = offsets.size();

  // Trace: per sample, a hit record (or none). Written by index → deterministic.
  struct Hit {
    bool hit = false;
    SurfaceSample s;
  };
  std::vector<Hit> hits(n_samples);
  pass.sample_direction.resize(n_samples);
  const TriangleSoup& soup = scene.soup();
  const auto t0 = Clock::now();
  run_with_threads(settings.threads, [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_pixels, 64), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t p = r.begin(); p != r.end(); ++p) {
        const int row = static_cast<int>(p / static_cast<std::size_t>(pass.width));
        const int col = static_cast<int>(p % static_cast<std::size_t>(pass.width));
        for (std::size_t i = 0; i < spp; ++i) {
          const Ray ray = camera.primary_ray(col + offsets[i].x(), row + offsets[i].y());
          pass.sample_direction[p * spp + i] = ray.direction;
          const std::optional<SurfaceHit> h = scene.surface_hit(ray);  // normal faces the camera
          if (!h) continue;
          Hit& out = hits[p * spp + i];
          out.hit = true;
          out.s.position = h->position;
          out.s.normal = h->normal;
          out.s.view_dir = -ray.direction;
          out.s.material_slot = soup.triangle_material.empty() ? 0u : soup.triangle_material[h->triangle];
          out.s.pixel = static_cast<std::uint32_t>(p);
        }
      }
    });
  });
  pass.trace_seconds = seconds_since(t0);

  pass.sample_surface.assign(n_samples, GeometryPass::kBackground);
  std::vector<QueryPoint> points;
  for (std::size_t k = 0; k < n_samples; ++k) {
    if (!hits[k].hit) continue;
    pass.sample_surface[k] = static_cast<std::uint32_t>(pass.surfaces.size());
    pass.surfaces.push_back(hits[k].s);
    points.push_back(QueryPoint{hits[k].s.position, hits[k].s.normal});
  }
  hits.clear();
  hits.shrink_to_fit();
  const auto t1 = Clock::now();
  pass.visibility = compute_visibility_cache(scene, points, settings.visibility, settings.method, settings.threads, progress);
  pass.visibility_seconds = seconds_since(t1);
  return pass;
}

void update_sun(GeometryPass& pass, const Scene& scene, const Vec3& sun_dir, const RenderSettings& settings) {
  const auto t0 = Clock::now();
  const Vec3 s = sun_dir.normalized();
  pass.sun_direction = sun_dir;
  pass.sun_set = true;
  pass.sun_visible.assign(pass.surfaces.size(), 0);
  if (s.z() < 0) {  // sun below the horizon: no direct light anywhere
    pass.sun_seconds = seconds_since(t0);
    return;
  }
  tbb::enumerable_thread_specific<std::unique_ptr<BandVisibility>> workers;
  run_with_threads(settings.threads, [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pass.surfaces.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        auto& w = workers.local();
                        if (!w) w = std::make_unique<BandVisibility>(scene, settings.visibility);
                        for (std::size_t k = r.begin(); k != r.end(); ++k) {
                          const SurfaceSample& ss = pass.surfaces[k];
                          // Faces turned away from the sun are in their own shadow (N·S ≤ 0).
                          if (!(ss.normal.dot(s) > 0)) continue;
                          pass.sun_visible[k] = w->direction_visible(QueryPoint{ss.position, ss.normal}, s) ? 1 : 0;
                        }
                      });
  });
  pass.sun_seconds = seconds_since(t0);
}

SkyLight sky_light_of(const SkyModel& sky) {
  SkyLight l;
  l.radiance = [&sky](const Vec3& d, Spectrum& out) { sky.radiance_into(d, out); };
  l.sun_direction = sky.sun_direction();
  l.sun_direct_normal = sky.sun_direct_normal();
  return l;
}

RenderLayers shade(const GeometryPass& pass, const SkyModel& sky, std::span<const Material* const> slot_materials,
                   const RenderSettings& settings) {
  return shade(pass, sky_light_of(sky), slot_materials, settings);
}

RenderLayers shade(const GeometryPass& pass, const SkyLight& sky, std::span<const Material* const> slot_materials,
                   const RenderSettings& settings) {
  if (!pass.sun_set || (pass.sun_direction - sky.sun_direction).norm() > 1e-12)
    throw std::logic_error("shade: the geometry pass's sun visibility is not for this sky's sun (call update_sun)");
  if (slot_materials.size() != pass.material_slots.size())
    throw std::logic_error("shade: " + std::to_string(slot_materials.size()) + " materials for " +
                           std::to_string(pass.material_slots.size()) + " slots");
  for (const Material* m : slot_materials)
    if (!m) throw std::logic_error("shade: null material");

  const Vec3 sun_dir = sky.sun_direction.normalized();
  const Spectrum& e_dn = sky.sun_direct_normal;
  const SkyRadianceGrid grid(sky.radiance, settings.threads);
  // Diffuse sky: per-band tables (seed eq. 1) built from the gridded sky, each also projected
  // onto XYZ × the diffuse BRDF (1 − s)ρ_d/π of every distinct material, so a sample's diffuse
  // sky radiance integrates straight to XYZ (3 channels instead of 41).
  std::vector<const Material*> materials;
  const std::vector<std::size_t> slot_diffuse = distinct_index(slot_materials, materials);
  std::vector<std::vector<Spectrum>> diffuse_projections;
  for (const Material* m : materials) {
    const Spectrum brdf = m->diffuse_brdf();
    diffuse_projections.push_back({xyz_weights(0) * brdf, xyz_weights(1) * brdf, xyz_weights(2) * brdf});
  }
  SkyLutCache luts([&grid](const Vec3& d, Spectrum& out) { grid(d, out); }, 360, 1e-9, diffuse_projections, false);
  // Specular sky in XYZ (specular_sky_colour.h): one projected sky per distinct Fresnel table of
  // a specular material (slots without a specular term map to an entry left empty).
  std::vector<const FresnelTable*> slot_tables;
  for (const Material* m : slot_materials)
    slot_tables.push_back(m->has_specular() ? m->specular_lobe(settings.paper_scale).fresnel : nullptr);
  std::vector<const FresnelTable*> tables;
  const std::vector<std::size_t> slot_specular = distinct_index(std::span<const FresnelTable* const>(slot_tables), tables);
  std::vector<std::unique_ptr<ColourSpecularSky>> specular_skies;
  specular_skies.resize(tables.size());
  for (std::size_t k = 0; k < slot_materials.size(); ++k)
    if (slot_materials[k]->has_specular() && !specular_skies[slot_specular[k]])
      specular_skies[slot_specular[k]] = std::make_unique<ColourSpecularSky>(grid, slot_tables[k]);
  const Spectrum xyz_weight_spectra[3] = {xyz_weights(0), xyz_weights(1), xyz_weights(2)};
  const ProjectedSkyGrid background = grid.project(xyz_weight_spectra);

  std::vector<ShadedRgb> shaded(pass.surfaces.size());
  run_with_threads(settings.threads, [&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, pass.surfaces.size(), 64), [&](const tbb::blocked_range<std::size_t>& r) {
          // Consecutive samples mostly lie on one plane and share its diffuse table:
          // the last one is kept while the cache would serve the same table.
          std::shared_ptr<const SkyLut> memo_lut;
          std::size_t memo_k = 0, memo_material = 0;
          for (std::size_t k = r.begin(); k != r.end(); ++k) {
            const SurfaceSample& ss = pass.surfaces[k];
            const Material& m = *slot_materials[ss.material_slot];
            const bool sun_vis = pass.sun_visible[k] != 0;
            const PointVisibilityView view = pass.visibility.view(k);
            ShadedRgb& out = shaded[k];
            out.sun_diffuse = spectrum_to_linear_srgb(sun_diffuse_radiance(m, ss.normal, sun_dir, e_dn, sun_vis));
            out.sun_specular = spectrum_to_linear_srgb(
                sun_specular_radiance(m, ss.normal, sun_dir, ss.view_dir, e_dn, sun_vis, settings.paper_scale));
            if (m.specular_weight < 1.0) {
              double xyz[3];
              const std::size_t material = slot_diffuse[ss.material_slot];
              if (!memo_lut || material != memo_material || !SkyLutCache::same_table(view, pass.visibility.view(memo_k))) {
                memo_lut = luts.projected_for(view, material);
                memo_material = material;
              }
              memo_k = k;
              diffuse_sky_channels(view, *memo_lut, xyz);
              out.sky_diffuse = xyz_to_linear_srgb(Xyz{xyz[0], xyz[1], xyz[2]});
            } else {
              out.sky_diffuse = Vec3::Zero();
            }
            out.sky_specular = Vec3::Zero();
          }
        });
  });
  // Specular sky: the ε-march, exactly at block corners and wherever the image is not flat.
  std::vector<Xyz> specular_xyz(pass.surfaces.size());
  const auto material_of = [&](std::size_t k) -> const Material& { return *slot_materials[pass.surfaces[k].material_slot]; };
  // Reuse classes (specular_reuse.h): 0 for rough materials; near-mirrors (rougher than a
  // perfect mirror, smoother than specular_reuse_min_roughness) 1 or 2 where their lobe window is
  // wholly open or wholly closed sky (lobe_window_sky), −1 where a visibility edge is near their
  // reflection; perfect mirrors −1 (a single look-up each anyway).
  std::vector<std::int8_t> reuse_class(pass.surfaces.size(), -1);
  if (settings.specular_reuse_block >= 4 && settings.specular_reuse_tolerance > 0.0) {
    run_with_threads(settings.threads, [&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pass.surfaces.size(), 256),
                        [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t k = r.begin(); k != r.end(); ++k) {
                            const Material& m = material_of(k);
                            if (!m.has_specular()) continue;
                            if (m.roughness_m >= settings.specular_reuse_min_roughness) {
                              reuse_class[k] = 0;
                            } else if (m.roughness_m >= settings.specular.mirror_below_m) {
                              const LobeWindowSky w = lobe_window_sky(pass.visibility.view(k), pass.surfaces[k].view_dir,
                                                                      m.specular_lobe(settings.paper_scale), settings.specular);
                              reuse_class[k] = w == LobeWindowSky::kOpen ? 1 : w == LobeWindowSky::kClosed ? 2 : -1;
                            }
                          }
                        });
    });
  }
  std::atomic<std::size_t> specular_evaluations{0};  // a sum over marched samples: order-independent
  const SpecularReuseStats reuse = shade_specular_with_reuse(
      pass, settings.specular_reuse_block, settings.specular_reuse_tolerance,
      [&](std::size_t k) { return material_of(k).has_specular(); },
      [&](std::size_t k) { return static_cast<int>(reuse_class[k]); },
      [&](std::size_t k) {
        const SurfaceSample& ss = pass.surfaces[k];
        SpecularSkyStats stats;
        const Xyz x = specular_skies[slot_specular[ss.material_slot]]->radiance_xyz(
            pass.visibility.view(k), ss.view_dir, material_of(k).specular_lobe(settings.paper_scale), settings.specular, &stats);
        specular_evaluations.fetch_add(stats.radiance_evals, std::memory_order_relaxed);
        return x;
      },
      settings.threads, specular_xyz);
  for (std::size_t k = 0; k < pass.surfaces.size(); ++k)
    if (material_of(k).has_specular()) shaded[k].sky_specular = xyz_to_linear_srgb(specular_xyz[k]);

  RenderLayers L;
  L.width = pass.width;
  L.height = pass.height;
  L.specular_exact = reuse.exact;
  L.specular_interpolated = reuse.interpolated;
  L.specular_evaluations = specular_evaluations.load();
  const std::size_t n_pixels = static_cast<std::size_t>(pass.width) * static_cast<std::size_t>(pass.height);
  for (auto* layer : {&L.sun_diffuse, &L.sun_specular, &L.sky_diffuse, &L.sky_specular, &L.total})
    layer->assign(n_pixels * 3, 0.0f);
  const std::size_t spp = static_cast<std::size_t>(pass.samples);
  const double inv = 1.0 / static_cast<double>(spp);
  run_with_threads(settings.threads, [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_pixels, 256), [&](const tbb::blocked_range<std::size_t>& r) {
      double xyz[ProjectedSkyGrid::kMaxChannels];
      for (std::size_t p = r.begin(); p != r.end(); ++p) {
        Vec3 acc[5] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
        for (std::size_t i = 0; i < spp; ++i) {
          const std::uint32_t k = pass.sample_surface[p * spp + i];
          if (k == GeometryPass::kBackground) {
            background.lookup(pass.sample_direction[p * spp + i], xyz);
            acc[4] += xyz_to_linear_srgb(Xyz{xyz[0], xyz[1], xyz[2]});
            continue;
          }
          const ShadedRgb& s = shaded[k];
          acc[0] += s.sun_diffuse;
          acc[1] += s.sun_specular;
          acc[2] += s.sky_diffuse;
          acc[3] += s.sky_specular;
          acc[4] += s.sun_diffuse + s.sun_specular + s.sky_diffuse + s.sky_specular;
        }
        std::vector<float>* layers[5] = {&L.sun_diffuse, &L.sun_specular, &L.sky_diffuse, &L.sky_specular, &L.total};
        for (int j = 0; j < 5; ++j) {
          for (int c = 0; c < 3; ++c) {
            const double v = acc[j][c] * inv;
            if (!std::isfinite(v))
              throw std::logic_error("renderer: non-finite value in pixel (column " +
                                     std::to_string(p % static_cast<std::size_t>(pass.width)) + ", row " +
                                     std::to_string(p / static_cast<std::size_t>(pass.width)) + ")");
            (*layers[j])[p * 3 + static_cast<std::size_t>(c)] = static_cast<float>(v);
          }
        }
      }
    });
  });
  return L;
}

std::vector<const Material*> materials_for_slots(std::span<const std::string> slots, const std::string& default_material,
                                                 const std::string& context) {
  std::vector<const Material*> out;
  for (const std::string& s : slots) {
    bool builtin = false;
    for (const Material& m : builtin_materials())
      if (m.name == s) builtin = true;
    out.push_back(builtin ? &find_material(s, context) : &find_material(default_material, context));
  }
  return out;
}

}  // namespace skyband
