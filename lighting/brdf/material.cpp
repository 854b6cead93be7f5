#include "lighting/brdf/material.h"

#include <array>

#include "geometry/core/input_error.h"

namespace skyband {

namespace {

// Piecewise-linear reflectance through a few control points (nm, value), clamped at the ends.
template <std::size_t N>
Spectrum curve(const std::array<double, N>& nm, const std::array<double, N>& value) {
  return resample(std::span<const double>(nm.data(), N), std::span<const double>(value.data(), N));
}

// reference-notes §4.3 [S: pbrt-v4 src/pbrt/util/spectrum.cpp Al_eta, Al_k].
constexpr std::array<double, 8> kAlNm{400, 451, 506, 551, 605, 653, 708, 800};
constexpr std::array<double, 8> kAlN{0.490, 0.620, 0.789, 0.963, 1.22, 1.49, 1.91, 2.80};
constexpr std::array<double, 8> kAlK{4.86, 5.48, 6.15, 6.70, 7.31, 7.82, 8.39, 8.45};

Material make_diffuse(std::string name, std::string provenance, Spectrum rho) {
  Material m;
  m.name = std::move(name);
  m.provenance = std::move(provenance);
  m.diffuse_albedo = rho;
  return m;
}

Material make_dielectric(std::string name, std::string provenance, Spectrum rho, double s, double rough, double n) {
  Material m = make_diffuse(std::move(name), std::move(provenance), rho);
  m.specular_weight = s;
  m.roughness_m = rough;
  m.fresnel_kind = FresnelKind::kDielectric;
  m.dielectric_n = n;
  m.fresnel = FresnelTable::dielectric(n);
  return m;
}

std::vector<Material> make_builtin() {
  std::vector<Material> all;
  all.push_back(make_diffuse("diffuse-wall",
                             "[E] light grey-beige render, Lambertian only (seed Fig. 5a: 'no specular reflection'); "
                             "albedo 0.40-0.55 rising toward red, typical of light cement render.",
                             curve<3>({400, 550, 700}, {0.40, 0.50, 0.55})));
  all.push_back(make_dielectric("painted-wall",
                                "[E] off-white exterior paint: TiO2 white absorbs below ~420 nm (0.30 at 380 nm to 0.80 "
                                "from 460 nm); reference-notes §4.3 ranges for paint: m 0.3-0.5, s 0.02-0.1, n 1.5.",
                                curve<4>({380, 420, 460, 780}, {0.30, 0.60, 0.80, 0.80}), 0.06, 0.4, 1.5));
  all.push_back(make_dielectric("ceramic-tile",
                                "[E] brown glazed tile (seed Fig. 6 tiled building): dark reddish body 0.08-0.30; glaze "
                                "per reference-notes §4.3: m 0.05-0.15 (0.1 used), n 1.5; specular weight 0.25.",
                                curve<4>({400, 500, 600, 700}, {0.08, 0.10, 0.22, 0.30}), 0.25, 0.1, 1.5));
  {
    Material al = make_diffuse("aluminium-panel",
                               "[S] n, k of aluminium from pbrt-v4 (reference-notes §4.3); [E] mill finish m = 0.2 "
                               "(range 0.1-0.3), 10% diffusely scattering weathered layer of albedo 0.6.",
                               Spectrum::constant(0.6));
    al.specular_weight = 0.9;
    al.roughness_m = 0.2;
    al.fresnel_kind = FresnelKind::kConductor;
    al.conductor_n = aluminium_n();
    al.conductor_k = aluminium_k();
    al.fresnel = FresnelTable::conductor(al.conductor_n, al.conductor_k);
    all.push_back(std::move(al));
  }
  all.push_back(make_dielectric("window-glass",
                                "[E] soda-lime float glass n = 1.52 (reference-notes §4.3; BK7 is 1.519 at 542 nm), "
                                "near mirror m = 0.01; the interior seen through it is taken as black (no diffuse term).",
                                Spectrum::constant(0.0), 1.0, 0.01, 1.52));
  all.push_back(make_dielectric("window-frame",
                                "[E] dark bronze anodised aluminium frame: lacquer/oxide film n = 1.6, m = 0.1, specular "
                                "weight 0.4, warm dark body 0.05-0.12.",
                                curve<3>({400, 550, 700}, {0.05, 0.08, 0.12}), 0.4, 0.1, 1.6));
  all.push_back(make_diffuse("ground",
                             "[E] mix of asphalt and concrete paving, Lambertian, albedo 0.10-0.16 (typical urban "
                             "ground 0.1-0.2).",
                             curve<3>({400, 550, 700}, {0.10, 0.13, 0.16})));
  return all;
}

}  // namespace

Spectrum aluminium_n() {
  return curve<8>(kAlNm, kAlN);
}
Spectrum aluminium_k() {
  return curve<8>(kAlNm, kAlK);
}

Spectrum Material::diffuse_brdf() const {
  return diffuse_albedo * ((1.0 - specular_weight) / kPi);
}

Spectrum Material::brdf(const Vec3& n, const Vec3& l, const Vec3& v, bool paper_scale) const {
  MicrofacetCosines c;
  if (!microfacet_cosines(n, l, v, c)) return Spectrum{};
  Spectrum f = diffuse_brdf();
  if (has_specular()) {
    const double lobe = specular_lobe(paper_scale).factor(c);
    Spectrum fr;
    fresnel.eval(c.v_dot_h, fr);
    f += fr * lobe;
  }
  return f;
}

const std::vector<Material>& builtin_materials() {
  static const std::vector<Material> all = make_builtin();
  return all;
}

std::vector<std::string> material_names() {
  std::vector<std::string> names;
  for (const Material& m : builtin_materials()) names.push_back(m.name);
  return names;
}

const Material& find_material(std::string_view name, std::string_view context) {
  for (const Material& m : builtin_materials())
    if (m.name == name) return m;
  std::string known;
  for (const Material& m : builtin_materials()) known += (known.empty() ? "" : ", ") + m.name;
  throw InputError(std::string(context) + ": unknown material '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace skyband
