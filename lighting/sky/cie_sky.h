#pragma once
// CIE sky luminance distributions with a fixed spectral shape.
//
// * CIE standard general skies, types 1–15 (CIE S 011/E:2003 = ISO 15469:2004; coefficients as
//   grouped in Darula & Kittler 2002, reference-notes §3.3):
//     L(Z, χ)/L_z = f(χ)·φ(Z) / (f(Z_s)·φ(0))
//     φ(Z) = 1 + a·exp(b / cos Z)                  (gradation; φ(90°) = 1)
//     f(χ) = 1 + c·[exp(d·χ) − exp(d·π/2)] + e·cos²χ   (scattering indicatrix)
//   Z zenith angle of the view direction, χ its angle to the sun, Z_s the sun's zenith angle.
//   Type 12 is the CIE standard clear sky (the 1973 formula).
// * CIE standard overcast sky (Moon & Spencer 1942, CIE 1955): L(Z)/L_z = (1 + 2 cos Z)/3.
//
// Zenith luminance L_z (cd·m⁻²): a user value, or gensky-style formulas (Radiance
// src/gen/gensky.c, reference-notes §3.3): overcast L_z = 8.6 sin h + 0.123 kcd·m⁻², clear
// L_z = (1.376 T − 1.81) tan h + 0.38 kcd·m⁻² with turbidity T = 2.45. Engineering choices [E]:
// types 1–5 (no circumsolar indicatrix, c = 0) use the overcast formula, types 11–15 the clear
// one, the intermediate types 6–10 their geometric mean; tan h is evaluated at min(h, 80°)
// (the clear formula has no meaning near the zenith singularity); for the sun below the horizon
// both formulas are evaluated at h = 0 and faded linearly to zero at h = −6° (end of civil
// twilight), since the CIE skies describe daylight only.
//
// Spectrum: L(λ, dir) = L(dir)[cd·m⁻²] · shape(λ) with shape normalised to 1 cd·m⁻² (i.e.
// K_m ∫ shape ȳ dλ = 1), giving W·m⁻²·sr⁻¹·nm⁻¹. The shape comes from the caller (sky_model.h
// takes it from the physical atmosphere). Directions below the horizon have zero radiance.
// Directions: world x east, y north, z up.
#include <string>

#include "geometry/core/vec3.h"
#include "lighting/spectrum/spectrum.h"

namespace skyband {

struct CieGeneralSkyCoefficients {
  double a, b, c, d, e;
};

// Coefficients of general sky type 1..15; throws InputError otherwise.
CieGeneralSkyCoefficients cie_general_sky_coefficients(int type);

// φ(Z), gradation function; Z in radians, 0 ≤ Z ≤ π/2 (φ = 1 at and beyond the horizon).
double cie_gradation(double zenith_rad, double a, double b);
// f(χ), scattering indicatrix; χ in radians [0, π].
double cie_indicatrix(double chi_rad, double c, double d, double e);

// gensky zenith luminances, cd·m⁻², sun altitude in radians (valid for h ≥ 0; see above for the
// clamps used by cie_default_zenith_luminance_cd_m2).
double gensky_overcast_zenith_luminance_cd_m2(double sun_altitude_rad);
double gensky_clear_zenith_luminance_cd_m2(double sun_altitude_rad, double turbidity = 2.45);
// type 0 = standard overcast, 1..15 = general sky types (choices [E] above).
double cie_default_zenith_luminance_cd_m2(int type, double sun_altitude_rad);

// Scale a spectrum to unit luminance: K_m ∫ s ȳ dλ = 1 (so that multiplying by a luminance in
// cd·m⁻² gives W·m⁻²·sr⁻¹·nm⁻¹). Throws InputError if s has no luminance or is not finite.
Spectrum unit_luminance_shape(const Spectrum& s);

class CieSky {
 public:
  // type 0 = CIE standard overcast (sun position irrelevant), 1..15 = general sky types.
  // `sun_dir` unit vector; zenith_luminance_cd_m2 ≥ 0; `spectral_shape` any spectrum with
  // positive luminance (it is normalised here).
  CieSky(int type, const Vec3& sun_dir, double zenith_luminance_cd_m2, const Spectrum& spectral_shape);

  int type() const { return type_; }
  bool is_standard_overcast() const { return type_ == 0; }
  // Types whose luminance has no sun term (overcast, 1–5): the sun is taken as hidden.
  bool sun_hidden() const { return type_ <= 5; }
  double zenith_luminance_cd_m2() const { return lz_; }
  const Spectrum& unit_shape() const { return shape_; }
  const Vec3& sun_direction() const { return sun_dir_; }

  // L/L_z of a unit direction (0 below the horizon).
  double relative_luminance(const Vec3& dir) const;
  double luminance_cd_m2(const Vec3& dir) const { return lz_ * relative_luminance(dir); }
  // Spectral radiance W·m⁻²·sr⁻¹·nm⁻¹; radiance_into does not allocate.
  void radiance_into(const Vec3& dir, Spectrum& out) const;
  Spectrum radiance(const Vec3& dir) const {
    Spectrum s;
    radiance_into(dir, s);
    return s;
  }
  std::string name() const;  // "cie-overcast" or "cie-N"

 private:
  int type_;
  Vec3 sun_dir_;
  double lz_;
  Spectrum shape_;
  CieGeneralSkyCoefficients k_{};
  double inv_norm_ = 1;  // 1/(f(Z_s)·φ(0))
};

}  // namespace skyband
