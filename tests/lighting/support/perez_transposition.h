#pragma once
// Test-only independent model: the Perez 1990 plane-of-array sky diffuse transposition (R. Perez,
// P. Ineichen, R. Seals, J. Michalsky, R. Stewart, Solar Energy 44(5) 271–289 (1990), with its
// "allsitescomposite1990" F1/F2 coefficients), written to reproduce pvlib's
// `irradiance.perez(..., model='allsitescomposite1990')` (pvlib-python, BSD-3-Clause):
//   ε = ((DHI + DNI)/DHI + κ Z³)/(1 + κ Z³), κ = 1.041, Δ = DHI·m/I0, bins as the sky model
//   (ε < 1.065 falls in bin 1);
//   F1 = max(0, f11 + f12 Δ + f13 Z),  F2 = f21 + f22 Δ + f23 Z;
//   a = max(0, cos AOI),  b = max(cos 85°, cos Z);
//   isotropic   = DHI · (1 − F1)(1 + cos β)/2,
//   circumsolar = DHI · F1 a/b,
//   horizon     = DHI · F2 sin β    (kept signed: it is negative for F2 < 0),
//   sky diffuse = max(0, isotropic + circumsolar + horizon).
// β the surface tilt. Angles in degrees; azimuths clockwise from north (180 = south); Z the
// (apparent) sun zenith as passed to pvlib. It is a different model from the Perez 1993 sky
// (lighting/sky/perez_sky.h): the tests compare the two, they do not expect equality.
namespace skyband::test {

struct Perez1990Diffuse {
  double sky_diffuse = 0;  // W·m⁻²
  double isotropic = 0;
  double circumsolar = 0;
  double horizon = 0;
};

// cos of the angle of incidence of the sun on the surface (pvlib `aoi_projection`), unclamped.
double perez1990_aoi_projection(double surface_tilt_deg, double surface_azimuth_deg, double solar_zenith_deg,
                                double solar_azimuth_deg);

// All zero (pvlib's night convention) when the air mass is NaN or DHI is 0; the components are
// zeroed where the clamped total is 0, as in pvlib.
Perez1990Diffuse perez1990_sky_diffuse(double surface_tilt_deg, double surface_azimuth_deg, double dhi_W_m2, double dni_W_m2,
                                       double dni_extra_W_m2, double solar_zenith_deg, double solar_azimuth_deg, double air_mass);

}  // namespace skyband::test
