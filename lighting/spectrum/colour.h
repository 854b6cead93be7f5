#pragma once
// Colour and photometry of spectra on skyband's 41-sample grid (380–780 nm, 10 nm):
//   spectrum → CIE 1931 XYZ (2° observer), XYZ → linear sRGB (Rec. 709 primaries, D65 white),
//   chromaticity xy, luminous quantities with K_m = 683 lm/W, and correlated colour temperature
//   by Robertson's method.
//
// Units: spectrum_to_xyz(s) carries the unit of s times nm (e.g. a radiance in
// W·m⁻²·sr⁻¹·nm⁻¹ gives radiometric XYZ in W·m⁻²·sr⁻¹); luminous(s) = K_m·Y turns it into the
// photometric unit (W·m⁻²·sr⁻¹·nm⁻¹ → cd·m⁻², W·m⁻²·nm⁻¹ → lx).
//
// Sources: CIE 1931 2° colour-matching functions, 5 nm table (CIE 15:2004), as carried in
// ebruneton/precomputed_atmospheric_scattering atmosphere/constants.h (BSD-3-Clause) and in
// /work/shared/data/spectra/cie1931_2deg_5nm.txt; sRGB: IEC 61966-2-1:1999; D65: CIE 15:2004
// Table T.1; CCT: A. R. Robertson, "Computation of correlated color temperature and distribution
// temperature", JOSA 58(11) 1528–1535 (1968), isotemperature-line table as reprinted in
// Wyszecki & Stiles, Color Science (2nd ed., 1982), Table 1(3.11); Planck: CODATA 2018 constants.
#include <optional>
#include <span>

#include <Eigen/Core>

#include "geometry/core/vec3.h"
#include "lighting/spectrum/spectrum.h"

namespace skyband {

// Maximum luminous efficacy of radiation for photopic vision (lm/W), CIE 15:2004.
inline constexpr double kMaxLuminousEfficacy_lm_W = 683.0;

struct Xyz {
  double X = 0, Y = 0, Z = 0;
};

struct CmfRow {
  double wavelength_nm, xbar, ybar, zbar;
};

// The embedded CIE 1931 2° table, 360–830 nm every 5 nm (95 rows).
std::span<const CmfRow> cie1931_2deg_5nm();

// x̄, ȳ, z̄ sampled on the Spectrum grid (every other row of the 5-nm table).
const Spectrum& cmf_x();
const Spectrum& cmf_y();
const Spectrum& cmf_z();

// x̄, ȳ, z̄ (c = 0, 1, 2) times the trapezoid weights of the grid (nm): spectrum_to_xyz(s) is
// the dot product of these with s, so any linear map of spectra to XYZ can be pre-projected.
const Spectrum& xyz_weights(int c);

// ∫ s(λ)·{x̄,ȳ,z̄}(λ) dλ by the trapezoid rule on the grid (same rule as Spectrum::integral_nm).
Xyz spectrum_to_xyz(const Spectrum& s);

// K_m·∫ s ȳ dλ: luminance (cd·m⁻²) of a spectral radiance, illuminance (lx) of a spectral
// irradiance.
double luminous(const Spectrum& s);

// Linear sRGB from XYZ, matrix derived from the Rec. 709 primaries and the D65 white point
// (xy = 0.3127, 0.3290) so that XYZ of D65 with Y = 1 maps to RGB = (1, 1, 1).
const Eigen::Matrix3d& linear_srgb_from_xyz();
Vec3 xyz_to_linear_srgb(const Xyz& xyz);
// Convenience: spectrum → XYZ → linear sRGB (unit: the spectrum's unit × nm).
Vec3 spectrum_to_linear_srgb(const Spectrum& s);

// CIE 1931 chromaticity (x, y); empty when X + Y + Z ≤ 0 (e.g. no light).
std::optional<Vec2> chromaticity_xy(const Xyz& xyz);

// CIE 1960 UCS (u, v) from xy (Robertson's method works in this space).
Vec2 uv1960_from_xy(const Vec2& xy);

// Correlated colour temperature (K) by Robertson (1968): the isotemperature line nearest to the
// chromaticity in CIE 1960 uv. Valid range of the table: 1667 K (600 MK⁻¹) to infinity; empty
// outside it. Robertson's own accuracy is a few K below 10 000 K.
std::optional<double> cct_robertson_K(const Vec2& xy);

// Planck's law, spectral radiance of a black body (W·m⁻²·sr⁻¹·nm⁻¹) at wavelength_nm:
//   L = 2hc²/λ⁵ / (exp(hc/(λ k T)) − 1).
double planck_radiance_W_m2_sr_nm(double wavelength_nm, double temperature_K);
Spectrum planck_spectrum(double temperature_K);

// CIE standard illuminant D65 (relative, 100 at 560 nm) on the grid.
Spectrum cie_d65();

}  // namespace skyband
