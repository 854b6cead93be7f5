#include "render/specular_sky_colour.h"

#include <stdexcept>
#include <vector>

namespace skyband {

ColourSpecularSky::ColourSpecularSky(const SkyRadianceGrid& sky, const FresnelTable* fresnel) : fresnel_(fresnel) {
  if (fresnel) {
    factors_ = std::make_shared<const FresnelFactors>(*fresnel);
    rank_ = factors_->rank();
  }
  std::vector<Spectrum> weights;
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < rank_; ++j) weights.push_back(factors_ ? xyz_weights(c) * factors_->v(j) : xyz_weights(c));
  grid_ = sky.project(weights);
}

namespace {
template <int N>
Xyz to_xyz(const ColourChannels<N>& acc) {
  constexpr int R = N / 3;
  Xyz r;
  for (int j = 0; j < R; ++j) {
    r.X += acc.v[static_cast<std::size_t>(j)];
    r.Y += acc.v[static_cast<std::size_t>(R + j)];
    r.Z += acc.v[static_cast<std::size_t>(2 * R + j)];
  }
  return r;
}
}  // namespace

template <int R>
Xyz ColourSpecularSky::integrate(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                                 const SpecularSkyOptions& opt, SpecularSkyStats& stats) const {
  Policy<R> p{this};
  return to_xyz(specular_detail::specular_sky_integral(view, view_dir, lobe, p, opt, stats));
}

// The AVX2 + FMA build: the same source, `flatten` inlining the whole march (the inline and
// template functions of specular_sky.h, fast_exp.h, sky_radiance_grid.h) into this one function
// compiled for the wider instruction set, so no out-of-line copy of a shared inline function
// is ever compiled for AVX2 (which the linker could pick for callers on other processors).
// Functions defined in .cpp files (the per-line and per-point set-up) stay calls to their
// default builds. Only reached when uses_avx2().
#if defined(__GNUC__) && defined(__x86_64__)
#define SKYBAND_AVX2_DISPATCH 1
template <int R>
__attribute__((target("avx2,fma"), flatten)) Xyz ColourSpecularSky::integrate_avx2(const PointVisibilityView& view,
                                                                                   const Vec3& view_dir, const SpecularLobe& lobe,
                                                                                   const SpecularSkyOptions& opt,
                                                                                   SpecularSkyStats& stats) const {
  Policy<R, true> p{this};
  return to_xyz(specular_detail::specular_sky_integral(view, view_dir, lobe, p, opt, stats));
}
#else
#define SKYBAND_AVX2_DISPATCH 0
template <int R>
Xyz ColourSpecularSky::integrate_avx2(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                                      const SpecularSkyOptions& opt, SpecularSkyStats& stats) const {
  return integrate<R>(view, view_dir, lobe, opt, stats);
}
#endif

bool ColourSpecularSky::uses_avx2() {
#if SKYBAND_AVX2_DISPATCH
  static const bool avx2 = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  }();
  return avx2;
#else
  return false;
#endif
}

Xyz ColourSpecularSky::radiance_xyz(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                                    const SpecularSkyOptions& opt, SpecularSkyStats* stats_out) const {
  return dispatch(view, view_dir, lobe, opt, stats_out, uses_avx2());
}

Xyz ColourSpecularSky::radiance_xyz_portable(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                                             const SpecularSkyOptions& opt, SpecularSkyStats* stats_out) const {
  return dispatch(view, view_dir, lobe, opt, stats_out, false);
}

Xyz ColourSpecularSky::dispatch(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                                const SpecularSkyOptions& opt, SpecularSkyStats* stats_out, bool avx2) const {
  if (lobe.fresnel != fresnel_) throw std::logic_error("ColourSpecularSky: lobe with a different Fresnel table");
  SpecularSkyStats stats;
  Xyz r;
  auto run = [&]<int R>() {
    return avx2 ? integrate_avx2<R>(view, view_dir, lobe, opt, stats) : integrate<R>(view, view_dir, lobe, opt, stats);
  };
  switch (rank_) {
    case 1:
      r = run.template operator()<1>();
      break;
    case 2:
      r = run.template operator()<2>();
      break;
    case 3:
      r = run.template operator()<3>();
      break;
    default:
      r = run.template operator()<4>();
      break;
  }
  if (stats_out) *stats_out = stats;
  return r;
}

}  // namespace skyband
