#include "lighting/sky/cie_sky.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "geometry/core/input_error.h"
#include "lighting/spectrum/colour.h"

namespace skyband {

namespace {
// CIE S 011/E:2003 Table 1 (gradation groups I–VI, indicatrix groups 1–6), per type 1..15.
constexpr CieGeneralSkyCoefficients kTypes[15] = {
    {4.0, -0.70, 0, -1.0, 0},      {4.0, -0.70, 2, -1.5, 0.15},   {1.1, -0.8, 0, -1.0, 0},       {1.1, -0.8, 2, -1.5, 0.15},
    {0.0, -1.0, 0, -1.0, 0},       {0.0, -1.0, 2, -1.5, 0.15},    {0.0, -1.0, 5, -2.5, 0.30},    {0.0, -1.0, 10, -3.0, 0.45},
    {-1.0, -0.55, 2, -1.5, 0.15},  {-1.0, -0.55, 5, -2.5, 0.30},  {-1.0, -0.55, 10, -3.0, 0.45}, {-1.0, -0.32, 10, -3.0, 0.45},
    {-1.0, -0.32, 16, -3.0, 0.30}, {-1.0, -0.15, 16, -3.0, 0.30}, {-1.0, -0.15, 24, -2.8, 0.15}};

constexpr double kDeg = kPi / 180.0;

// Linear fade of the zenith luminance below the horizon (see header, [E]).
double twilight_fade(double h) {
  return h >= 0 ? 1.0 : std::max(0.0, 1.0 + h / (6.0 * kDeg));
}
}  // namespace

CieGeneralSkyCoefficients cie_general_sky_coefficients(int type) {
  if (type < 1 || type > 15) throw InputError("CIE general sky type " + std::to_string(type) + " is not in 1..15");
  return kTypes[type - 1];
}

double cie_gradation(double zenith_rad, double a, double b) {
  const double cz = std::cos(zenith_rad);
  if (cz <= 0) return 1.0;  // limit of exp(b/cos Z) → 0 for b < 0 at the horizon
  return 1.0 + a * std::exp(b / cz);
}

double cie_indicatrix(double chi_rad, double c, double d, double e) {
  const double cc = std::cos(chi_rad);
  return 1.0 + c * (std::exp(d * chi_rad) - std::exp(d * kPi / 2)) + e * cc * cc;
}

double gensky_overcast_zenith_luminance_cd_m2(double h) {
  return 1000.0 * (8.6 * std::sin(h) + 0.123);
}

double gensky_clear_zenith_luminance_cd_m2(double h, double turbidity) {
  return 1000.0 * ((1.376 * turbidity - 1.81) * std::tan(h) + 0.38);
}

double cie_default_zenith_luminance_cd_m2(int type, double sun_altitude_rad) {
  if (type < 0 || type > 15) throw InputError("CIE sky type " + std::to_string(type) + " is not in 0..15");
  if (!std::isfinite(sun_altitude_rad)) throw InputError("CIE sky: sun altitude is not finite");
  const double h = std::clamp(sun_altitude_rad, 0.0, 80.0 * kDeg);
  const double fade = twilight_fade(sun_altitude_rad);
  const double overcast =
      gensky_overcast_zenith_luminance_cd_m2(std::min(sun_altitude_rad < 0 ? 0.0 : sun_altitude_rad, kPi / 2));
  const double clear = gensky_clear_zenith_luminance_cd_m2(h);
  double lz = 0;
  if (type <= 5)
    lz = overcast;
  else if (type >= 11)
    lz = clear;
  else
    lz = std::sqrt(overcast * clear);
  return fade * lz;
}

Spectrum unit_luminance_shape(const Spectrum& s) {
  const double lum = luminous(s);
  if (!s.all_finite() || !(lum > 0)) throw InputError("CIE sky: spectral shape has no positive luminance");
  return s * (1.0 / lum);
}

CieSky::CieSky(int type, const Vec3& sun_dir, double zenith_luminance_cd_m2, const Spectrum& spectral_shape)
    : type_(type), sun_dir_(sun_dir), lz_(zenith_luminance_cd_m2), shape_(unit_luminance_shape(spectral_shape)) {
  if (type < 0 || type > 15) throw InputError("CIE sky type " + std::to_string(type) + " is not in 0..15 (0 = overcast)");
  if (!(zenith_luminance_cd_m2 >= 0) || !std::isfinite(zenith_luminance_cd_m2)) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g", zenith_luminance_cd_m2);
    throw InputError(std::string("CIE sky: zenith luminance ") + buf + " cd/m2 must be finite and >= 0");
  }
  if (!sun_dir.allFinite() || std::abs(sun_dir.norm() - 1.0) > 1e-6)
    throw InputError("CIE sky: sun direction is not a unit vector");
  if (type_ >= 1) {
    k_ = kTypes[type_ - 1];
    const double zs = std::acos(std::clamp(sun_dir_.z(), -1.0, 1.0));
    inv_norm_ = 1.0 / (cie_indicatrix(zs, k_.c, k_.d, k_.e) * cie_gradation(0.0, k_.a, k_.b));
  }
}

double CieSky::relative_luminance(const Vec3& dir) const {
  const double cz = dir.z();
  if (cz <= 0) return 0.0;
  if (type_ == 0) return (1.0 + 2.0 * cz) / 3.0;  // Moon–Spencer
  const double chi = std::acos(std::clamp(dir.dot(sun_dir_), -1.0, 1.0));
  const double phi = 1.0 + k_.a * std::exp(k_.b / cz);
  return cie_indicatrix(chi, k_.c, k_.d, k_.e) * phi * inv_norm_;
}

void CieSky::radiance_into(const Vec3& dir, Spectrum& out) const {
  const double l = lz_ * relative_luminance(dir);
  for (int i = 0; i < kSpectrumSamples; ++i) out[i] = shape_[i] * l;
}

std::string CieSky::name() const {
  return type_ == 0 ? std::string("cie-overcast") : "cie-" + std::to_string(type_);
}

}  // namespace skyband
