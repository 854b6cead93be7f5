#include "geometry/horizon/horizon_profile.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "geometry/core/input_error.h"
#include "geometry/visibility/sky_visibility.h"

namespace skyband {

std::size_t horizon_azimuth_count(double step_deg) {
  if (!(step_deg >= kMinHorizonStepDeg) || !(step_deg <= 360)) {
    char value[32];
    std::snprintf(value, sizeof value, "%.6g", step_deg);
    throw InputError(std::string("--horizon-step ") + value + ": must be between 0.01 and 360 degrees");
  }
  std::size_t m = 0;
  while (double(m) * step_deg < 360.0) ++m;
  return m;
}

void for_each_horizon_profile(const Scene& scene, std::span<const QueryPoint> points, const VisibilityOptions& options,
                              double step_deg, int threads, const std::function<void(std::size_t, std::size_t)>& progress,
                              const std::function<void(std::size_t, std::size_t, std::span<const double>)>& consume) {
  const std::size_t m = horizon_azimuth_count(step_deg);
  std::vector<double> wx(m), wy(m);
  for (std::size_t k = 0; k < m; ++k) {
    const double az = double(k) * step_deg * kPi / 180;  // clockwise from north: x east, y north
    wx[k] = std::sin(az), wy[k] = std::cos(az);
  }
  // Points per block: at most 4096, and at most ~2²² elevations (32 MB) however fine the step.
  const std::size_t kBlock = std::clamp<std::size_t>((std::size_t(1) << 22) / m, 1, 4096);
  std::vector<QueryPoint> up;
  std::vector<double> elevations;
  for (std::size_t first = 0; first < points.size(); first += kBlock) {
    const std::size_t count = std::min(kBlock, points.size() - first);
    up.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const QueryPoint& q = points[first + i];
      up[i] = {q.position + options.surface_offset_m * q.normal, Vec3(0, 0, 1)};
    }
    VisibilityOptions at_point = options;
    at_point.surface_offset_m = 0;  // the offset is applied above, along the point's own normal
    elevations.assign(count * m, 0.0);
    for_each_visible_sky(scene, up, at_point, SkyFactorsMethod::exact, threads, {}, true,
                         [&](std::size_t i, const VisibleSky& sky, SkyVisibility&) {
                           for (std::size_t k = 0; k < m; ++k)
                             elevations[i * m + k] = sky.horizon_elevation(wx[k], wy[k]) * 180 / kPi;
                         });
    consume(first, count, elevations);
    if (progress) progress(first + count, points.size());
  }
}

}  // namespace skyband
