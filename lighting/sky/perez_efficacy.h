#pragma once
// Perez luminous efficacy and zenith luminance model: R. Perez, P. Ineichen, R. Seals,
// J. Michalsky, R. Stewart, "Modeling daylight availability and irradiance components from direct
// and global irradiance", Solar Energy 44(5) 271–289 (1990) [Perez90], eqs. 6–10 and Table 4.
// Per clearness bin i (lighting/sky/perez_sky.h, the same ε, Δ and bins as the sky model):
//   global horizontal   η_g = a_i + b_i W + c_i cos Z + d_i ln Δ                 (lm/W, eq. 6)
//   diffuse horizontal  η_d = a_i + b_i W + c_i cos Z + d_i ln Δ                 (lm/W, eq. 7)
//   direct normal       η_b = max(0, a_i + b_i W + c_i exp(5.73 Z − 5) + d_i Δ)  (lm/W, eq. 8)
//   zenith luminance    L_z / DHI = a_i + c_i cos Z + c'_i exp(−3 Z) + d_i Δ     (cd·m⁻² per W·m⁻²)
// Z the sun zenith angle in radians, W the atmospheric precipitable water in cm, from the surface
// dew point T_d (°C) by W = exp(0.07 T_d − 0.075) (Perez90 eq. 3, after Wright, Perez &
// Michalsky 1989). Illuminances are the irradiances times their efficacies (GHI·η_g etc.).
//
// Coefficients: Table 4 of Perez90 as transcribed in Radiance's gendaylit.c (global, direct,
// diffuse) and gendaymtx.c (direct, diffuse), which agree with each other digit for digit. Two
// other public transcriptions differ in one digit each (diffuse c of bin 3: −5.52, direct c of
// bin 7: −1.25); the program of Muneer, "Solar radiation and daylight models", has −5.5334 and
// −1.26, as here. The zenith luminance coefficients are those of ladybug-tools' skymodel.py, the
// one public transcription found; they agree with Muneer's 7-digit values to ±0.01.
//
// Domain: the model was fitted for the sun above the horizon; Z is the model zenith of the sky
// condition (clamped at 90°) and Δ its clamped brightness (≥ 0.01, so ln Δ is finite). With the
// sun below the horizon the formulas are still evaluated at Z = 90° (twilight skies, DHI > 0).
#include "lighting/sky/perez_sky.h"

namespace skyband {

// W (cm) from the dew point (°C); throws InputError if it is not finite.
double precipitable_water_cm(double dew_point_C);

struct PerezEfficacy {
  double global_lm_W = 0;
  double direct_lm_W = 0;
  double diffuse_lm_W = 0;
  double zenith_luminance_per_dhi = 0;  // cd·m⁻² per W·m⁻² of DHI
};

// Efficacies of bin 0..7 at precipitable water W (cm), zenith Z (rad) and brightness Δ (> 0).
// Throws InputError for a bin outside 0..7, W < 0 or Δ ≤ 0 (or any of them not finite).
PerezEfficacy perez_luminous_efficacy(int bin, double precipitable_water_cm, double zenith_rad, double brightness);

struct PerezIlluminance {
  double global_horizontal_lux = 0;
  double direct_normal_lux = 0;
  double diffuse_horizontal_lux = 0;
  double zenith_luminance_cd_m2 = 0;
};

// Illuminances of one hour: GHI (W·m⁻², ≥ 0; measured or DNI cos Z + DHI) times η_g, the
// condition's DNI times η_b and DHI times η_d, and the zenith luminance, with the condition's
// bin, model zenith and clamped brightness. All zero when GHI, DNI and DHI are all zero.
PerezIlluminance perez_illuminance(double ghi_W_m2, const PerezSkyCondition& condition, double precipitable_water_cm);

}  // namespace skyband
