#pragma once
// Direct sunlight reflected toward the viewer (method.md §1; reference-notes §1.6):
//     I_sun(λ) = f(s, V; λ)·E_dn(λ)·max(0, N·s)·vis_sun
// with f the material's full BRDF (material.h: (1 − w_s)·ρ_d/π + w_s·f_s), E_dn the direct-normal
// spectral irradiance of the sun (W·m⁻²·nm⁻¹) and s the unit direction toward the sun. The sun is
// a parallel source; whether it is blocked is the geometry core's job (`sun_visible`).
// Result: spectral radiance, W·m⁻²·sr⁻¹·nm⁻¹.
#include "geometry/core/vec3.h"
#include "lighting/brdf/material.h"
#include "lighting/spectrum/spectrum.h"

namespace skyband {

// Diffuse part only: E_dn·max(0, N·s)·(1 − w_s)·ρ_d/π.
inline Spectrum sun_diffuse_radiance(const Material& m, const Vec3& n, const Vec3& sun_dir, const Spectrum& e_dn_W_m2_nm,
                                     bool sun_visible) {
  const double cos_i = n.dot(sun_dir);
  if (!sun_visible || cos_i <= 0.0) return Spectrum{};
  return m.diffuse_brdf() * e_dn_W_m2_nm * cos_i;
}

// Specular part only: w_s·f_s(s, V)·E_dn·(N·s).
inline Spectrum sun_specular_radiance(const Material& m, const Vec3& n, const Vec3& sun_dir, const Vec3& view_dir,
                                      const Spectrum& e_dn_W_m2_nm, bool sun_visible, bool paper_scale = false) {
  MicrofacetCosines c;
  if (!sun_visible || !m.has_specular() || !microfacet_cosines(n, sun_dir, view_dir, c)) return Spectrum{};
  Spectrum f;
  m.fresnel.eval(c.v_dot_h, f);
  return f * e_dn_W_m2_nm * (m.specular_lobe(paper_scale).factor(c) * c.n_dot_l);
}

// Both parts: the sun's whole contribution to the radiance toward V. A view from behind the
// surface (N·V ≤ 0) sees nothing reflected.
inline Spectrum sun_reflected_radiance(const Material& m, const Vec3& n, const Vec3& sun_dir, const Vec3& view_dir,
                                       const Spectrum& e_dn_W_m2_nm, bool sun_visible, bool paper_scale = false) {
  if (n.dot(view_dir) <= 0.0) return Spectrum{};
  return sun_diffuse_radiance(m, n, sun_dir, e_dn_W_m2_nm, sun_visible) +
         sun_specular_radiance(m, n, sun_dir, view_dir, e_dn_W_m2_nm, sun_visible, paper_scale);
}

}  // namespace skyband
