#include "lighting/specular_sky_colour.h"

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

template <int R>
Xyz ColourSpecularSky::integrate(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                                 const SpecularSkyOptions& opt, SpecularSkyStats& stats) const {
  Policy<R> p{this};
  const auto acc = specular_detail::specular_sky_integral(view, view_dir, lobe, p, opt, stats);
  Xyz r;
  for (int j = 0; j < R; ++j) {
    r.X += acc.v[static_cast<std::size_t>(j)];
    r.Y += acc.v[static_cast<std::size_t>(R + j)];
    r.Z += acc.v[static_cast<std::size_t>(2 * R + j)];
  }
  return r;
}

Xyz ColourSpecularSky::radiance_xyz(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe,
                                    const SpecularSkyOptions& opt, SpecularSkyStats* stats_out) const {
  if (lobe.fresnel != fresnel_) throw std::logic_error("ColourSpecularSky: lobe with a different Fresnel table");
  SpecularSkyStats stats;
  Xyz r;
  switch (rank_) {
    case 1: r = integrate<1>(view, view_dir, lobe, opt, stats); break;
    case 2: r = integrate<2>(view, view_dir, lobe, opt, stats); break;
    case 3: r = integrate<3>(view, view_dir, lobe, opt, stats); break;
    default: r = integrate<4>(view, view_dir, lobe, opt, stats); break;
  }
  if (stats_out) *stats_out = stats;
  return r;
}

}  // namespace skyband
