#pragma once
// Cook–Torrance specular BRDF (seed appendix; method.md §5; reference-notes §4.2).
//
// skyband implements the energy-consistent microfacet form
//     f_s(L, V) = F(V·H) · D_n(N·H) · G / (4 (N·L)(N·V))        [sr⁻¹]
// with D_n the normalised Beckmann distribution (beckmann.h), so that reflected radiance is
// L_o = ∫ f_s L_i (N·L) dω and the directional albedo ∫ f_s (N·L) dω ≤ 1 when F ≤ 1.
//
// The seed (and Cook & Torrance 1982) write R_s = (F/π)·D_CT·G/((N·L)(N·V)) with D_CT = π·D_n,
// i.e. R_s = 4·f_s. `paper_scale = true` multiplies by kPaperScale = 4 to reproduce the paper's
// numbers literally (its albedo then reaches ≈ 4: not energy conserving, use only to compare).
//
// The Fresnel factor is supplied by the caller (a scalar or a spectrum): everything here is the
// Fresnel-free, wavelength-independent part.
#include "geometry/core/vec3.h"
#include "lighting/brdf/beckmann.h"
#include "lighting/brdf/fresnel.h"
#include "lighting/integrals/fast_exp.h"

namespace skyband {

inline constexpr double kPaperScale = 4.0;

// Cosines that the Cook–Torrance terms depend on, for unit N, L, V.
struct MicrofacetCosines {
  double n_dot_l = 0, n_dot_v = 0, n_dot_h = 0, v_dot_h = 0;
};

// Computes the cosines with H = normalize(L + V). Returns false (and leaves a zero BRDF) when L
// or V is at or below the surface or L = −V. (Inline: the sky integrals call it per direction.)
inline bool microfacet_cosines(const Vec3& n, const Vec3& l, const Vec3& v, MicrofacetCosines& c) {
  c.n_dot_l = n.dot(l);
  c.n_dot_v = n.dot(v);
  if (c.n_dot_l <= 0.0 || c.n_dot_v <= 0.0) return false;
  const Vec3 sum = l + v;
  const double len = sum.norm();
  if (!(len > 0.0)) return false;
  c.n_dot_h = n.dot(sum) / len;
  c.v_dot_h = v.dot(sum) / len;
  return true;
}

// D_n·G / (4 (N·L)(N·V)) — f_s without F, in sr⁻¹ (times kPaperScale if paper_scale), with
// `exp_neg(x)` = e^{−x} in the Beckmann factor.
template <class ExpNeg>
inline double cook_torrance_lobe_with(const MicrofacetCosines& c, double roughness_m, bool paper_scale, ExpNeg&& exp_neg) {
  if (c.n_dot_l <= 0.0 || c.n_dot_v <= 0.0) return 0.0;
  const double d = beckmann_d_with(c.n_dot_h, roughness_m, exp_neg);
  const double g = cook_torrance_g(c.n_dot_h, c.n_dot_v, c.n_dot_l, c.v_dot_h);
  const double fs = d * g / (4.0 * c.n_dot_l * c.n_dot_v);
  return paper_scale ? kPaperScale * fs : fs;
}

inline double cook_torrance_lobe(const MicrofacetCosines& c, double roughness_m, bool paper_scale = false) {
  return cook_torrance_lobe_with(c, roughness_m, paper_scale, [](double x) { return std::exp(-x); });
}

// f_s(L, V) for a wavelength-independent Fresnel factor `fresnel` (sr⁻¹).
double cook_torrance_fs(const Vec3& n, const Vec3& l, const Vec3& v, double roughness_m, double fresnel,
                        bool paper_scale = false);

// White-furnace directional albedo ρ(θ_v) = ∫_{N·L>0} f_s (N·L) dω with F = 1, by quadrature in
// half-vector space: with u = tan²θ_h/m² and w = 1 − e^{−u}, D_n cos θ_h dω_h = dw dφ/2π and
// dω_l = 4(V·H) dω_h, so ρ = ∫_0^1 dw ∫_0^{2π} dφ/2π · G·(V·H)/((N·V)(N·H)) · [N·L > 0].
// Composite midpoint rule on `nodes` × `nodes` cells; the integrand is bounded with a jump where
// L crosses the horizon, so the error falls like 1/nodes (≈ 3·10⁻⁴ at nodes = 600 for the cases
// in cook_torrance_test).
double cook_torrance_albedo(double roughness_m, double theta_v_rad, int nodes = 600, bool paper_scale = false);

// What the sky integrals need of a material's specular term s·f_s: roughness, weight s, spectral
// Fresnel table (not owned; must outlive the lobe) and the scale convention.
struct SpecularLobe {
  double roughness_m = 0.3;
  double weight = 1.0;                    // s in R = s·R_s + d·R_d (Cook & Torrance 1982)
  const FresnelTable* fresnel = nullptr;  // nullptr: F = 1 (white furnace)
  bool paper_scale = false;

  // s·(D_n G / 4(N·L)(N·V))·(4 if paper_scale): the wavelength-independent factor, sr⁻¹.
  double factor(const MicrofacetCosines& c) const { return weight * cook_torrance_lobe(c, roughness_m, paper_scale); }
  // The same with the tabulated e^{−x} (fast_exp.h, relative difference < 10⁻¹⁰): the sky march.
  double factor_fast(const MicrofacetCosines& c) const {
    return weight * cook_torrance_lobe_with(c, roughness_m, paper_scale, [](double x) { return exp_neg(x); });
  }
};

}  // namespace skyband
