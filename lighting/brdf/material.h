#pragma once
// Named surface materials of the paper's figures (seed Figs. 5–6; method.md §7): spectral diffuse
// albedo plus a Cook–Torrance specular lobe (method.md §5, reference-notes §4.2–4.3).
//
// Reflection model (Cook & Torrance 1982, R = s·R_s + d·R_d with d = 1 − s):
//     f(L, V; λ) = (1 − s)·ρ_d(λ)/π + s·F(λ, V·H)·D_n G / (4 (N·L)(N·V))          [sr⁻¹]
// i.e. the diffuse term is weighted by (1 − specular weight), NOT by (1 − F). With F ≤ 1 and the
// white-furnace albedo of the specular lobe ≤ 1 (cook_torrance_test), the total directional
// albedo is ≤ s + (1 − s)·max ρ_d ≤ 1: energy conserving.
//
// Names: diffuse-wall, painted-wall, ceramic-tile, aluminium-panel, window-glass, window-frame,
// ground. Every number is an engineering estimate [E] unless its `provenance` names a source.
#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/vec3.h"
#include "lighting/brdf/cook_torrance.h"
#include "lighting/brdf/fresnel.h"
#include "lighting/spectrum/spectrum.h"

namespace skyband {

enum class FresnelKind { kNone, kDielectric, kConductor };

struct Material {
  std::string name;
  std::string provenance;        // one sentence: where the numbers come from
  Spectrum diffuse_albedo;       // ρ_d(λ), dimensionless
  double specular_weight = 0.0;  // s ∈ [0, 1]; the diffuse weight is 1 − s
  double roughness_m = 0.3;      // Beckmann RMS slope m
  FresnelKind fresnel_kind = FresnelKind::kNone;
  double dielectric_n = 1.5;                   // real refractive index (kDielectric)
  Spectrum conductor_n, conductor_k;           // complex index n + ik on the grid (kConductor)
  FresnelTable fresnel = FresnelTable::one();  // F(λ, cos θ) built from the above

  bool has_specular() const { return specular_weight > 0.0; }
  // (1 − s)·ρ_d/π, sr⁻¹.
  Spectrum diffuse_brdf() const;
  // Full f(L, V) for unit N, L, V (world frame), sr⁻¹; zero when L or V is below the surface.
  Spectrum brdf(const Vec3& n, const Vec3& l, const Vec3& v, bool paper_scale = false) const;
  // The specular lobe for the sky integrals (points into this material's Fresnel table).
  SpecularLobe specular_lobe(bool paper_scale = false) const {
    return SpecularLobe{roughness_m, specular_weight, &fresnel, paper_scale};
  }
};

// All built-in materials, in a fixed order.
const std::vector<Material>& builtin_materials();
std::vector<std::string> material_names();

// Lookup by name. Unknown name → InputError "<context>: unknown material '<name>' (known: ...)",
// with `context` naming where the name came from (a flag, a file and line).
const Material& find_material(std::string_view name, std::string_view context = "material");

// Aluminium complex refractive index on the 41-sample grid: pbrt-v4 Al_eta/Al_k samples
// (reference-notes §4.3, 400–800 nm) interpolated linearly; 380–399 nm clamp to the 400 nm value.
Spectrum aluminium_n();
Spectrum aluminium_k();

}  // namespace skyband
