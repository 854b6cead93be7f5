#include "lighting/sun/sun.h"

#include <algorithm>

namespace skyband {

namespace {
constexpr double kDeg = kPi / 180.0;
constexpr double kArcmin = kPi / (180.0 * 60.0);

double saemundsson_arcmin(double h_deg) {
  return 1.02 / std::tan((h_deg + 10.3 / (h_deg + 5.11)) * kDeg);
}
double bennett_arcmin(double h_deg) {
  return 1.0 / std::tan((h_deg + 7.31 / (h_deg + 4.4)) * kDeg);
}
}  // namespace

double altitude_of(const Vec3& dir) {
  return std::asin(std::clamp(dir.z(), -1.0, 1.0));
}

double azimuth_of(const Vec3& dir) {
  const double az = std::atan2(dir.x(), dir.y());
  return az < 0 ? az + 2.0 * kPi : az;
}

double refraction_rad(double true_altitude_rad) {
  const double h = std::clamp(true_altitude_rad / kDeg, -1.0, 90.0);
  return (saemundsson_arcmin(h) - saemundsson_arcmin(90.0)) * kArcmin;
}

double refraction_from_apparent_rad(double apparent_altitude_rad) {
  const double h = std::clamp(apparent_altitude_rad / kDeg, -1.0, 90.0);
  return (bennett_arcmin(h) - bennett_arcmin(90.0)) * kArcmin;
}

}  // namespace skyband
