#include "cli/render_output.h"

#include <cstdio>
#include <vector>

#include "cli/command_registry.h"
#include "io/exr_writer.h"
#include "io/png_writer.h"
#include "lighting/sun/sun.h"

namespace skyband::cli {

std::map<std::string, std::string> render_attributes(const SkyModel& sky, const RenderSettings& settings,
                                                     const std::string& extra_key, const std::string& extra_value) {
  char sun[160];
  std::snprintf(sun, sizeof sun, "altitude %.4f deg, azimuth %.4f deg (clockwise from north), direct normal %.2f W/m2",
                altitude_of(sky.sun_direction()) * 180.0 / kPi, azimuth_of(sky.sun_direction()) * 180.0 / kPi,
                sky.sun_direct_normal().integral_nm());
  char quality[300];
  std::snprintf(quality, sizeof quality,
                "visibility %s, bands %d, tolerance %g, specular epsilon %g, specular reuse block %d tolerance %g, samples per "
                "pixel %d, %s",
                settings.method == SkyFactorsMethod::bands   ? "band method"
                : settings.method == SkyFactorsMethod::exact ? "exact union"
                                                             : "exact (horizon or union)",
                settings.visibility.bands, settings.visibility.tolerance, settings.specular.epsilon,
                settings.specular_reuse_block, settings.specular_reuse_tolerance, settings.samples_per_pixel,
                settings.paper_scale ? "Cook-Torrance 1982 scale" : "microfacet f_s");
  std::map<std::string, std::string> a = {
      {"skyband_version", SKYBAND_VERSION},
      {"skyband_command", invocation()},
      {"skyband_sun", sun},
      {"skyband_sky", sky.describe()},
      {"skyband_quality", quality},
      {"skyband_units",
       "linear sRGB (Rec. 709 primaries, D65) of CIE 1931 XYZ = integral of spectral radiance "
       "(W m-2 sr-1 nm-1) times xbar, ybar, zbar over 380-780 nm: W m-2 sr-1, CMF-weighted; "
       "luminance cd m-2 = 683 * Y"},
      {"skyband_layers",
       "sun_diffuse + sun_specular + sky_diffuse + sky_specular = total on surfaces; background "
       "(no hit) holds the sky radiance in total only"},
  };
  if (!extra_key.empty()) a[extra_key] = extra_value;
  return a;
}

double write_render(const std::filesystem::path& exr_path, const RenderLayers& L, std::map<std::string, std::string> attributes,
                    std::optional<double> exposure) {
  const double e = exposure ? *exposure : auto_exposure(L.total);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", e);
  attributes["skyband_png_exposure"] = buf;
  std::vector<ImageLayer> layers = {{"sun_diffuse", L.sun_diffuse},
                                    {"sun_specular", L.sun_specular},
                                    {"sky_diffuse", L.sky_diffuse},
                                    {"sky_specular", L.sky_specular},
                                    {"total", L.total}};
  write_exr(exr_path, L.width, L.height, layers, attributes);
  std::filesystem::path png = exr_path;
  png.replace_extension(".png");
  write_png_srgb(png, L.width, L.height, L.total, e);
  return e;
}

}  // namespace skyband::cli
