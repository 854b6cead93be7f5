#include "lighting/support/perez_transposition.h"

#include <algorithm>
#include <cmath>

namespace skyband::test {

namespace {

constexpr double kPiT = 3.14159265358979323846;
constexpr double kDegT = kPiT / 180.0;

// Perez 1990 "all sites composite" coefficients (as in pvlib `_get_perez_coefficients('allsitescomposite1990')`):
// per bin f11, f12, f13, f21, f22, f23.
constexpr double kF[8][6] = {
    {-0.0080, 0.5880, -0.0620, -0.0600, 0.0720, -0.0220}, {0.1300, 0.6830, -0.1510, -0.0190, 0.0660, -0.0290},
    {0.3300, 0.4870, -0.2210, 0.0550, -0.0640, -0.0260},  {0.5680, 0.1870, -0.2950, 0.1090, -0.1520, -0.0140},
    {0.8730, -0.3920, -0.3620, 0.2260, -0.4620, 0.0010},  {1.1320, -1.2370, -0.4120, 0.2880, -0.8230, 0.0560},
    {1.0600, -1.6000, -0.3590, 0.2640, -1.1270, 0.1310},  {0.6780, -0.3270, -0.2500, 0.1560, -1.3770, 0.2510}};

// pvlib's np.digitize on (0, 1.065, 1.23, 1.5, 1.95, 2.8, 4.5, 6.2) minus one.
int bin_of(double eps) {
  constexpr double kEdges[7] = {1.065, 1.23, 1.5, 1.95, 2.8, 4.5, 6.2};
  int b = 0;
  for (double e : kEdges)
    if (eps >= e) ++b;
  return b;
}

}  // namespace

double perez1990_aoi_projection(double tilt, double surface_az, double zen, double sun_az) {
  return std::cos(tilt * kDegT) * std::cos(zen * kDegT) +
         std::sin(tilt * kDegT) * std::sin(zen * kDegT) * std::cos((sun_az - surface_az) * kDegT);
}

Perez1990Diffuse perez1990_sky_diffuse(double tilt, double surface_az, double dhi, double dni, double dni_extra, double zen,
                                       double sun_az, double air_mass) {
  Perez1990Diffuse out;
  if (std::isnan(air_mass) || dhi == 0) return out;
  const double z = zen * kDegT;
  const double kz3 = 1.041 * z * z * z;
  const double delta = dhi * air_mass / dni_extra;
  const double eps = ((dhi + dni) / dhi + kz3) / (1 + kz3);
  const double* f = kF[bin_of(eps)];
  const double F1 = std::max(0.0, f[0] + f[1] * delta + f[2] * z);
  const double F2 = f[3] + f[4] * delta + f[5] * z;
  const double a = std::max(0.0, perez1990_aoi_projection(tilt, surface_az, zen, sun_az));
  const double b = std::max(std::cos(85 * kDegT), std::cos(z));
  out.isotropic = dhi * 0.5 * (1 - F1) * (1 + std::cos(tilt * kDegT));
  out.circumsolar = dhi * F1 * a / b;
  out.horizon = dhi * F2 * std::sin(tilt * kDegT);
  out.sky_diffuse = std::max(0.0, out.isotropic + out.circumsolar + out.horizon);
  if (out.sky_diffuse == 0) out = Perez1990Diffuse{};
  return out;
}

}  // namespace skyband::test
