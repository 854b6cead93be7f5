#include "lighting/sky/perez_efficacy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "geometry/core/input_error.h"

namespace skyband {

namespace {

struct Row {
  double a, b, c, d;
};

// Perez90 Table 4, bins 1..8 (see the header for the transcriptions compared).
constexpr Row kGlobal[kPerezBinCount] = {{96.63, -0.47, 11.50, -9.16}, {107.54, 0.79, 1.79, -1.19}, {98.73, 0.70, 4.40, -6.95},
                                         {92.72, 0.56, 8.36, -8.31},   {86.73, 0.98, 7.10, -10.94}, {88.34, 1.39, 6.06, -7.60},
                                         {78.63, 1.47, 4.93, -11.37},  {99.65, 1.86, -4.46, -3.15}};
constexpr Row kDirect[kPerezBinCount] = {
    {57.20, -4.55, -2.98, 117.12}, {98.99, -3.46, -1.21, 12.38},   {109.83, -4.90, -1.71, -8.81}, {110.34, -5.84, -1.99, -4.56},
    {106.36, -3.97, -1.75, -6.16}, {107.19, -1.25, -1.51, -26.73}, {105.75, 0.77, -1.26, -34.44}, {101.18, 1.58, -1.10, -8.29}};
constexpr Row kDiffuse[kPerezBinCount] = {{97.24, -0.46, 12.00, -8.91},   {107.22, 1.15, 0.59, -3.95},
                                          {104.97, 2.96, -5.53, -8.77},   {102.39, 5.59, -13.95, -13.90},
                                          {100.71, 5.94, -22.75, -23.74}, {106.42, 3.83, -36.15, -28.83},
                                          {141.88, 1.90, -53.24, -14.03}, {152.23, 0.35, -45.27, -7.98}};
// Zenith luminance: a, c (cos Z), c' (exp(−3Z)), d (Δ).
constexpr Row kZenith[kPerezBinCount] = {{40.86, 26.77, -29.59, -45.75}, {26.58, 14.73, 58.46, -21.25},
                                         {19.34, 2.28, 100.00, 0.25},    {13.25, -1.39, 124.79, 15.66},
                                         {14.47, -5.09, 160.09, 9.13},   {19.76, -3.88, 154.61, -19.21},
                                         {28.39, -9.67, 151.58, -69.39}, {42.91, -19.62, 130.80, -164.08}};

std::string fmt(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace

double precipitable_water_cm(double dew_point_C) {
  if (!std::isfinite(dew_point_C)) throw InputError("Perez efficacy: dew point " + fmt(dew_point_C) + " C is not finite");
  return std::exp(0.07 * dew_point_C - 0.075);
}

PerezEfficacy perez_luminous_efficacy(int bin, double w, double zenith_rad, double brightness) {
  if (bin < 0 || bin >= kPerezBinCount)
    throw InputError("Perez efficacy: clearness bin " + std::to_string(bin) + " is not in 0..7");
  if (!std::isfinite(w) || w < 0)
    throw InputError("Perez efficacy: precipitable water " + fmt(w) + " cm must be finite and >= 0");
  if (!std::isfinite(brightness) || !(brightness > 0))
    throw InputError("Perez efficacy: sky brightness " + fmt(brightness) + " must be > 0");
  if (!std::isfinite(zenith_rad)) throw InputError("Perez efficacy: sun zenith " + fmt(zenith_rad) + " is not finite");
  const double cz = std::cos(zenith_rad), ln_delta = std::log(brightness);
  const Row& g = kGlobal[bin];
  const Row& b = kDirect[bin];
  const Row& d = kDiffuse[bin];
  const Row& z = kZenith[bin];
  PerezEfficacy e;
  e.global_lm_W = g.a + g.b * w + g.c * cz + g.d * ln_delta;
  e.diffuse_lm_W = d.a + d.b * w + d.c * cz + d.d * ln_delta;
  e.direct_lm_W = std::max(0.0, b.a + b.b * w + b.c * std::exp(5.73 * zenith_rad - 5) + b.d * brightness);
  e.zenith_luminance_per_dhi = z.a + z.b * cz + z.c * std::exp(-3 * zenith_rad) + z.d * brightness;
  return e;
}

PerezIlluminance perez_illuminance(double ghi_W_m2, const PerezSkyCondition& condition, double w) {
  if (!std::isfinite(ghi_W_m2) || ghi_W_m2 < 0)
    throw InputError("Perez efficacy: global horizontal irradiance " + fmt(ghi_W_m2) + " W/m2 must be finite and >= 0");
  PerezIlluminance out;
  if (ghi_W_m2 == 0 && condition.dni_W_m2 == 0 && condition.dhi_W_m2 == 0) return out;
  const PerezEfficacy e = perez_luminous_efficacy(condition.bin, w, condition.model_zenith_rad, condition.brightness);
  out.global_horizontal_lux = ghi_W_m2 * e.global_lm_W;
  out.direct_normal_lux = condition.dni_W_m2 * e.direct_lm_W;
  out.diffuse_horizontal_lux = condition.dhi_W_m2 * e.diffuse_lm_W;
  out.zenith_luminance_cd_m2 = condition.dhi_W_m2 * e.zenith_luminance_per_dhi;
  return out;
}

}  // namespace skyband
