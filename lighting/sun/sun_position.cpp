#include "lighting/sun/sun_position.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <span>

#include "geometry/core/input_error.h"
#include "lighting/sun/sun.h"

namespace skyband {

namespace {

// ---------------------------------------------------------------------------------------------
// Reda & Andreas (2004), Table A4.2: Earth periodic terms (A, B, C): term = A·cos(B + C·JME).
// L and B in 1e-8 rad, R in 1e-8 AU.
struct PeriodicTerm {
  double a, b, c;
};

// The SPA tables keep the layout of their source, several terms a line:
// clang-format off
constexpr PeriodicTerm kL0[] = {
    {175347046.0, 0, 0}, {3341656.0, 4.6692568, 6283.07585}, {34894.0, 4.6261, 12566.1517},
    {3497.0, 2.7441, 5753.3849}, {3418.0, 2.8289, 3.5231}, {3136.0, 3.6277, 77713.7715},
    {2676.0, 4.4181, 7860.4194}, {2343.0, 6.1352, 3930.2097}, {1324.0, 0.7425, 11506.7698},
    {1273.0, 2.0371, 529.691}, {1199.0, 1.1096, 1577.3435}, {990, 5.233, 5884.927},
    {902, 2.045, 26.298}, {857, 3.508, 398.149}, {780, 1.179, 5223.694}, {753, 2.533, 5507.553},
    {505, 4.583, 18849.228}, {492, 4.205, 775.523}, {357, 2.92, 0.067}, {317, 5.849, 11790.629},
    {284, 1.899, 796.298}, {271, 0.315, 10977.079}, {243, 0.345, 5486.778}, {206, 4.806, 2544.314},
    {205, 1.869, 5573.143}, {202, 2.458, 6069.777}, {156, 0.833, 213.299}, {132, 3.411, 2942.463},
    {126, 1.083, 20.775}, {115, 0.645, 0.98}, {103, 0.636, 4694.003}, {102, 0.976, 15720.839},
    {102, 4.267, 7.114}, {99, 6.21, 2146.17}, {98, 0.68, 155.42}, {86, 5.98, 161000.69},
    {85, 1.3, 6275.96}, {85, 3.67, 71430.7}, {80, 1.81, 17260.15}, {79, 3.04, 12036.46},
    {75, 1.76, 5088.63}, {74, 3.5, 3154.69}, {74, 4.68, 801.82}, {70, 0.83, 9437.76},
    {62, 3.98, 8827.39}, {61, 1.82, 7084.9}, {57, 2.78, 6286.6}, {56, 4.39, 14143.5},
    {56, 3.47, 6279.55}, {52, 0.19, 12139.55}, {52, 1.33, 1748.02}, {51, 0.28, 5856.48},
    {49, 0.49, 1194.45}, {41, 5.37, 8429.24}, {41, 2.4, 19651.05}, {39, 6.17, 10447.39},
    {37, 6.04, 10213.29}, {37, 2.57, 1059.38}, {36, 1.71, 2352.87}, {36, 1.78, 6812.77},
    {33, 0.59, 17789.85}, {30, 0.44, 83996.85}, {30, 2.74, 1349.87}, {25, 3.16, 4690.48}};
constexpr PeriodicTerm kL1[] = {
    {628331966747.0, 0, 0}, {206059.0, 2.678235, 6283.07585}, {4303.0, 2.6351, 12566.1517},
    {425.0, 1.59, 3.523}, {119.0, 5.796, 26.298}, {109.0, 2.966, 1577.344}, {93, 2.59, 18849.23},
    {72, 1.14, 529.69}, {68, 1.87, 398.15}, {67, 4.41, 5507.55}, {59, 2.89, 5223.69},
    {56, 2.17, 155.42}, {45, 0.4, 796.3}, {36, 0.47, 775.52}, {29, 2.65, 7.11}, {21, 5.34, 0.98},
    {19, 1.85, 5486.78}, {19, 4.97, 213.3}, {17, 2.99, 6275.96}, {16, 0.03, 2544.31},
    {16, 1.43, 2146.17}, {15, 1.21, 10977.08}, {12, 2.83, 1748.02}, {12, 3.26, 5088.63},
    {12, 5.27, 1194.45}, {12, 2.08, 4694}, {11, 0.77, 553.57}, {10, 1.3, 6286.6},
    {10, 4.24, 1349.87}, {9, 2.7, 242.73}, {9, 5.64, 951.72}, {8, 5.3, 2352.87},
    {6, 2.65, 9437.76}, {6, 4.67, 4690.48}};
constexpr PeriodicTerm kL2[] = {
    {52919.0, 0, 0}, {8720.0, 1.0721, 6283.0758}, {309.0, 0.867, 12566.152}, {27, 0.05, 3.52},
    {16, 5.19, 26.3}, {16, 3.68, 155.42}, {10, 0.76, 18849.23}, {9, 2.06, 77713.77},
    {7, 0.83, 775.52}, {5, 4.66, 1577.34}, {4, 1.03, 7.11}, {4, 3.44, 5573.14}, {3, 5.14, 796.3},
    {3, 6.05, 5507.55}, {3, 1.19, 242.73}, {3, 6.12, 529.69}, {3, 0.31, 398.15},
    {3, 2.28, 553.57}, {2, 4.38, 5223.69}, {2, 3.75, 0.98}};
constexpr PeriodicTerm kL3[] = {{289.0, 5.844, 6283.076}, {35, 0, 0}, {17, 5.49, 12566.15},
                                {3, 5.2, 155.42}, {1, 4.72, 3.52}, {1, 5.3, 18849.23},
                                {1, 5.97, 242.73}};
constexpr PeriodicTerm kL4[] = {{114.0, 3.142, 0}, {8, 4.13, 6283.08}, {1, 3.84, 12566.15}};
constexpr PeriodicTerm kL5[] = {{1, 3.14, 0}};

constexpr PeriodicTerm kB0[] = {{280.0, 3.199, 84334.662}, {102.0, 5.422, 5507.553},
                                {80, 3.88, 5223.69}, {44, 3.7, 2352.87}, {32, 4, 1577.34}};
constexpr PeriodicTerm kB1[] = {{9, 3.9, 5507.55}, {6, 1.73, 5223.69}};

constexpr PeriodicTerm kR0[] = {
    {100013989.0, 0, 0}, {1670700.0, 3.0984635, 6283.07585}, {13956.0, 3.05525, 12566.1517},
    {3084.0, 5.1985, 77713.7715}, {1628.0, 1.1739, 5753.3849}, {1576.0, 2.8469, 7860.4194},
    {925.0, 5.453, 11506.77}, {542.0, 4.564, 3930.21}, {472.0, 3.661, 5884.927},
    {346.0, 0.964, 5507.553}, {329.0, 5.9, 5223.694}, {307.0, 0.299, 5573.143},
    {243.0, 4.273, 11790.629}, {212.0, 5.847, 1577.344}, {186.0, 5.022, 10977.079},
    {175.0, 3.012, 18849.228}, {110.0, 5.055, 5486.778}, {98, 0.89, 6069.78}, {86, 5.69, 15720.84},
    {86, 1.27, 161000.69}, {65, 0.27, 17260.15}, {63, 0.92, 529.69}, {57, 2.01, 83996.85},
    {56, 5.24, 71430.7}, {49, 3.25, 2544.31}, {47, 2.58, 775.52}, {45, 5.54, 9437.76},
    {43, 6.01, 6275.96}, {39, 5.36, 4694}, {38, 2.39, 8827.39}, {37, 0.83, 19651.05},
    {37, 4.9, 12139.55}, {36, 1.67, 12036.46}, {35, 1.84, 2942.46}, {33, 0.24, 7084.9},
    {32, 0.18, 5088.63}, {32, 1.78, 398.15}, {28, 1.21, 6286.6}, {28, 1.9, 6279.55},
    {26, 4.59, 10447.39}};
constexpr PeriodicTerm kR1[] = {{103019.0, 1.10749, 6283.07585}, {1721.0, 1.0644, 12566.1517},
                                {702.0, 3.142, 0}, {32, 1.02, 18849.23}, {31, 2.84, 5507.55},
                                {25, 1.32, 5223.69}, {18, 1.42, 1577.34}, {10, 5.91, 10977.08},
                                {9, 1.42, 6275.96}, {9, 0.27, 5486.78}};
constexpr PeriodicTerm kR2[] = {{4359.0, 5.7846, 6283.0758}, {124.0, 5.579, 12566.152},
                                {12, 3.14, 0}, {9, 3.63, 77713.77}, {6, 1.87, 5573.14},
                                {3, 5.47, 18849.23}};
constexpr PeriodicTerm kR3[] = {{145.0, 4.273, 6283.076}, {7, 3.92, 12566.15}};
constexpr PeriodicTerm kR4[] = {{4, 2.56, 6283.08}};

// Table A4.3: nutation in longitude and obliquity. Multipliers of (X0 … X4) and coefficients
// (a, b, c, d): Δψ += (a + b·JCE)·sin(ΣXY), Δε += (c + d·JCE)·cos(ΣXY), in 0.0001″.
struct NutationTerm {
  int y[5];
  double a, b, c, d;
};
constexpr NutationTerm kNutation[] = {
    {{0, 0, 0, 0, 1}, -171996, -174.2, 92025, 8.9}, {{-2, 0, 0, 2, 2}, -13187, -1.6, 5736, -3.1},
    {{0, 0, 0, 2, 2}, -2274, -0.2, 977, -0.5},      {{0, 0, 0, 0, 2}, 2062, 0.2, -895, 0.5},
    {{0, 1, 0, 0, 0}, 1426, -3.4, 54, -0.1},        {{0, 0, 1, 0, 0}, 712, 0.1, -7, 0},
    {{-2, 1, 0, 2, 2}, -517, 1.2, 224, -0.6},       {{0, 0, 0, 2, 1}, -386, -0.4, 200, 0},
    {{0, 0, 1, 2, 2}, -301, 0, 129, -0.1},          {{-2, -1, 0, 2, 2}, 217, -0.5, -95, 0.3},
    {{-2, 0, 1, 0, 0}, -158, 0, 0, 0},              {{-2, 0, 0, 2, 1}, 129, 0.1, -70, 0},
    {{0, 0, -1, 2, 2}, 123, 0, -53, 0},             {{2, 0, 0, 0, 0}, 63, 0, 0, 0},
    {{0, 0, 1, 0, 1}, 63, 0.1, -33, 0},             {{2, 0, -1, 2, 2}, -59, 0, 26, 0},
    {{0, 0, -1, 0, 1}, -58, -0.1, 32, 0},           {{0, 0, 1, 2, 1}, -51, 0, 27, 0},
    {{-2, 0, 2, 0, 0}, 48, 0, 0, 0},                {{0, 0, -2, 2, 1}, 46, 0, -24, 0},
    {{2, 0, 0, 2, 2}, -38, 0, 16, 0},               {{0, 0, 2, 2, 2}, -31, 0, 13, 0},
    {{0, 0, 2, 0, 0}, 29, 0, 0, 0},                 {{-2, 0, 1, 2, 2}, 29, 0, -12, 0},
    {{0, 0, 0, 2, 0}, 26, 0, 0, 0},                 {{-2, 0, 0, 2, 0}, -22, 0, 0, 0},
    {{0, 0, -1, 2, 1}, 21, 0, -10, 0},              {{0, 2, 0, 0, 0}, 17, -0.1, 0, 0},
    {{2, 0, -1, 0, 1}, 16, 0, -8, 0},               {{-2, 2, 0, 2, 2}, -16, 0.1, 7, 0},
    {{0, 1, 0, 0, 1}, -15, 0, 9, 0},                {{-2, 0, 1, 0, 1}, -13, 0, 7, 0},
    {{0, -1, 0, 0, 1}, -12, 0, 6, 0},               {{0, 0, 2, -2, 0}, 11, 0, 0, 0},
    {{2, 0, -1, 2, 1}, -10, 0, 5, 0},               {{2, 0, 1, 2, 2}, -8, 0, 3, 0},
    {{0, 1, 0, 2, 2}, 7, 0, -3, 0},                 {{-2, 1, 1, 0, 0}, -7, 0, 0, 0},
    {{0, -1, 0, 2, 2}, -7, 0, 3, 0},                {{2, 0, 0, 2, 1}, -7, 0, 3, 0},
    {{2, 0, 1, 0, 0}, 6, 0, 0, 0},                  {{-2, 0, 2, 2, 2}, 6, 0, -3, 0},
    {{-2, 0, 1, 2, 1}, 6, 0, -3, 0},                {{2, 0, -2, 0, 1}, -6, 0, 3, 0},
    {{2, 0, 0, 0, 1}, -6, 0, 3, 0},                 {{0, -1, 1, 0, 0}, 5, 0, 0, 0},
    {{-2, -1, 0, 2, 1}, -5, 0, 3, 0},               {{-2, 0, 0, 0, 1}, -5, 0, 3, 0},
    {{0, 0, 2, 2, 1}, -5, 0, 3, 0},                 {{-2, 0, 2, 0, 1}, 4, 0, 0, 0},
    {{-2, 1, 0, 2, 1}, 4, 0, 0, 0},                 {{0, 0, 1, -2, 0}, 4, 0, 0, 0},
    {{-1, 0, 1, 0, 0}, -4, 0, 0, 0},                {{-2, 1, 0, 0, 0}, -4, 0, 0, 0},
    {{1, 0, 0, 0, 0}, -4, 0, 0, 0},                 {{0, 0, 1, 2, 0}, 3, 0, 0, 0},
    {{0, 0, -2, 2, 2}, -3, 0, 0, 0},                {{-1, -1, 1, 0, 0}, -3, 0, 0, 0},
    {{0, 1, 1, 0, 0}, -3, 0, 0, 0},                 {{0, -1, 1, 2, 2}, -3, 0, 0, 0},
    {{2, -1, -1, 2, 2}, -3, 0, 0, 0},               {{0, 0, 3, 2, 2}, -3, 0, 0, 0},
    {{2, -1, 0, 2, 2}, -3, 0, 0, 0}};
// clang-format on
static_assert(std::size(kNutation) == 63);
static_assert(std::size(kL0) == 64 && std::size(kL1) == 34 && std::size(kL2) == 20);
static_assert(std::size(kR0) == 40 && std::size(kR1) == 10 && std::size(kR2) == 6);

constexpr double kDeg = kPi / 180.0;

double limit_degrees(double d) {
  d = std::fmod(d, 360.0);
  return d < 0 ? d + 360.0 : d;
}

// Σ A·cos(B + C·JME) (eq. 9).
double periodic_sum(std::span<const PeriodicTerm> terms, double jme) {
  double s = 0;
  for (const auto& t : terms) s += t.a * std::cos(t.b + t.c * jme);
  return s;
}

// Σ_i X_i·JME^i / 1e8 (eq. 11) for a series X0, X1, ….
double earth_value(std::span<const std::span<const PeriodicTerm>> series, double jme) {
  double s = 0, p = 1;
  for (const auto& terms : series) {
    s += periodic_sum(terms, jme) * p;
    p *= jme;
  }
  return s / 1e8;
}

double third_order(double a, double b, double c, double d, double x) {
  return a + x * (b + x * (c + x * d));
}

[[noreturn]] void bad(const std::string& field, double value, const std::string& why) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", value);
  throw InputError("sun position: " + field + " = " + buf + " " + why);
}

bool is_leap(int y) {
  return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
}
int days_in_month(int y, int m) {
  static constexpr int d[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return m == 2 && is_leap(y) ? 29 : d[m - 1];
}

}  // namespace

double julian_day(const LocalDateTime& t) {
  // SPA eq. 4; the day D carries the UT fraction of day.
  int y = t.year, m = t.month;
  const double ut_hours = t.hour - t.utc_offset_hours + (t.minute + t.second / 60.0) / 60.0;
  const double d = t.day + ut_hours / 24.0;
  if (m < 3) {
    y -= 1;
    m += 12;
  }
  double jd = std::trunc(365.25 * (y + 4716.0)) + std::trunc(30.6001 * (m + 1)) + d - 1524.5;
  if (jd > 2299160.0) {
    const double a = std::trunc(y / 100.0);
    jd += 2 - a + std::trunc(a / 4);
  }
  return jd;
}

SpaResult sun_position_spa(const SpaInput& in) {
  // NaN is tested first (std::isnan): an ordered comparison with a NaN raises FE_INVALID.
  const auto within = [](double x, double lo, double hi) { return !std::isnan(x) && x >= lo && x <= hi; };
  if (!within(in.latitude_deg, -90, 90)) bad("latitude_deg", in.latitude_deg, "is outside [-90, 90]");
  if (!within(in.longitude_deg, -180, 180)) bad("longitude_deg", in.longitude_deg, "is outside [-180, 180]");
  if (!within(in.elevation_m, -6500000, std::numeric_limits<double>::max()))
    bad("elevation_m", in.elevation_m, "is below -6500000 m");
  if (in.time.year < -2000 || in.time.year > 6000) bad("year", in.time.year, "is outside the SPA's range [-2000, 6000]");
  if (!within(in.pressure_mbar, 0, 5000) || in.pressure_mbar == 0) bad("pressure_mbar", in.pressure_mbar, "is outside (0, 5000]");
  if (!within(in.temperature_C, -273, 6000) || in.temperature_C == -273)
    bad("temperature_C", in.temperature_C, "is outside (-273, 6000]");
  if (!within(in.delta_t_s, -8000, 8000)) bad("delta_t_s", in.delta_t_s, "is outside [-8000, 8000]");
  if (!within(in.atmos_refraction_deg, -5, 5)) bad("atmos_refraction_deg", in.atmos_refraction_deg, "is outside [-5, 5]");
  if (!within(in.time.utc_offset_hours, -18, 18)) bad("utc_offset_hours", in.time.utc_offset_hours, "is outside [-18, 18]");

  SpaResult r;
  // 3.1 Julian day, century and millennium (eqs. 4–8).
  const double jd = julian_day(in.time);
  const double jde = jd + in.delta_t_s / 86400.0;
  const double jc = (jd - 2451545.0) / 36525.0;
  const double jce = (jde - 2451545.0) / 36525.0;
  const double jme = jce / 10.0;
  r.julian_day = jd;

  // 3.2 Earth heliocentric longitude, latitude, radius (eqs. 9–14).
  const std::span<const PeriodicTerm> l_series[] = {kL0, kL1, kL2, kL3, kL4, kL5};
  const std::span<const PeriodicTerm> b_series[] = {kB0, kB1};
  const std::span<const PeriodicTerm> r_series[] = {kR0, kR1, kR2, kR3, kR4};
  const double L = limit_degrees(earth_value(l_series, jme) / kDeg);
  const double B = earth_value(b_series, jme) / kDeg;
  const double R = earth_value(r_series, jme);
  r.heliocentric_longitude_deg = L;
  r.heliocentric_latitude_deg = B;
  r.earth_radius_au = R;

  // 3.3 Geocentric longitude and latitude (eqs. 13–14).
  const double theta = limit_degrees(L + 180.0);
  const double beta = -B;

  // 3.4 Nutation (eqs. 15–23).
  const double x[5] = {third_order(297.85036, 445267.111480, -0.0019142, 1.0 / 189474.0, jce),  // X0 elongation of the Moon
                       third_order(357.52772, 35999.050340, -0.0001603, -1.0 / 300000.0, jce),  // X1 anomaly of the Sun
                       third_order(134.96298, 477198.867398, 0.0086972, 1.0 / 56250.0, jce),    // X2 anomaly of the Moon
                       third_order(93.27191, 483202.017538, -0.0036825, 1.0 / 327270.0, jce),   // X3 Moon's argument of latitude
                       third_order(125.04452, -1934.136261, 0.0020708, 1.0 / 450000.0, jce)};   // X4 ascending node
  double dpsi = 0, deps = 0;
  for (const auto& t : kNutation) {
    double arg = 0;
    for (int j = 0; j < 5; ++j) arg += x[j] * t.y[j];
    arg *= kDeg;
    dpsi += (t.a + t.b * jce) * std::sin(arg);
    deps += (t.c + t.d * jce) * std::cos(arg);
  }
  dpsi /= 36000000.0;  // 0.0001″ → degrees
  deps /= 36000000.0;
  r.nutation_longitude_deg = dpsi;
  r.nutation_obliquity_deg = deps;

  // 3.5 True obliquity of the ecliptic (eqs. 24–25), U = JME/10.
  const double u = jme / 10.0;
  static constexpr double kEps[] = {84381.448, -4680.93, -1.55, 1999.25, -51.38, -249.67, -39.05, 7.12, 27.87, 5.79, 2.45};
  double eps0 = 0, up = 1;
  for (double c : kEps) {
    eps0 += c * up;
    up *= u;
  }
  const double eps = eps0 / 3600.0 + deps;
  r.true_obliquity_deg = eps;

  // 3.6–3.7 Aberration and apparent sun longitude (eqs. 26–27).
  const double dtau = -20.4898 / (3600.0 * R);
  const double lambda = theta + dpsi + dtau;
  r.apparent_longitude_deg = lambda;

  // 3.8 Apparent sidereal time at Greenwich (eqs. 28–29).
  const double nu0 = limit_degrees(280.46061837 + 360.98564736629 * (jd - 2451545.0) + jc * jc * (0.000387933 - jc / 38710000.0));
  const double nu = nu0 + dpsi * std::cos(eps * kDeg);

  // 3.9–3.10 Geocentric right ascension and declination (eqs. 30–32).
  const double lr = lambda * kDeg, er = eps * kDeg, br = beta * kDeg;
  const double alpha = limit_degrees(std::atan2(std::sin(lr) * std::cos(er) - std::tan(br) * std::sin(er), std::cos(lr)) / kDeg);
  const double delta = std::asin(std::sin(br) * std::cos(er) + std::cos(br) * std::sin(er) * std::sin(lr)) / kDeg;
  r.right_ascension_deg = alpha;
  r.declination_deg = delta;

  // 3.11 Observer local hour angle (eq. 33).
  const double H = limit_degrees(nu + in.longitude_deg - alpha);
  r.hour_angle_deg = H;

  // 3.12 Topocentric right ascension, declination, hour angle (eqs. 34–40): parallax.
  const double xi = 8.794 / (3600.0 * R) * kDeg;
  const double phi = in.latitude_deg * kDeg;
  const double uu = std::atan(0.99664719 * std::tan(phi));
  const double xx = std::cos(uu) + in.elevation_m / 6378140.0 * std::cos(phi);
  const double yy = 0.99664719 * std::sin(uu) + in.elevation_m / 6378140.0 * std::sin(phi);
  const double Hr = H * kDeg, dr = delta * kDeg;
  const double dalpha = std::atan2(-xx * std::sin(xi) * std::sin(Hr), std::cos(dr) - xx * std::sin(xi) * std::cos(Hr));
  const double delta_p =
      std::atan2((std::sin(dr) - yy * std::sin(xi)) * std::cos(dalpha), std::cos(dr) - xx * std::sin(xi) * std::cos(Hr));
  const double Hp = Hr - dalpha;
  r.topocentric_right_ascension_deg = alpha + dalpha / kDeg;
  r.topocentric_declination_deg = delta_p / kDeg;
  r.topocentric_hour_angle_deg = Hp / kDeg;

  // 3.13–3.14 Topocentric elevation, refraction, zenith (eqs. 41–44).
  const double e0 = std::asin(std::sin(phi) * std::sin(delta_p) + std::cos(phi) * std::cos(delta_p) * std::cos(Hp)) / kDeg;
  double de = 0;
  constexpr double kSunRadiusDeg = 0.26667;
  if (e0 >= -(kSunRadiusDeg + in.atmos_refraction_deg))
    de = (in.pressure_mbar / 1010.0) * (283.0 / (273.0 + in.temperature_C)) * 1.02 /
         (60.0 * std::tan((e0 + 10.3 / (e0 + 5.11)) * kDeg));
  r.elevation_no_refraction_deg = e0;
  r.refraction_correction_deg = de;
  r.zenith_deg = 90.0 - (e0 + de);

  // 3.15 Topocentric azimuth (eqs. 45–46): astronomers' Γ from south, + 180° → from north, clockwise.
  const double gamma = std::atan2(std::sin(Hp), std::cos(Hp) * std::sin(phi) - std::tan(delta_p) * std::cos(phi)) / kDeg;
  r.azimuth_deg = limit_degrees(gamma + 180.0);
  return r;
}

double surface_incidence_deg(const SpaResult& sun, double slope_deg, double azm_rotation_deg) {
  const double th = sun.zenith_deg * kDeg, w = slope_deg * kDeg;
  const double gamma_astro = (sun.azimuth_deg - 180.0) * kDeg, g = azm_rotation_deg * kDeg;
  const double c = std::cos(th) * std::cos(w) + std::sin(w) * std::sin(th) * std::cos(gamma_astro - g);
  return std::acos(std::clamp(c, -1.0, 1.0)) / kDeg;
}

Vec3 direction_from_altitude_azimuth_deg(double altitude_deg, double azimuth_deg) {
  return direction_from_altitude_azimuth(altitude_deg * kDeg, azimuth_deg * kDeg);  // lighting/sun/sun.h
}

// ---------------------------------------------------------------------------------------------
// ISO-8601 parsing.
namespace {

struct Cursor {
  std::string_view s;
  std::size_t i = 0;
  bool done() const { return i >= s.size(); }
  char peek() const { return done() ? '\0' : s[i]; }
  bool digits(int n, int& out) {
    if (i + static_cast<std::size_t>(n) > s.size()) return false;
    int v = 0;
    for (int k = 0; k < n; ++k) {
      const char c = s[i + static_cast<std::size_t>(k)];
      if (c < '0' || c > '9') return false;
      v = v * 10 + (c - '0');
    }
    i += static_cast<std::size_t>(n);
    out = v;
    return true;
  }
  bool lit(char c) {
    if (peek() != c) return false;
    ++i;
    return true;
  }
};

}  // namespace

LocalDateTime parse_iso8601(std::string_view text, std::string_view flag, std::optional<double> utc_offset_hours) {
  const auto fail = [&](const std::string& why) -> InputError {
    return InputError(std::string(flag) + " '" + std::string(text) + "': " + why +
                      " (expected ISO 8601 like 2026-06-21T12:00:00+02:00 or ...Z)");
  };
  Cursor c{text};
  LocalDateTime t;
  bool neg_year = c.lit('-');
  if (!c.digits(4, t.year)) throw fail("cannot read the year");
  if (neg_year) t.year = -t.year;
  if (!c.lit('-') || !c.digits(2, t.month)) throw fail("cannot read the month");
  if (!c.lit('-') || !c.digits(2, t.day)) throw fail("cannot read the day");
  if (!(c.lit('T') || c.lit('t') || c.lit(' '))) throw fail("missing 'T' between date and time");
  if (!c.digits(2, t.hour)) throw fail("cannot read the hour");
  if (!c.lit(':') || !c.digits(2, t.minute)) throw fail("cannot read the minutes");
  if (c.lit(':')) {
    int s = 0;
    if (!c.digits(2, s)) throw fail("cannot read the seconds");
    t.second = s;
    if (c.lit('.') || c.lit(',')) {
      double scale = 0.1;
      bool any = false;
      while (c.peek() >= '0' && c.peek() <= '9') {
        t.second += scale * (c.peek() - '0');
        scale *= 0.1;
        ++c.i;
        any = true;
      }
      if (!any) throw fail("empty fraction of a second");
    }
  }
  std::optional<double> zone;
  if (c.lit('Z') || c.lit('z')) {
    zone = 0.0;
  } else if (c.peek() == '+' || c.peek() == '-') {
    const double sign = c.peek() == '-' ? -1.0 : 1.0;
    ++c.i;
    int zh = 0, zm = 0;
    if (!c.digits(2, zh)) throw fail("cannot read the UTC offset hours");
    if (c.lit(':')) {
      if (!c.digits(2, zm)) throw fail("cannot read the UTC offset minutes");
    } else if (!c.done()) {
      if (!c.digits(2, zm)) throw fail("cannot read the UTC offset minutes");
    }
    if (zh > 18 || zm > 59) throw fail("UTC offset out of range");
    zone = sign * (zh + zm / 60.0);
  }
  if (!c.done()) throw fail("unexpected text '" + std::string(text.substr(c.i)) + "'");
  if (t.month < 1 || t.month > 12) throw fail("month out of range");
  if (t.day < 1 || t.day > days_in_month(t.year, t.month)) throw fail("day out of range for the month");
  if (t.hour > 23 || t.minute > 59 || t.second >= 61.0) throw fail("time of day out of range");
  if (zone && utc_offset_hours && std::abs(*zone - *utc_offset_hours) > 1e-9)
    throw fail("its UTC offset disagrees with the explicit time-zone offset " + std::to_string(*utc_offset_hours) + " h");
  if (!zone && !utc_offset_hours) throw fail("no UTC offset: add Z or ±hh:mm, or give --tz");
  t.utc_offset_hours = zone ? *zone : *utc_offset_hours;
  if (!std::isfinite(t.utc_offset_hours) || std::abs(t.utc_offset_hours) > 18) throw fail("UTC offset out of range");
  return t;
}

}  // namespace skyband
