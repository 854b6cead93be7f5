#pragma once
// The Perez all-weather sky: the relative luminance (or radiance) distribution of R. Perez,
// R. Seals, J. Michalsky, "All-weather model for sky luminance distribution — preliminary
// configuration and validation", Solar Energy 50(3) 235–245 (1993), erratum Solar Energy 51(5)
// 423 (1993) [Perez93], driven by the sky condition parameters of R. Perez, P. Ineichen,
// R. Seals, J. Michalsky, R. Stewart, "Modeling daylight availability and irradiance components
// from direct and global irradiance", Solar Energy 44(5) 271–289 (1990) [Perez90].
//
// Sky condition (Perez90 eqs. 1–2), from the diffuse horizontal and direct normal irradiance:
//   clearness   ε = ((DHI + DNI)/DHI + κ Z³) / (1 + κ Z³),   κ = 1.041, Z sun zenith in radians;
//   brightness  Δ = DHI · m / I0,
// m the relative optical air mass (Kasten & Young 1989 by default), I0 the extraterrestrial normal
// irradiance of the day (Spencer 1971 × 1367 W·m⁻² by default). ε falls in one of eight bins with
// lower edges 1.000, 1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200 (bin 8 is open above); bin
// k (1-based in the papers) is index k − 1 here. Each edge belongs to the bin above it.
//
// Relative luminance of a sky element at zenith angle θ and angle γ from the sun (Perez93 eq. 1):
//   l(θ, γ) = [1 + a exp(b / cos θ)] · [1 + c exp(d γ) + e cos² γ]
//             (gradation G(θ))         (indicatrix F(γ))
// with, for each of a…e, x = x1 + x2 Z + Δ (x3 + x4 Z) (Perez93 eq. 6, Table 1), except in bin 1
// where c = exp((Δ (c1 + c2 Z))^c3) − c4 and d = −exp(Δ (d1 + d2 Z)) + d3 + Δ d4 (eqs. 7–8).
//
// The sky is scaled so that it reproduces the horizontal diffuse quantity it is given:
//   L(w) = k · l(θ(w), γ(w)),   k = DHI / ∫_{z>0} l cos θ dω,
// in W·m⁻²·sr⁻¹ (broadband radiance) when normalised to DHI in W·m⁻², or in cd·m⁻² when
// normalised to the diffuse horizontal illuminance in lux (lighting/sky/perez_efficacy.h).
//
// Domain and pitfalls, and what is done about each [E = engineering choice]:
//  * Parameter clamps, as in Radiance's gendaylit.c (J.-J. Delaunay, Fraunhofer ISE 1994, the
//    implementation daylighting practice has used since; limits in check_parametrization added by
//    J. Wienold 2009, the Δ floor in coeff_lum_perez): Δ is clamped to [0.01, 0.6], and in bins
//    2–5 (1.065 < ε < 2.8) the coefficient formulas use max(Δ, 0.2). ε needs no clamp: it is ≥ 1
//    for DNI ≥ 0 and enters the coefficients only through its bin (gendaylit's clamp of ε to
//    [1, 12.01) selects the same bins).
//  * Sun zenith: the coefficient formulas, ε and the default air mass use Z clamped to ≤ 90°
//    (the model was fitted for suns above the horizon; gendaymtx.c clamps the same way). A sun
//    below the horizon with DHI > 0 (twilight) still gives a valid sky: the angle γ is measured
//    from the true sun direction, so the brightest sky is towards the sun along the horizon [E]
//    (gendaymtx also moves the sun itself to the horizon; keeping it where it is keeps the sky
//    continuous as the sun sets and puts the circumsolar peak where the sun is). No lower limit
//    on Z: gendaylit and gendaymtx use Z ≥ 3°, gendaymtx "to keep circumsolar off zenith", i.e.
//    out of its zenith sky patch; the integration here has no patches.
//  * Horizon: l is defined for cos θ > 0 only (directions with z ≤ 0 have zero radiance). For
//    b < 0, exp(b / cos θ) → 0 as cos θ → 0⁺ (no overflow, no NaN). The table gives b ≥ 0 in
//    bin 6 at Δ ≤ 0.05 with a high sun or Δ ≥ 0.4 with the sun at the horizon, bin 7 at Δ ≥ 0.5,
//    and bin 8 at Δ ≳ 0.3 (clear skies rarely exceed Δ ≈ 0.2): G would then grow without bound
//    towards the horizon and the normalisation integral diverge, so b is clamped to ≤ 0 [E]
//    (gendaylit refuses such skies).
//  * Negative factors: where the table makes G < 0 (a < −1 with small |b|, bin 6 at small Δ:
//    near the zenith) or F < 0 (c < 0, bin 4 at Δ ≳ 0.53 with a high sun: near the sun), each
//    factor is clamped to ≥ 0 [E] (gendaymtx clamps the product per sky patch; clamping each
//    factor keeps two negative factors from making a positive luminance). If nothing of the sky
//    is left, the sky is uniform (l ≡ 1), as in gendaymtx.
//  * DHI = 0: no sky (zero radiance everywhere; the coefficients are not evaluated).
//
// Normalisation quadrature (perez_horizontal_integral): the integral is taken in polar
// coordinates (γ, ψ) about the sun, where F depends on γ alone, so the circumsolar cusp of
// exp(dγ) at the sun (and at the antisolar point) becomes the smooth exp(dγ) sin γ:
//   ∫ l cos θ dω = ∫₀^π F(γ) sin γ J(γ) dγ,   J(γ) = ∫ G(μ) μ dψ over the part of the circle of
// radius γ about the sun that lies above the horizon (and inside the region G ≥ 0), with
// μ = cos θ = cos γ cos Z + sin γ sin Z cos ψ. Of J, the term ∫ μ dψ is exact (arc ends by
// arccos). The term a ∫ μ exp(b/μ) dψ is C∞ but not analytic where the arc reaches the horizon:
// exp(b/μ) switches on over μ ~ |b|, so a single Gauss–Legendre rule converges slowly; the arc is
// cut into pieces with μ ratio 4 towards the horizon (each then analytic in a Bernstein ellipse
// of fixed shape) and dropped below μ = |b|/20 (integrand < 2.1e-9 μ). The γ integral is split
// where the circle of radius γ touches the horizon or the boundary of G ≥ 0 (J has square-root
// behaviour there, removed by the map γ = γ0 + (γ1 − γ0)(1 − cos t)/2 on every piece), at
// distances |b|, |b|/4, |b|/16 on both sides of the horizon tangencies (the same switch-on seen
// across circles), and where F crosses zero. `nodes` is the Gauss–Legendre order of the γ pieces
// (half of it on the graded ones); the arcs use nodes/2, 5·nodes/12 and nodes/3. exp(−x) in the
// arcs is lighting/integrals/fast_exp.h (relative error < 3e-11).
// Accuracy of the default 24 against an independent adaptive Gauss–Kronrod integration in
// zenith/azimuth coordinates: ≤ 3e-10 relative on ordinary skies (every bin, Δ 0.08–0.35, sun
// from the zenith to 3° below the horizon), ≤ 7e-9 at the corners of the clamped range (Δ 0.01
// or 0.6, sun at the zenith or below the horizon); 32 nodes give ≤ 1e-11 (the fast exp's error
// then dominates). Cost: ~2000–2500 evaluations of cos and exp per call (about 40–60 µs on the
// 2-core test machine; see the timing output of perez_sky_test).
//
// Frames: world x east, y north, z up; directions are unit vectors.
#include "geometry/core/vec3.h"

namespace skyband {

inline constexpr double kPerezKappa = 1.041;  // rad⁻³, Perez90 eq. 1
inline constexpr int kPerezBinCount = 8;
// Lower edges of the clearness bins 1..8 (Perez90 Table 1, Perez93 Table 1); bin 8 is open above.
inline constexpr double kPerezClearnessLowerEdges[kPerezBinCount] = {1.000, 1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200};
inline constexpr double kPerezMinBrightness = 0.01;  // gendaylit's limits on Δ
inline constexpr double kPerezMaxBrightness = 0.6;
inline constexpr double kPerezMinBrightnessBins2to5 = 0.2;  // gendaylit coeff_lum_perez
inline constexpr double kSolarConstant_W_m2 = 1367.0;       // WRC 1981, as used by gendaylit

// Relative optical air mass, F. Kasten & A. T. Young, "Revised optical air mass tables and
// approximation formula", Applied Optics 28(22) 4735–4738 (1989):
//   m = 1 / (cos Z + 0.50572 (96.07995 − Z[°])^−1.6364),
// Z the sun zenith angle in radians, clamped to [0, π/2] (m(90°) = 37.92). Throws InputError if Z
// is not finite.
double relative_air_mass_kasten_young(double zenith_rad);

// Extraterrestrial normal irradiance (W·m⁻²) on day `day_of_year` (1..366): the solar constant
// times Spencer's eccentricity factor (J. W. Spencer, "Fourier series representation of the
// position of the sun", Search 2(5) 172, 1971; Iqbal 1983 eq. 1.2.1):
//   E0 = 1.000110 + 0.034221 cos Γ + 0.001280 sin Γ + 0.000719 cos 2Γ + 0.000077 sin 2Γ,
//   Γ = 2π (day − 1)/365.
// Throws InputError for a day outside 1..366 or a non-positive solar constant.
double extraterrestrial_normal_irradiance_W_m2(int day_of_year, double solar_constant_W_m2 = kSolarConstant_W_m2);

// ε (Perez90 eq. 1). dhi, dni ≥ 0 (W·m⁻²), zenith in radians, used as given (callers clamp).
// Returns +∞ when dhi = 0 (the limit for DNI > 0; no sky either way).
double perez_sky_clearness(double dhi_W_m2, double dni_W_m2, double zenith_rad);
// Δ (Perez90 eq. 2), unclamped.
double perez_sky_brightness(double dhi_W_m2, double air_mass, double extraterrestrial_W_m2);
// Bin index 0..7 of ε (ε < 1 goes to bin 0, +∞ to bin 7). Throws InputError for NaN.
int perez_clearness_bin(double clearness);

// The parameters of one hour's sky, after the clamps listed above.
struct PerezSkyCondition {
  double dhi_W_m2 = 0;
  double dni_W_m2 = 0;
  double sun_zenith_rad = 0;                // as given (may exceed π/2)
  double model_zenith_rad = 0;              // min(sun_zenith_rad, π/2): used in ε, m and the coefficients
  double clearness = 1;                     // ε, ≥ 1 (+∞ when DHI = 0)
  double brightness = kPerezMinBrightness;  // Δ clamped to [0.01, 0.6]
  double brightness_unclamped = 0;          // Δ before the clamp
  int bin = 0;                              // 0..7
  bool has_sky() const { return dhi_W_m2 > 0; }
};

// Throws InputError when dhi or dni is negative or not finite, the zenith is not in [0, π], or
// air mass / extraterrestrial irradiance is not positive and finite.
PerezSkyCondition perez_sky_condition(double dhi_W_m2, double dni_W_m2, double sun_zenith_rad, double air_mass,
                                      double extraterrestrial_W_m2);
// Same with the default air mass (Kasten & Young at the model zenith) and I0 of `day_of_year`.
PerezSkyCondition perez_sky_condition(double dhi_W_m2, double dni_W_m2, double sun_zenith_rad, int day_of_year);

struct PerezSkyCoefficients {
  double a = 0, b = 0, c = 0, d = 0, e = 0;  // all zero: the uniform sky l ≡ 1
};

// The coefficient formulas of Perez93 (eqs. 6–8, Table 1) as printed: bin 0..7, Δ and Z (rad)
// used as given, no clamps. Throws InputError for a bin outside 0..7.
PerezSkyCoefficients perez_sky_coefficients_raw(int bin, double brightness, double zenith_rad);
// The coefficients of a sky condition: Δ floor 0.2 in bins 2–5, Z = model zenith, b ≤ 0.
PerezSkyCoefficients perez_sky_coefficients(const PerezSkyCondition& condition);

// G(θ) = max(0, 1 + a exp(b / cos θ)) for cos θ > 0, b ≤ 0 (limit 1 at the horizon for b < 0).
double perez_gradation(double cos_theta, double a, double b);
// F(γ) = max(0, 1 + c exp(d γ) + e cos² γ), γ in [0, π].
double perez_indicatrix(double gamma_rad, double c, double d, double e);
// l = G(θ) F(γ); 0 for cos θ ≤ 0.
double perez_relative_luminance(const PerezSkyCoefficients& k, double cos_theta, double gamma_rad);

// ∫_{z>0} l(θ, γ) cos θ dω (sr) for the sun in direction `sun_dir` (unit; may be below the
// horizon), by the quadrature described above with `nodes` Gauss–Legendre nodes per piece
// (4..128). Requires b ≤ 0. Returns 0 when the clamped l vanishes on the whole sky.
double perez_horizontal_integral(const PerezSkyCoefficients& k, const Vec3& sun_dir, int nodes = 24);

// One hour's sky: L(w) = scale · l(θ(w), γ(w)).
struct PerezSky {
  Vec3 sun_dir{0, 0, 1};  // unit, world frame; may point below the horizon
  PerezSkyCoefficients coefficients;
  double scale = 0;  // 0: no sky
  PerezSkyCondition condition;

  // Radiance (W·m⁻²·sr⁻¹) or luminance (cd·m⁻²) of unit direction `dir`, in the unit of the
  // quantity the sky was normalised to per steradian; 0 for dir.z ≤ 0.
  double radiance(const Vec3& dir) const;
};

// The sky of `condition` for the sun in `sun_dir`, scaled so that ∫_{z>0} L cos θ dω equals
// `horizontal_diffuse` (DHI in W·m⁻² for radiance; diffuse horizontal illuminance in lux for
// luminance; ≥ 0). No sky (scale 0) when the condition has DHI = 0 or horizontal_diffuse = 0.
// Throws InputError if sun_dir is not a unit vector, or horizontal_diffuse is negative or not
// finite. The sun direction should agree with condition.sun_zenith_rad (it is not checked).
PerezSky make_perez_sky(const PerezSkyCondition& condition, const Vec3& sun_dir, double horizontal_diffuse, int nodes = 24);

}  // namespace skyband
