#pragma once
// One sky object for the renderer and the CLI: the physical spectral sky (Atmosphere + SkyTable,
// single or multiple scattering) or a CIE sky (general types 1–15, standard overcast) whose
// spectral shape is taken from the physical model for the same sun and atmosphere.
//
//   * radiance(dir): spectral radiance W·m⁻²·sr⁻¹·nm⁻¹ of the sky dome along unit `dir` (world
//     frame x east, y north, z up); zero for directions at or below the horizon (the ground and
//     its reflections are the scene's business, not the sky's).
//   * sun_direct_normal(): spectral direct-normal irradiance W·m⁻²·nm⁻¹ of the sun at the ground
//     (Atmosphere::sun_direct_normal at the sun's apparent altitude); zero once the whole disc is
//     below the horizon, and zero for CIE skies without a sun term (overcast, types 1–5).
//   * The sun direction is apparent (refracted): altitude = asin(sun_dir.z).
//
// CIE spectral shapes (an engineering choice [E], see cie_sky.h): for sun-hidden types (overcast,
// 1–5) the shape of the physical global horizontal irradiance (direct·sin h + diffuse), i.e.
// sunlight and skylight mixed by the cloud deck; for the other types the shape of the physical
// sky's horizontal diffuse irradiance. If that spectrum has no luminance (sun far below the
// horizon) the CIE D65 shape is used. Sun below the horizon: physical sky as computed by the
// atmosphere model (twilight); CIE zenith luminance fades to zero at −6° (cie_sky.h).
//
// Closed set of alternatives in a std::variant: no virtual calls in the radiance hot path.
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "geometry/core/vec3.h"
#include "lighting/atmosphere/atmosphere.h"
#include "lighting/atmosphere/sky_table.h"
#include "lighting/sky/cie_sky.h"
#include "lighting/spectrum/spectrum.h"

namespace skyband {

struct SkyModelSpec {
  bool physical = true;
  ScatteringOrders orders = ScatteringOrders::Multiple;  // physical sky (and CIE shape source)
  int cie_type = 0;                                      // CIE: 0 = standard overcast, 1..15
  std::optional<double> zenith_luminance_cd_m2;          // CIE: user value, else gensky-style
};

// "single" | "multiple" | "cie-1" … "cie-15" | "cie-overcast"; anything else throws InputError
// naming `flag` and the text.
SkyModelSpec parse_sky_model(std::string_view text, std::string_view flag);

// ∫_{upper hemisphere} L(ω) (n·ω) dω for n = +z, by the midpoint rule on n_zenith × 2·n_zenith
// cells of (zenith angle, azimuth). `radiance_into(dir, Spectrum&)` is any callable.
template <class RadianceInto>
Spectrum horizontal_irradiance(const RadianceInto& radiance_into, int n_zenith = 180) {
  Spectrum sum, l;
  const int n_az = 2 * n_zenith;
  const double dz = 0.5 * kPi / n_zenith, da = 2.0 * kPi / n_az;
  for (int i = 0; i < n_zenith; ++i) {
    const double z = (i + 0.5) * dz;
    const double w = std::cos(z) * std::sin(z) * dz * da;
    for (int j = 0; j < n_az; ++j) {
      const double a = (j + 0.5) * da;
      radiance_into(Vec3(std::sin(a) * std::sin(z), std::cos(a) * std::sin(z), std::cos(z)), l);
      for (int k = 0; k < kSpectrumSamples; ++k) sum[k] += w * l[k];
    }
  }
  return sum;
}

class SkyModel {
 public:
  // Validates everything (atmosphere parameters, sun direction, model); throws InputError.
  SkyModel(const AtmosphereParams& atmosphere, const Vec3& sun_dir, const SkyModelSpec& spec);

  Spectrum radiance(const Vec3& dir) const {
    Spectrum s;
    radiance_into(dir, s);
    return s;
  }
  void radiance_into(const Vec3& dir, Spectrum& out) const {
    if (dir.z() <= 0) {
      out = Spectrum{};
      return;
    }
    std::visit([&](const auto& sky) { sky.radiance_into(dir, out); }, sky_);
  }
  const Spectrum& sun_direct_normal() const { return sun_direct_normal_; }
  const Vec3& sun_direction() const { return sun_dir_; }
  double sun_altitude_rad() const;
  const Atmosphere& atmosphere() const { return atmosphere_; }
  const SkyModelSpec& spec() const { return spec_; }
  // "single", "multiple", "cie-N", "cie-overcast".
  std::string model_name() const;
  // One line for provenance: model, atmosphere parameters, sun, CIE zenith luminance.
  std::string describe() const;
  // The CIE sky when the model is one (for its zenith luminance etc.), else nullptr.
  const CieSky* cie() const { return std::get_if<CieSky>(&sky_); }

 private:
  Atmosphere atmosphere_;
  SkyModelSpec spec_;
  Vec3 sun_dir_;
  Spectrum sun_direct_normal_;
  std::variant<SkyTable, CieSky> sky_;
};

}  // namespace skyband
