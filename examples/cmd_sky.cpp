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
#include <string>

#include <nlohmann/json.hpp>

#include "examples/command_registry.h"
#include "geometry/input_error.h"
#include "io/exr_writer.h"
#include "io/png_writer.h"
#include "lighting/colour.h"
#include "lighting/sky_model.h"
#include "lighting/sun.h"
#include "lighting/sun_position.h"

namespace skyband::cli {
namespace {

constexpr double kDeg = kPi / 180.0;

struct SkyOptions {
  double sun_altitude_deg = 0, sun_azimuth_deg = 180;
  double lat_deg = 0, lon_deg = 0, elevation_m = 0;
  std::string time;
  double tz_hours = 0, delta_t_s = 69.0, pressure_mbar = 1013.25, temperature_C = 15.0;
  double aod550 = AtmosphereParams{}.aod550;
  double angstrom_alpha = AtmosphereParams{}.angstrom_alpha;
  double ozone_du = AtmosphereParams{}.ozone_du;
  std::string model = "multiple";
  double zenith_luminance = 0;
  std::string out;
  int size = 512;
  double exposure = 0;
  bool half = false;
  bool json = false;
  // Which options were given.
  CLI::Option *o_alt = nullptr, *o_az = nullptr, *o_lat = nullptr, *o_lon = nullptr, *o_time = nullptr, *o_tz = nullptr,
              *o_zl = nullptr, *o_exposure = nullptr;
};

std::string fmt(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

void require_finite(const char* flag, double v) {
  if (!std::isfinite(v)) throw InputError(std::string(flag) + " " + fmt(v) + ": not a finite number");
}

void require_range(const char* flag, double v, double lo, double hi, const char* what) {
  require_finite(flag, v);
  if (v < lo || v > hi) throw InputError(std::string(flag) + " " + fmt(v) + ": " + what);
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

struct SunPlacement {
  double altitude_deg, azimuth_deg;
  nlohmann::json source;
};

SunPlacement place_sun(const SkyOptions& o) {
  const bool by_angle = o.o_alt->count() > 0 || o.o_az->count() > 0;
  const bool by_place = o.o_lat->count() > 0 || o.o_lon->count() > 0 || o.o_time->count() > 0 || o.o_tz->count() > 0;
  if (by_angle && by_place) throw InputError("give either --sun-altitude [--sun-azimuth] or --lat --lon --time, not both");
  if (by_angle) {
    if (o.o_alt->count() == 0) throw InputError("--sun-azimuth needs --sun-altitude");
    require_range("--sun-altitude", o.sun_altitude_deg, -90.0, 90.0, "altitude must be in [-90, 90] degrees");
    require_range("--sun-azimuth", o.sun_azimuth_deg, -360.0, 360.0, "azimuth must be in [-360, 360] degrees (clockwise from north)");
    double az = std::fmod(o.sun_azimuth_deg, 360.0);
    if (az < 0) az += 360.0;
    return {o.sun_altitude_deg, az, {{"method", "given"}}};
  }
  if (!by_place) throw InputError("no sun: give --sun-altitude DEG [--sun-azimuth DEG] or --lat DEG --lon DEG --time ISO8601");
  if (o.o_lat->count() == 0 || o.o_lon->count() == 0 || o.o_time->count() == 0)
    throw InputError("sun from place and time needs all of --lat, --lon and --time");
  require_range("--lat", o.lat_deg, -90.0, 90.0, "latitude must be in [-90, 90] degrees");
  require_range("--lon", o.lon_deg, -180.0, 180.0, "longitude must be in [-180, 180] degrees (east positive)");
  require_range("--tz", o.tz_hours, -18.0, 18.0, "UTC offset must be in [-18, 18] hours");
  require_range("--delta-t", o.delta_t_s, -8000.0, 8000.0, "ΔT must be in [-8000, 8000] s");
  require_range("--pressure-mbar", o.pressure_mbar, 1e-3, 5000.0, "pressure must be in (0, 5000] mbar");
  require_range("--temperature-c", o.temperature_C, -272.0, 6000.0, "temperature must be above -273 °C");
  SpaInput in;
  in.latitude_deg = o.lat_deg;
  in.longitude_deg = o.lon_deg;
  in.elevation_m = o.elevation_m;
  in.time = parse_iso8601(o.time, "--time", o.o_tz->count() ? std::optional<double>(o.tz_hours) : std::nullopt);
  in.delta_t_s = o.delta_t_s;
  in.pressure_mbar = o.pressure_mbar;
  in.temperature_C = o.temperature_C;
  const SpaResult r = sun_position_spa(in);
  nlohmann::json src = {{"method", "NREL SPA (Reda & Andreas 2004)"},
                        {"latitude_deg", o.lat_deg},
                        {"longitude_deg", o.lon_deg},
                        {"elevation_m", o.elevation_m},
                        {"time", o.time},
                        {"utc_offset_hours", in.time.utc_offset_hours},
                        {"delta_t_s", o.delta_t_s},
                        {"julian_day", r.julian_day},
                        {"zenith_deg_refracted", r.zenith_deg},
                        {"declination_deg", r.topocentric_declination_deg}};
  return {90.0 - r.zenith_deg, r.azimuth_deg, src};
}

void run_sky(const SkyOptions& o) {
  // --- validate everything first (one place), then compute ----------------------------------
  const SunPlacement sun = place_sun(o);
  AtmosphereParams ap;
  require_finite("--aod550", o.aod550);
  require_finite("--angstrom-alpha", o.angstrom_alpha);
  require_finite("--ozone-du", o.ozone_du);
  require_finite("--elevation", o.elevation_m);
  if (o.aod550 < 0) throw InputError("--aod550 " + fmt(o.aod550) + ": optical depth must be >= 0");
  if (o.ozone_du < 0) throw InputError("--ozone-du " + fmt(o.ozone_du) + ": ozone column must be >= 0");
  ap.aod550 = o.aod550;
  ap.angstrom_alpha = o.angstrom_alpha;
  ap.ozone_du = o.ozone_du;
  ap.ground_elevation_m = o.elevation_m;
  try {
    ap.validate();
  } catch (const InputError& e) {
    throw InputError(std::string("atmosphere (--aod550/--angstrom-alpha/--ozone-du/--elevation): ") + e.what());
  }
  SkyModelSpec spec = parse_sky_model(o.model, "--model");
  if (o.o_zl->count()) {
    if (spec.physical) throw InputError("--zenith-luminance applies to CIE skies only, not --model " + o.model);
    require_range("--zenith-luminance", o.zenith_luminance, 0.0, 1e7, "zenith luminance must be in [0, 1e7] cd/m2");
    spec.zenith_luminance_cd_m2 = o.zenith_luminance;
  }
  std::filesystem::path exr_path, png_path;
  if (!o.out.empty()) {
    exr_path = o.out;
    if (exr_path.extension() != ".exr") throw InputError("--out '" + o.out + "': the file name must end in .exr");
    png_path = exr_path;
    png_path.replace_extension(".png");
    const std::filesystem::path dir = exr_path.has_parent_path() ? exr_path.parent_path() : std::filesystem::path(".");
    if (!std::filesystem::is_directory(dir)) throw InputError("--out '" + o.out + "': folder '" + dir.string() + "' does not exist");
    if (o.size < 16 || o.size > 8192) throw InputError("--size " + std::to_string(o.size) + ": must be in [16, 8192] pixels");
  }
  if (o.o_exposure->count() && !(o.exposure > 0 && std::isfinite(o.exposure)))
    throw InputError("--exposure " + fmt(o.exposure) + ": must be finite and > 0");

  const Vec3 sun_dir = direction_from_altitude_azimuth(sun.altitude_deg * kDeg, sun.azimuth_deg * kDeg);
  const SkyModel sky(ap, sun_dir, spec);

  // --- sun -----------------------------------------------------------------------------------
  const Spectrum& dn = sky.sun_direct_normal();
  const Xyz dn_xyz = spectrum_to_xyz(dn);
  // --- sky: horizontal diffuse (hemisphere quadrature, 0.5° cells) and zenith -----------------
  const Spectrum diffuse = horizontal_irradiance([&](const Vec3& d, Spectrum& out) { sky.radiance_into(d, out); }, 180);
  const Spectrum zenith = sky.radiance(Vec3(0, 0, 1));
  const Xyz diffuse_xyz = spectrum_to_xyz(diffuse), zenith_xyz = spectrum_to_xyz(zenith);
  const double sin_alt = std::max(0.0, std::sin(sun.altitude_deg * kDeg));
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
    sky_j["cie"] = {{"type", c->type()}, {"zenith_luminance_cd_m2", c->zenith_luminance_cd_m2()},
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
  if (!exr_path.empty()) {
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
        {"skyband_units", "linear sRGB (Rec.709, D65) of CIE 1931 XYZ = integral of L(lambda)*cmf over 380-780 nm; "
                          "L in W m-2 sr-1 nm-1 -> pixel unit W m-2 sr-1; luminance cd m-2 = 683*Y"},
        {"skyband_projection", "equi-angular fisheye: radius proportional to zenith angle, zenith at centre, horizon on "
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
  o->o_alt = sub->add_option("--sun-altitude", o->sun_altitude_deg, "Apparent sun altitude, degrees [-90, 90]");
  o->o_az = sub->add_option("--sun-azimuth", o->sun_azimuth_deg, "Sun azimuth, degrees clockwise from north (default 180 = south)");
  o->o_lat = sub->add_option("--lat", o->lat_deg, "Latitude, degrees north (with --lon, --time: NREL SPA)");
  o->o_lon = sub->add_option("--lon", o->lon_deg, "Longitude, degrees east");
  o->o_time = sub->add_option("--time", o->time, "Local time, ISO 8601: 2026-06-21T12:00:00+02:00, ...Z, or without offset plus --tz");
  o->o_tz = sub->add_option("--tz", o->tz_hours, "UTC offset of --time in hours (east positive), when --time has none");
  sub->add_option("--elevation", o->elevation_m, "Site elevation above sea level, metres (SPA parallax and atmosphere ground)");
  sub->add_option("--delta-t", o->delta_t_s, "Delta T = TT - UT1, seconds (default 69)");
  sub->add_option("--pressure-mbar", o->pressure_mbar, "Mean local pressure for SPA refraction, mbar (default 1013.25)");
  sub->add_option("--temperature-c", o->temperature_C, "Mean local temperature for SPA refraction, deg C (default 15)");
  sub->add_option("--aod550", o->aod550, "Aerosol optical depth at 550 nm (default 0.1)");
  sub->add_option("--angstrom-alpha", o->angstrom_alpha, "Angstrom exponent (default 1.3)");
  sub->add_option("--ozone-du", o->ozone_du, "Ozone column, Dobson units (default 300)");
  sub->add_option("--model", o->model, "Sky model: single | multiple | cie-1 ... cie-15 | cie-overcast (default multiple)");
  o->o_zl = sub->add_option("--zenith-luminance", o->zenith_luminance, "CIE skies: zenith luminance cd/m2 (default gensky-style formula)");
  sub->add_option("--out", o->out, "Write an HDR fisheye FILE.exr and a tone-mapped FILE.png beside it");
  sub->add_option("--size", o->size, "Fisheye image size in pixels (default 512)");
  o->o_exposure = sub->add_option("--exposure", o->exposure, "PNG exposure multiplier (default: automatic, log-average key 0.18)");
  sub->add_flag("--half", o->half, "Store the EXR as half floats (default 32-bit float)");
  sub->add_flag("--json", o->json, "Print one JSON object to stdout instead of the summary");
  sub->callback([o] { run_sky(*o); });
  return sub;
}

const CommandRegistration registration("sky", setup_sky);

}  // namespace
}  // namespace skyband::cli
