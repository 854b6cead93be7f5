// skyband render — render a scene file (io/scene_file.h) to a multi-layer linear EXR plus a
// tone-mapped PNG preview beside it.
//
//   skyband render --scene FILE.toml [--out FILE.exr] [--set key=value ...] [--exposure E]
//                  [--threads T]
//
// Layers: sun_diffuse, sun_specular, sky_diffuse, sky_specular, total (each R, G, B), linear
// sRGB in W·m⁻²·sr⁻¹ weighted by the CIE 1931 colour-matching functions (render/renderer.h).
// The PNG exposure is --exposure, else the scene's image.exposure, else automatic (log-average
// key 0.18 of the total layer); pass the same value to every image of a series.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/command_registry.h"
#include "cli/number_text.h"
#include "cli/render_output.h"
#include "geometry/core/input_error.h"
#include "io/scene_file.h"
#include "lighting/sun/sun.h"
#include "render/renderer.h"

namespace skyband::cli {
namespace {

struct RenderOptions {
  std::string scene, out = "render.exr";
  std::vector<std::string> sets;
  double exposure = 0;
  int threads = 0;
  bool quiet = false;
  CLI::Option* o_exposure = nullptr;
};

double since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void run_render(const RenderOptions& o) {
  // Validate everything first.
  const std::filesystem::path exr(o.out);
  if (exr.extension() != ".exr") throw InputError("--out '" + o.out + "': the file name must end in .exr");
  if (o.o_exposure->count() && !(o.exposure > 0 && std::isfinite(o.exposure)))
    throw InputError("--exposure " + shortest_text(o.exposure) + ": must be finite and > 0");
  if (o.threads < 0 || o.threads > 1024) throw InputError("--threads " + std::to_string(o.threads) + ": must be in [0, 1024]");
  const SceneDescription desc = load_scene_file(o.scene, o.sets);
  const PinholeCamera camera(desc.camera);
  RenderSettings settings;
  settings.samples_per_pixel = desc.samples;
  settings.method = desc.visibility;
  settings.visibility.bands = desc.bands;
  settings.visibility.tolerance = desc.tolerance;
  settings.specular.epsilon = desc.epsilon;
  settings.paper_scale = desc.paper_scale;
  settings.specular_reuse_block = desc.reuse_block;
  settings.specular_reuse_tolerance = desc.reuse_tolerance;
  settings.threads = o.threads;
  const Vec3 sun_dir = direction_from_altitude_azimuth(desc.sun_altitude_deg * kPi / 180.0, desc.sun_azimuth_deg * kPi / 180.0);
  const SkyModel sky(desc.atmosphere, sun_dir, desc.sky_spec);

  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::string> report;
  const Scene scene(load_scene_geometry(desc, &report));
  if (!o.quiet)
    std::fprintf(stderr, "scene: %zu triangles from %zu mesh file(s)\n", scene.soup().triangle_count(), desc.meshes.size());
  const std::vector<const Material*> mats =
      materials_for_slots(scene.soup().material_names, desc.default_material, desc.file.string());
  GeometryPass pass = trace_geometry(scene, camera, settings);
  update_sun(pass, scene, sun_dir, settings);
  const auto t1 = std::chrono::steady_clock::now();
  const RenderLayers layers = shade(pass, sky, mats, settings);
  const double t_shade = since(t1);
  std::optional<double> exposure;
  if (o.o_exposure->count())
    exposure = o.exposure;
  else if (desc.exposure)
    exposure = desc.exposure;
  auto attrs = render_attributes(sky, settings, "skyband_scene", desc.file.string());
  const double e = write_render(exr, layers, attrs, exposure);
  if (!o.quiet)
    std::fprintf(stderr,
                 "rendered %dx%d, %zu surface samples: trace %.2f s, visibility %.2f s, sun %.2f s, shading %.2f s, "
                 "total %.2f s; PNG exposure %.4g\nwrote %s and %s\n",
                 layers.width, layers.height, pass.surfaces.size(), pass.trace_seconds, pass.visibility_seconds, pass.sun_seconds,
                 t_shade, since(t0), e, exr.string().c_str(),
                 std::filesystem::path(exr).replace_extension(".png").string().c_str());
}

const CommandRegistration reg("render", [](CLI::App& app) {
  auto opts = std::make_shared<RenderOptions>();
  CLI::App* sub = app.add_subcommand("render", "Render a scene file to a multi-layer EXR and a PNG preview");
  sub->add_option("--scene", opts->scene, "Scene file (TOML; keys in io/scene_file.h)")->required();
  sub->add_option("--out", opts->out, "Output EXR (the PNG is written beside it)")->capture_default_str();
  sub->add_option("--set", opts->sets, "Override a scene key: --set sun.altitude_deg=17 (repeatable)");
  opts->o_exposure = sub->add_option("--exposure", opts->exposure, "PNG exposure (linear scale before tone mapping)");
  sub->add_option("--threads", opts->threads, "Worker threads (0 = all cores)")->capture_default_str();
  sub->add_flag("--quiet", opts->quiet, "No progress output");
  sub->callback([opts] { run_render(*opts); });
  return sub;
});

}  // namespace
}  // namespace skyband::cli
