// skyband sky — the sun and the sky for one moment and place: sun position (NREL SPA) or a given
// sun altitude/azimuth, direct-normal sun spectrum, sky radiance from the physical atmosphere
// (single or multiple scattering) or a CIE sky, photometry and colour, and optionally an HDR
// fisheye image of the sky dome.
//
// Conventions: world x east, y north, z up; azimuth in degrees clockwise from north (0 = N,
// 90 = E); sun direction = (sin az·cos alt, cos az·cos alt, sin alt). Altitudes are apparent
// (refracted): --sun-altitude is taken as seen; with --lat/--lon/--time the SPA's refracted
// topocentric altitude is used.
//
// Fisheye image (--out FILE.exr, plus FILE.png beside it): equi-angular (radius ∝ zenith angle),
// zenith at the centre, horizon on the inscribed circle, NORTH UP and EAST LEFT — the sky as seen
// lying on the ground looking up (all-sky-camera / star-chart convention). Pixels outside the
// circle are 0. One layer "sky" (channels sky.R/G/B): linear sRGB (Rec. 709 primaries, D65) of
// X, Y, Z = ∫ L(λ)·x̄, ȳ, z̄(λ) dλ over 380–780 nm, L in W·m⁻²·sr⁻¹·nm⁻¹, so the unit is
// W·m⁻²·sr⁻¹ (CMF-weighted); luminance in cd·m⁻² = 683·Y. The sun disc is not drawn (its
// radiance is in the JSON/summary as direct-normal irradiance). The PNG is tone mapped (see
// io/png_writer.h) with --exposure or an automatic exposure (log-average key 0.18).
//
// Sun below the horizon: no direct sun (direct-normal irradiance 0 once the disc has set); the
// physical sky is whatever the atmosphere model gives for that sun (twilight); CIE zenith
// luminance fades to zero at −6°.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <system_error>

#include <nlohmann/json.hpp>

#include "cli/command_registry.h"
#include "cli/obstructed_fisheye.h"
#include "cli/sun_sky_options.h"
#include "geometry/core/input_error.h"
#include "geometry/mesh/scene.h"
#include "io/exr_writer.h"
#include "io/mesh_reader.h"
#include "io/png_writer.h"
#include "io/scene_crs.h"
#include "lighting/sky/sky_model.h"
#include "lighting/spectrum/colour.h"

namespace skyband::cli {
namespace {

struct SkyOptions {
  SunSkyOptions sun_sky;
  std::vector<double> at, normal;  // --at X,Y,Z, --normal NX,NY,NZ: the fisheye of one point of --mesh
  std::vector<std::string> meshes;
  std::string out;
  int size = 512;
  double exposure = 0;
  bool half = false;
  bool json = false;
  bool sun_path = false;  // --sun-path: the day's sun path on the --at fisheye
  CLI::Option* o_exposure = nullptr;
};

// The sun through the local day of --time (its UTC offset), every 10 minutes from 00:00 to
// 24:00: the marks of the --sun-path drawing.
std::vector<SunPathMark> day_sun_path(const SunSkyOptions& o) {
  const LocalDateTime day = o.local_time("--sun-path");
  std::vector<SunPathMark> marks;
  for (int minute = 0; minute <= 24 * 60; minute += 10) {
    LocalDateTime t = day;
    t.hour = minute / 60 % 24, t.minute = minute % 60, t.second = 0;
    if (minute == 24 * 60) t.hour = 23, t.minute = 59, t.second = 59;  // the day's end, same date
    marks.push_back({o.sun_at(t, "--sun-path").direction(), minute % 60 == 0});
  }
  return marks;
}

nlohmann::json xy_json(const Xyz& xyz) {
  const auto xy = chromaticity_xy(xyz);
  if (!xy) return nullptr;
  return nlohmann::json::array({xy->x(), xy->y()});
}

nlohmann::json cct_json(const Xyz& xyz) {
  const auto xy = chromaticity_xy(xyz);
  if (!xy) return nullptr;
  const auto t = cct_robertson_K(*xy);
  if (!t) return nullptr;
  return *t;
}

void run_sky(const SkyOptions& o) {
  // --- validate everything first (one place), then compute ----------------------------------
  const SunPlacement sun = o.sun_sky.place_sun();
  const AtmosphereParams ap = o.sun_sky.atmosphere();
  const SkyModelSpec spec = o.sun_sky.sky_spec();
  std::filesystem::path exr_path, png_path;
  if (!o.out.empty()) {
    exr_path = o.out;
    if (exr_path.extension() != ".exr") throw InputError("--out '" + o.out + "': the file name must end in .exr");
    png_path = exr_path;
    png_path.replace_extension(".png");
    const std::filesystem::path dir = exr_path.has_parent_path() ? exr_path.parent_path() : std::filesystem::path(".");
    std::error_code ec;  // the error_code form: a name the system refuses (> 255 bytes) is the user's input
    const std::filesystem::file_status status = std::filesystem::status(dir, ec);
    if (!std::filesystem::is_directory(status))
      throw InputError("--out '" + o.out + "': folder '" + dir.string() + "' " +
                       (ec && status.type() != std::filesystem::file_type::not_found ? "cannot be used: " + ec.message()
                                                                                     : std::string("does not exist")));
    if (o.size < 16 || o.size > 8192) throw InputError("--size " + std::to_string(o.size) + ": must be in [16, 8192] pixels");
  }
  if (o.o_exposure->count() && !(o.exposure > 0 && std::isfinite(o.exposure)))
    throw InputError("--exposure " + fmt(o.exposure) + ": must be finite and > 0");
  // --at: the point whose obstructed sky the fisheye shows.
  std::optional<QueryPoint> at;
  if (!o.at.empty() || !o.normal.empty() || !o.meshes.empty()) {
    if (o.at.size() != 3) throw InputError("--at: give the point as X,Y,Z (metres, the model's coordinates)");
    if (o.meshes.empty()) throw InputError("--at needs --mesh FILE (the model the point sees)");
    if (o.out.empty()) throw InputError("--at needs --out FILE.exr (the fisheye of what the point sees)");
    Vec3 n(0, 0, 1);
    if (!o.normal.empty()) {
      if (o.normal.size() != 3) throw InputError("--normal: give the face's normal as NX,NY,NZ");
      n = Vec3(o.normal[0], o.normal[1], o.normal[2]);
      if (!(n.norm() > 0) || !std::isfinite(n.norm())) throw InputError("--normal: must be a finite, non-zero vector");
      n.normalize();
    }
    const Vec3 p(o.at[0], o.at[1], o.at[2]);
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
      throw InputError("--at: coordinates must be finite");
    at = QueryPoint{p, n};
  }
  if (o.sun_path && !at) throw InputError("--sun-path draws on the fisheye of a point: give --at X,Y,Z and --mesh");
  const std::vector<SunPathMark> path = o.sun_path ? day_sun_path(o.sun_sky) : std::vector<SunPathMark>{};

  const Vec3 sun_dir = sun.direction();
  const SkyModel sky(ap, sun_dir, spec);

  // --- sun -----------------------------------------------------------------------------------
  const Spectrum& dn = sky.sun_direct_normal();
  const Xyz dn_xyz = spectrum_to_xyz(dn);
  // --- sky: horizontal diffuse (hemisphere quadrature, 0.5° cells) and zenith -----------------
  const Spectrum diffuse = horizontal_irradiance([&](const Vec3& d, Spectrum& out) { sky.radiance_into(d, out); }, 180);
  const Spectrum zenith = sky.radiance(Vec3(0, 0, 1));
  const Xyz diffuse_xyz = spectrum_to_xyz(diffuse), zenith_xyz = spectrum_to_xyz(zenith);
  const double sin_alt = std::max(0.0, sun_dir.z());
  const Spectrum global = diffuse + dn * sin_alt;
  const Spectrum tau_r = sky.atmosphere().rayleigh_optical_depth();
  const auto grid_index = [](double nm) { return static_cast<int>(std::lround((nm - kLambdaMinNm) / kLambdaStepNm)); };

  nlohmann::json j;
  j["skyband_version"] = SKYBAND_VERSION;
  j["conventions"] = "world x east, y north, z up; azimuth degrees clockwise from north; altitudes apparent (refracted)";
  std::vector<double> wl(kSpectrumSamples), dnv(dn.v.begin(), dn.v.end());
  for (int i = 0; i < kSpectrumSamples; ++i) wl[static_cast<std::size_t>(i)] = wavelength_nm(i);
  j["sun"] = {{"altitude_deg", sun.altitude_deg},
              {"azimuth_deg", sun.azimuth_deg},
              {"direction", {sun_dir.x(), sun_dir.y(), sun_dir.z()}},
              {"position", sun.source},
              {"above_horizon", dn.integral_nm() > 0},
              {"direct_normal_irradiance_W_m2", dn.integral_nm()},
              {"direct_normal_illuminance_lx", luminous(dn)},
              {"chromaticity_xy", xy_json(dn_xyz)},
              {"cct_K", cct_json(dn_xyz)},
              {"spectrum", {{"wavelength_nm", wl}, {"direct_normal_W_m2_nm", dnv}}}};
  nlohmann::json sky_j = {{"model", sky.model_name()},
                          {"horizontal_diffuse_irradiance_W_m2", diffuse.integral_nm()},
                          {"horizontal_diffuse_illuminance_lx", luminous(diffuse)},
                          {"horizontal_diffuse_chromaticity_xy", xy_json(diffuse_xyz)},
                          {"horizontal_diffuse_cct_K", cct_json(diffuse_xyz)},
                          {"global_horizontal_irradiance_W_m2", global.integral_nm()},
                          {"global_horizontal_illuminance_lx", luminous(global)},
                          {"zenith", {{"luminance_cd_m2", luminous(zenith)}, {"chromaticity_xy", xy_json(zenith_xyz)}}}};
  if (const CieSky* c = sky.cie())
    sky_j["cie"] = {{"type", c->type()},
                    {"zenith_luminance_cd_m2", c->zenith_luminance_cd_m2()},
                    {"zenith_luminance_source", spec.zenith_luminance_cd_m2 ? "user" : "gensky-style formula"}};
  j["sky"] = sky_j;
  j["atmosphere"] = {{"rayleigh_optical_depth",
                      {{"400", tau_r[grid_index(400)]}, {"550", tau_r[grid_index(550)]}, {"700", tau_r[grid_index(700)]}}},
                     {"aerosol_optical_depth_550", ap.aod550},
                     {"angstrom_alpha", ap.angstrom_alpha},
                     {"ozone_DU", ap.ozone_du},
                     {"ground_elevation_m", ap.ground_elevation_m}};
  j["units"] = {{"irradiance", "W m-2 (integrated 380-780 nm)"},
                {"spectral_irradiance", "W m-2 nm-1"},
                {"illuminance", "lx (K_m = 683 lm/W, CIE 1931 2-degree ybar)"},
                {"luminance", "cd m-2"}};

  // --- image -------------------------------------------------------------------------------
  if (at) {
    TriangleSoup soup;
    SceneCrs crs;
    for (const std::string& file : o.meshes) {
      MeshReadReport report;
      TriangleSoup part = read_mesh(file, &report, crs.next({}));
      crs.add(report);
      soup.append(part);
      if (!o.json)
        std::fprintf(stderr, "%s\n", report.summary().c_str());
      else
        for (const std::string& w : report.warnings) std::fprintf(stderr, "skyband: warning: %s\n", w.c_str());
    }
    const Scene scene(std::move(soup));
    Spectrum l;
    const ObstructedFisheye f = render_obstructed_fisheye(
        scene, *at, o.size,
        [&](const Vec3& d) {
          sky.radiance_into(d, l);
          return spectrum_to_linear_srgb(l);
        },
        o.o_exposure->count() ? o.exposure : 0.0, path);
    const std::vector<ImageLayer> layers{{"sky", f.sky_rgb}, {"visible", f.visible_rgb}};
    const std::map<std::string, std::string> attrs = {
        {"skyband_version", SKYBAND_VERSION},
        {"skyband_command", invocation()},
        {"skyband_point", "x=" + fmt(at->position.x()) + " y=" + fmt(at->position.y()) + " z=" + fmt(at->position.z()) +
                              " normal=" + fmt(at->normal.x()) + "," + fmt(at->normal.y()) + "," + fmt(at->normal.z())},
        {"skyband_sky", sky.describe()},
        {"skyband_layers",
         "sky: linear sRGB radiance (W m-2 sr-1, as the open-sky fisheye) where the point sees the sky, 0 "
         "where the scene or its own face hides it; visible: 1 or 0"},
        {"skyband_projection",
         "equi-angular fisheye: radius proportional to zenith angle, zenith at centre, horizon on "
         "the inscribed circle, north up, east left (seen from below)"}};
    write_exr(exr_path, o.size, o.size, layers, attrs, o.half ? ExrPixelType::Half : ExrPixelType::Float);
    write_png_rgb8(png_path, o.size, o.size, f.picture);
    j["point"] = {{"position", {at->position.x(), at->position.y(), at->position.z()}},
                  {"normal", {at->normal.x(), at->normal.y(), at->normal.z()}},
                  {"svf", f.svf},
                  {"sky_exposure", f.sky_exposure},
                  {"visible_fraction_of_fisheye_pixels", f.sky_pixels ? double(f.visible_pixels) / double(f.sky_pixels) : 0.0}};
    if (o.sun_path)
      j["point"]["sun_path"] = {{"step_min", 10},
                                {"marks_above_horizon", f.sun_marks_up},
                                {"marks_seen", f.sun_marks_seen},
                                {"sun_hours_estimate", double(f.sun_marks_seen) * 10.0 / 60.0}};
    j["image"] = {{"exr", exr_path.string()}, {"png", png_path.string()}, {"size_px", o.size}};
  } else if (!exr_path.empty()) {
    const int n = o.size;
    ImageLayer layer{"sky", std::vector<float>(static_cast<std::size_t>(n) * static_cast<std::size_t>(n) * 3, 0.0f)};
    Spectrum l;
    for (int row = 0; row < n; ++row)
      for (int col = 0; col < n; ++col) {
        const double u = 2.0 * (col + 0.5) / n - 1.0;  // right
        const double v = 1.0 - 2.0 * (row + 0.5) / n;  // up
        const double r = std::hypot(u, v);
        if (r >= 1.0) continue;
        const double zen = r * 0.5 * kPi;
        const double az = std::atan2(-u, v);  // north up, east left
        const Vec3 d(std::sin(az) * std::sin(zen), std::cos(az) * std::sin(zen), std::cos(zen));
        sky.radiance_into(d, l);
        const Vec3 rgb = spectrum_to_linear_srgb(l);
        float* px = &layer.rgb[(static_cast<std::size_t>(row) * static_cast<std::size_t>(n) + static_cast<std::size_t>(col)) * 3];
        for (int c = 0; c < 3; ++c) px[c] = static_cast<float>(rgb[c]);
      }
    const double exposure = o.o_exposure->count() ? o.exposure : auto_exposure(layer.rgb);
    const std::map<std::string, std::string> attrs = {
        {"skyband_version", SKYBAND_VERSION},
        {"skyband_command", invocation()},
        {"skyband_sun", "altitude_deg=" + fmt(sun.altitude_deg) + " azimuth_deg=" + fmt(sun.azimuth_deg) + " (" +
                            sun.source.value("method", std::string()) + ")"},
        {"skyband_sky", sky.describe()},
        {"skyband_units",
         "linear sRGB (Rec.709, D65) of CIE 1931 XYZ = integral of L(lambda)*cmf over 380-780 nm; "
         "L in W m-2 sr-1 nm-1 -> pixel unit W m-2 sr-1; luminance cd m-2 = 683*Y"},
        {"skyband_projection",
         "equi-angular fisheye: radius proportional to zenith angle, zenith at centre, horizon on "
         "the inscribed circle, north up, east left (seen from below); outside = 0; sun disc not drawn"},
        {"skyband_conventions", "world x east, y north, z up; azimuth clockwise from north"},
        {"skyband_png_exposure", fmt(exposure)}};
    write_exr(exr_path, n, n, std::span<const ImageLayer>(&layer, 1), attrs, o.half ? ExrPixelType::Half : ExrPixelType::Float);
    write_png_srgb(png_path, n, n, layer.rgb, exposure);
    j["image"] = {{"exr", exr_path.string()}, {"png", png_path.string()}, {"size_px", n}, {"png_exposure", exposure}};
  }

  if (o.json) {
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::printf("sun       altitude %.4f deg, azimuth %.4f deg (clockwise from north)%s\n", sun.altitude_deg, sun.azimuth_deg,
              dn.integral_nm() > 0 ? "" : " - below the horizon: no direct sun");
  std::printf("          direct normal %.2f W/m2 (380-780 nm), %.0f lx", dn.integral_nm(), luminous(dn));
  if (auto t = cct_json(dn_xyz); !t.is_null()) std::printf(", CCT %.0f K", t.get<double>());
  std::printf("\nsky       model %s; horizontal diffuse %.2f W/m2, %.0f lx; zenith %.0f cd/m2\n", sky.model_name().c_str(),
              diffuse.integral_nm(), luminous(diffuse), luminous(zenith));
  std::printf("          global horizontal %.0f lx\n", luminous(global));
  std::printf("atmosphere tau_R(550) %.4f, aod550 %g, alpha %g, ozone %g DU\n", tau_r[grid_index(550)], ap.aod550,
              ap.angstrom_alpha, ap.ozone_du);
  if (at)
    std::printf("point     svf %.6f, sky exposure %.6f (the fisheye shows what it sees; the red line is its horizon)\n",
                j["point"]["svf"].get<double>(), j["point"]["sky_exposure"].get<double>());
  if (at && o.sun_path)
    std::printf("sun path  %zu of %zu ten-minute marks above the horizon seen from the point (~%.1f h of sun)\n",
                j["point"]["sun_path"]["marks_seen"].get<std::size_t>(),
                j["point"]["sun_path"]["marks_above_horizon"].get<std::size_t>(),
                j["point"]["sun_path"]["sun_hours_estimate"].get<double>());
  if (!exr_path.empty()) std::printf("wrote     %s and %s\n", exr_path.string().c_str(), png_path.string().c_str());
}

CLI::App* setup_sky(CLI::App& app) {
  auto o = std::make_shared<SkyOptions>();
  CLI::App* sub = app.add_subcommand(
      "sky",
      "Sun and sky for one moment: sun position, direct sun spectrum, sky radiance (physical or CIE), photometry, "
      "optional HDR fisheye image.\nConventions: world x east, y north, z up; azimuth in degrees clockwise from north; "
      "sun direction = (sin az cos alt, cos az cos alt, sin alt); altitudes are apparent (refracted).\n"
      "Fisheye (--out): equi-angular, zenith at the centre, north up, east left (sky seen from below).");
  o->sun_sky.add_to(sub);
  sub->add_option("--out", o->out, "Write an HDR fisheye FILE.exr and a tone-mapped FILE.png beside it");
  sub->add_option("--at", o->at,
                  "With --mesh: the fisheye of what this point X,Y,Z sees (hidden sky grey, its horizon red, N/E/S/W)")
      ->delimiter(',');
  sub->add_option("--normal", o->normal, "With --at: the face's normal NX,NY,NZ (default 0,0,1)")->delimiter(',');
  sub->add_option("--mesh", o->meshes, "With --at: mesh or city model file; repeat for several")->check(CLI::ExistingFile);
  sub->add_flag("--sun-path", o->sun_path,
                "With --at and --lat/--lon/--time: draw the sun's path through that day, every 10 min (larger dots at the\n"
                "hours; yellow where the point sees the sun, dark orange where it is hidden)");
  sub->add_option("--size", o->size, "Fisheye image size in pixels (default 512)");
  o->o_exposure =
      sub->add_option("--exposure", o->exposure, "PNG exposure multiplier (default: automatic, log-average key 0.18)");
  sub->add_flag("--half", o->half, "Store the EXR as half floats (default 32-bit float)");
  sub->add_flag("--json", o->json, "Print one JSON object to stdout instead of the summary");
  sub->callback([o] { run_sky(*o); });
  return sub;
}

const CommandRegistration registration("sky", setup_sky);

}  // namespace
}  // namespace skyband::cli
