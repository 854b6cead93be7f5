#pragma once
// The renderer: spectral sun + sky shading of a triangle scene seen through a pinhole camera
// (method.md §1), in two phases so that relighting is cheap.
//
// Phase 1, geometry (trace_geometry): for every pixel sample the primary ray's closest hit
// (Scene::intersect, watertight) gives the hit point (re-evaluated on the triangle from its
// barycentrics), the geometric normal flipped to face the camera (meshes have inconsistent
// orientation), the unit view direction and the triangle's material slot; then the visible sky of
// every hit point on band sample lines (compute_visibility_cache, geometry/visibility/sky_visibility.h: by
// default the exact visible sky cut along the lines; one VisibilityCache entry per surface
// sample). None of this depends on the sky, the sun or the materials.
// Phase 1b, sun (update_sun): the exact shadow bit of every surface sample for one sun direction
// (BandVisibility::direction_visible: one sample plane per point); redo it when the sun moves.
// Phase 2, lighting (shade): for any sky model and any assignment of materials to slots,
//     sun_diffuse  = (1 − s)ρ_d/π · E_dn · max(0, N·S) · vis_sun                (sun_shading.h)
//     sun_specular = s f_s(S, V) · E_dn · (N·S) · vis_sun                       (sun_shading.h)
//     sky_diffuse  = (1 − s)ρ_d/π · Σ_bands w Σ_visible [E_l(α1) − E_l(α0)]     (seed eq. 1, sky_lut.h)
//     sky_specular = ∫_visible sky s f_s(ω, V) L(ω) (N·ω) dω, ε-truncated march (seed eqs. 7–10,
//                    specular_sky.h), evaluated directly in XYZ (specular_sky_colour.h) on the
//                    sky resampled on a grid (sky_radiance_grid.h)
// Every term is a spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹ on the 41-sample grid) converted to linear
// sRGB through CIE 1931 XYZ (colour.h): X, Y, Z = ∫ I(λ) x̄, ȳ, z̄(λ) dλ, so the OUTPUT UNIT IS
// W·m⁻²·sr⁻¹ weighted by the colour-matching functions (Y is luminance / 683 lm·W⁻¹). A pixel is
// the mean of its samples. Background samples (no hit) see the sky radiance along the ray; it
// goes into `total` only, so on surfaces total = the sum of the four layers.
//
// Parallel over samples with TBB; every output element is written by exactly one task and the
// visibility cache is thread-count independent, so the image is bit-identical whatever the
// number of threads. A NaN or Inf in any pixel is an internal error (std::logic_error naming
// the pixel), never written.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "geometry/bands/band_visibility.h"
#include "geometry/bands/visibility_cache.h"
#include "geometry/mesh/camera.h"
#include "geometry/mesh/scene.h"
#include "geometry/visibility/sky_factors.h"
#include "lighting/brdf/material.h"
#include "lighting/integrals/specular_sky_options.h"
#include "lighting/sky/sky_model.h"

namespace skyband {

struct RenderSettings {
  int samples_per_pixel = 1;  // anti-aliasing pattern of camera.h
  // How the visible sky of each surface sample is found (geometry/visibility/sky_visibility.h): exact by
  // default, cut along `visibility.bands` sample lines (geometry/bands/sample_lines.h); or the band
  // method's own geometry pass.
  SkyFactorsMethod method = SkyFactorsMethod::automatic;
  VisibilityOptions visibility;  // bands (N), tolerance (0 = fixed N), offsets
  SpecularSkyOptions specular;   // ε and steps of the partial-sky march (specular_sky.h)
  // Image-space reuse of the specular sky term (specular_reuse.h): quadtree blocks of up to this
  // many pixels, interpolated where the corners' bilinear interpolation predicts the marched
  // centre within the tolerance (relative), for materials at least this rough. Block < 4 or
  // tolerance 0: every sample exact.
  int specular_reuse_block = 32;
  double specular_reuse_tolerance = 0.01;
  double specular_reuse_min_roughness = 0.05;
  bool paper_scale = false;  // Cook–Torrance 1982 scale (×4) instead of the microfacet form
  int threads = 0;           // 0 = all cores
};

// One primary-ray hit.
struct SurfaceSample {
  Vec3 position;                // metres, on the hit triangle
  Vec3 normal;                  // unit geometric normal, facing the camera
  Vec3 view_dir;                // unit, from the surface toward the eye
  std::uint32_t material_slot;  // index into GeometryPass::material_slots
  std::uint32_t pixel;          // row·width + column
};

struct GeometryPass {
  static constexpr std::uint32_t kBackground = 0xffffffffu;
  int width = 0, height = 0, samples = 0;
  std::vector<std::uint32_t> sample_surface;  // per pixel sample (pixel·samples + i): surface or kBackground
  std::vector<Vec3> sample_direction;         // per pixel sample: unit primary-ray direction
  std::vector<SurfaceSample> surfaces;
  VisibilityCache visibility;               // entry k belongs to surfaces[k]
  std::vector<std::string> material_slots;  // the scene's material names (TriangleSoup::material_names)
  // Phase 1b state.
  Vec3 sun_direction{0, 0, 0};
  bool sun_set = false;
  std::vector<std::uint8_t> sun_visible;  // per surface: 1 = the sun is not blocked
  double trace_seconds = 0, visibility_seconds = 0, sun_seconds = 0;
};

// Phase 1. `progress(done, total)` reports the visibility pass (from one thread).
GeometryPass trace_geometry(const Scene& scene, const PinholeCamera& camera, const RenderSettings& settings,
                            const std::function<void(std::size_t, std::size_t)>& progress = {});

// Phase 1b: exact sun visibility of every surface sample for unit `sun_dir` (world, toward the sun).
void update_sun(GeometryPass& pass, const Scene& scene, const Vec3& sun_dir, const RenderSettings& settings);

struct RenderLayers {
  int width = 0, height = 0;
  // Linear sRGB, interleaved RGB, row-major, top row first; unit above.
  std::vector<float> sun_diffuse, sun_specular, sky_diffuse, sky_specular, total;
  // Specular sky samples marched exactly / interpolated (specular_reuse.h).
  std::size_t specular_exact = 0, specular_interpolated = 0;
  std::size_t specular_evaluations = 0;  // integrand evaluations of the marched samples (cost measure)
};

// The light of phase 2 as plain data: any sky radiance function (W·m⁻²·sr⁻¹·nm⁻¹, world
// direction; must be 0 at and below the horizon), the unit sun direction and its direct-normal
// spectral irradiance (W·m⁻²·nm⁻¹). SkyModel gives one (sky_light_of); tests use analytic skies.
struct SkyLight {
  std::function<void(const Vec3&, Spectrum&)> radiance;
  Vec3 sun_direction{0, 0, 1};
  Spectrum sun_direct_normal;
};
SkyLight sky_light_of(const SkyModel& sky);

RenderLayers shade(const GeometryPass& pass, const SkyLight& light, std::span<const Material* const> slot_materials,
                   const RenderSettings& settings);

// Phase 2. `slot_materials[k]` shades material slot k (size = pass.material_slots.size()). The
// pass must have been updated for sky.sun_direction() (else std::logic_error).
RenderLayers shade(const GeometryPass& pass, const SkyModel& sky, std::span<const Material* const> slot_materials,
                   const RenderSettings& settings);

// Built-in material for each slot: the slot's own name if it is a built-in material, else
// `default_material` (find_material: unknown names throw InputError naming `context`).
std::vector<const Material*> materials_for_slots(std::span<const std::string> slots, const std::string& default_material,
                                                 const std::string& context);

}  // namespace skyband
