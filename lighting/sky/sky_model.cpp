#include "lighting/sky/sky_model.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "geometry/core/input_error.h"
#include "lighting/spectrum/colour.h"

namespace skyband {

SkyModelSpec parse_sky_model(std::string_view text, std::string_view flag) {
  SkyModelSpec s;
  if (text == "single" || text == "multiple") {
    s.physical = true;
    s.orders = text == "single" ? ScatteringOrders::Single : ScatteringOrders::Multiple;
    return s;
  }
  s.physical = false;
  if (text == "cie-overcast") return s;
  if (text.size() > 4 && text.substr(0, 4) == "cie-") {
    int n = 0;
    const auto num = text.substr(4);
    const auto [p, ec] = std::from_chars(num.data(), num.data() + num.size(), n);
    if (ec == std::errc() && p == num.data() + num.size() && n >= 1 && n <= 15) {
      s.cie_type = n;
      return s;
    }
  }
  throw InputError(std::string(flag) + " '" + std::string(text) +
                   "': unknown sky model (expected single, multiple, cie-1 … cie-15 or cie-overcast)");
}

namespace {

Vec3 checked_unit(const Vec3& d) {
  const double n = d.norm();
  if (!d.allFinite() || !(n > 0)) throw InputError("sky model: sun direction is not a direction");
  return d / n;
}

std::variant<SkyTable, CieSky> make_sky(const Atmosphere& atm, const Vec3& sun, const SkyModelSpec& spec,
                                        const Spectrum& sun_dn) {
  if (spec.physical) return SkyTable(atm, sun, spec.orders);
  // CIE: spectral shape from the physical sky for the same sun (see header).
  const SkyTable table(atm, sun, spec.orders);
  Spectrum diffuse = horizontal_irradiance([&](const Vec3& d, Spectrum& out) { table.radiance_into(d, out); }, 90);
  Spectrum shape = diffuse;
  CieSky probe(spec.cie_type, sun, 0.0, cie_d65());
  if (probe.sun_hidden()) shape += sun_dn * std::max(0.0, sun.z());
  if (!shape.all_finite() || !(luminous(shape) > 1e-9 * luminous(cie_d65()))) shape = cie_d65();
  const double alt = std::asin(std::clamp(sun.z(), -1.0, 1.0));
  const double lz =
      spec.zenith_luminance_cd_m2 ? *spec.zenith_luminance_cd_m2 : cie_default_zenith_luminance_cd_m2(spec.cie_type, alt);
  return CieSky(spec.cie_type, sun, lz, shape);
}

}  // namespace

SkyModel::SkyModel(const AtmosphereParams& atmosphere, const Vec3& sun_dir, const SkyModelSpec& spec)
    : atmosphere_(atmosphere),
      spec_(spec),
      sun_dir_(checked_unit(sun_dir)),
      sun_direct_normal_(atmosphere_.sun_direct_normal(std::asin(std::clamp(sun_dir_.z(), -1.0, 1.0)))),
      sky_(make_sky(atmosphere_, sun_dir_, spec_, sun_direct_normal_)) {
  if (const CieSky* c = cie(); c && c->sun_hidden()) sun_direct_normal_ = Spectrum{};
}

double SkyModel::sun_altitude_rad() const {
  return std::asin(std::clamp(sun_dir_.z(), -1.0, 1.0));
}

std::string SkyModel::model_name() const {
  if (const CieSky* c = cie()) return c->name();
  return spec_.orders == ScatteringOrders::Single ? "single" : "multiple";
}

std::string SkyModel::describe() const {
  const AtmosphereParams& p = atmosphere_.params();
  const double alt = sun_altitude_rad() * 180.0 / kPi;
  double az = std::atan2(sun_dir_.x(), sun_dir_.y()) * 180.0 / kPi;
  if (az < 0) az += 360.0;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "model=%s aod550=%g angstrom_alpha=%g ozone_du=%g ground_elevation_m=%g aerosol_scale_height_m=%g "
                "aerosol_ssa=%g aerosol_g=%g ground_albedo=%g sun_altitude_deg=%.6f sun_azimuth_deg=%.6f",
                model_name().c_str(), p.aod550, p.angstrom_alpha, p.ozone_du, p.ground_elevation_m, p.aerosol_scale_height_m,
                p.aerosol_single_scattering_albedo, p.aerosol_asymmetry_g, p.ground_albedo, alt, az);
  std::string s = buf;
  if (const CieSky* c = cie()) {
    std::snprintf(buf, sizeof buf, " cie_zenith_luminance_cd_m2=%g%s", c->zenith_luminance_cd_m2(),
                  spec_.zenith_luminance_cd_m2 ? " (user)" : " (gensky-style)");
    s += buf;
  }
  return s;
}

}  // namespace skyband
