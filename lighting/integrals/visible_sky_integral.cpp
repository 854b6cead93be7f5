#include "lighting/integrals/visible_sky_integral.h"

#include "geometry/bands/sky_integral.h"
#include "geometry/visibility/sky_visibility.h"

namespace skyband {

void sky_channels(const VisibleSky& sky, const SkyTables& tables, double max_step_rad, std::vector<SkyFanTriangle>& fan,
                  double out[2]) {
  if (!sky.exact()) {
    integrate_irradiance_channels<2>(
        *sky.bands, [&](const Vec3& d, double* c) { tables.grid.lookup_unit_n<2>(d, c); }, out, max_step_rad);
    return;
  }
  sky.fan(fan);
  tables.columns.integrate_fan(fan, sky.normal, out, 0.25 * max_step_rad);
}

OpenSky::OpenSky(const SkyTables& tables, const VisibilityOptions& visibility, double max_step_rad) {
  const Scene empty{TriangleSoup{}};
  const QueryPoint up{Vec3(0, 0, 0), Vec3(0, 0, 1)};
  std::vector<SkyFanTriangle> fan;
  SkyVisibility exact_sky(empty, visibility, SkyFactorsMethod::exact);
  sky_channels(exact_sky.compute(up), tables, max_step_rad, fan, exact);
  SkyVisibility band_sky(empty, visibility, SkyFactorsMethod::bands);
  sky_channels(band_sky.compute(up), tables, max_step_rad, fan, bands);
}

}  // namespace skyband
