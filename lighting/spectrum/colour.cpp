#include "lighting/spectrum/colour.h"

#include <array>
#include <cmath>

#include <Eigen/Dense>

namespace skyband {

namespace {

// CIE 1931 2° colour-matching functions, 5 nm, 360–830 nm (source: see colour.h).
constexpr std::array<CmfRow, 95> kCie1931_5nm = {{
    {360.0, 0.0001299, 3.917e-06, 0.0006061},
    {365.0, 0.0002321, 6.965e-06, 0.001086},
    {370.0, 0.0004149, 1.239e-05, 0.001946},
    {375.0, 0.0007416, 2.202e-05, 0.003486},
    {380.0, 0.001368, 3.9e-05, 0.006450001},
    {385.0, 0.002236, 6.4e-05, 0.01054999},
    {390.0, 0.004243, 0.00012, 0.02005001},
    {395.0, 0.00765, 0.000217, 0.03621},
    {400.0, 0.01431, 0.000396, 0.06785001},
    {405.0, 0.02319, 0.00064, 0.1102},
    {410.0, 0.04351, 0.00121, 0.2074},
    {415.0, 0.07763, 0.00218, 0.3713},
    {420.0, 0.13438, 0.004, 0.6456},
    {425.0, 0.21477, 0.0073, 1.0390501},
    {430.0, 0.2839, 0.0116, 1.3856},
    {435.0, 0.3285, 0.01684, 1.62296},
    {440.0, 0.34828, 0.023, 1.74706},
    {445.0, 0.34806, 0.0298, 1.7826},
    {450.0, 0.3362, 0.038, 1.77211},
    {455.0, 0.3187, 0.048, 1.7441},
    {460.0, 0.2908, 0.06, 1.6692},
    {465.0, 0.2511, 0.0739, 1.5281},
    {470.0, 0.19536, 0.09098, 1.28764},
    {475.0, 0.1421, 0.1126, 1.0419},
    {480.0, 0.09564, 0.13902, 0.8129501},
    {485.0, 0.05795001, 0.1693, 0.6162},
    {490.0, 0.03201, 0.20802, 0.46518},
    {495.0, 0.0147, 0.2586, 0.3533},
    {500.0, 0.0049, 0.323, 0.272},
    {505.0, 0.0024, 0.4073, 0.2123},
    {510.0, 0.0093, 0.503, 0.1582},
    {515.0, 0.0291, 0.6082, 0.1117},
    {520.0, 0.06327, 0.71, 0.07824999},
    {525.0, 0.1096, 0.7932, 0.05725001},
    {530.0, 0.1655, 0.862, 0.04216},
    {535.0, 0.2257499, 0.9148501, 0.02984},
    {540.0, 0.2904, 0.954, 0.0203},
    {545.0, 0.3597, 0.9803, 0.0134},
    {550.0, 0.4334499, 0.9949501, 0.008749999},
    {555.0, 0.5120501, 1.0, 0.005749999},
    {560.0, 0.5945, 0.995, 0.0039},
    {565.0, 0.6784, 0.9786, 0.002749999},
    {570.0, 0.7621, 0.952, 0.0021},
    {575.0, 0.8425, 0.9154, 0.0018},
    {580.0, 0.9163, 0.87, 0.001650001},
    {585.0, 0.9786, 0.8163, 0.0014},
    {590.0, 1.0263, 0.757, 0.0011},
    {595.0, 1.0567, 0.6949, 0.001},
    {600.0, 1.0622, 0.631, 0.0008},
    {605.0, 1.0456, 0.5668, 0.0006},
    {610.0, 1.0026, 0.503, 0.00034},
    {615.0, 0.9384, 0.4412, 0.00024},
    {620.0, 0.8544499, 0.381, 0.00019},
    {625.0, 0.7514, 0.321, 0.0001},
    {630.0, 0.6424, 0.265, 4.999999e-05},
    {635.0, 0.5419, 0.217, 3e-05},
    {640.0, 0.4479, 0.175, 2e-05},
    {645.0, 0.3608, 0.1382, 1e-05},
    {650.0, 0.2835, 0.107, 0.0},
    {655.0, 0.2187, 0.0816, 0.0},
    {660.0, 0.1649, 0.061, 0.0},
    {665.0, 0.1212, 0.04458, 0.0},
    {670.0, 0.0874, 0.032, 0.0},
    {675.0, 0.0636, 0.0232, 0.0},
    {680.0, 0.04677, 0.017, 0.0},
    {685.0, 0.0329, 0.01192, 0.0},
    {690.0, 0.0227, 0.00821, 0.0},
    {695.0, 0.01584, 0.005723, 0.0},
    {700.0, 0.01135916, 0.004102, 0.0},
    {705.0, 0.008110916, 0.002929, 0.0},
    {710.0, 0.005790346, 0.002091, 0.0},
    {715.0, 0.004109457, 0.001484, 0.0},
    {720.0, 0.002899327, 0.001047, 0.0},
    {725.0, 0.00204919, 0.00074, 0.0},
    {730.0, 0.001439971, 0.00052, 0.0},
    {735.0, 0.0009999493, 0.0003611, 0.0},
    {740.0, 0.0006900786, 0.0002492, 0.0},
    {745.0, 0.0004760213, 0.0001719, 0.0},
    {750.0, 0.0003323011, 0.00012, 0.0},
    {755.0, 0.0002348261, 8.48e-05, 0.0},
    {760.0, 0.0001661505, 6e-05, 0.0},
    {765.0, 0.000117413, 4.24e-05, 0.0},
    {770.0, 8.307527e-05, 3e-05, 0.0},
    {775.0, 5.870652e-05, 2.12e-05, 0.0},
    {780.0, 4.150994e-05, 1.499e-05, 0.0},
    {785.0, 2.935326e-05, 1.06e-05, 0.0},
    {790.0, 2.067383e-05, 7.4657e-06, 0.0},
    {795.0, 1.455977e-05, 5.2578e-06, 0.0},
    {800.0, 1.025398e-05, 3.7029e-06, 0.0},
    {805.0, 7.221456e-06, 2.6078e-06, 0.0},
    {810.0, 5.085868e-06, 1.8366e-06, 0.0},
    {815.0, 3.581652e-06, 1.2934e-06, 0.0},
    {820.0, 2.522525e-06, 9.1093e-07, 0.0},
    {825.0, 1.776509e-06, 6.4153e-07, 0.0},
    {830.0, 1.251141e-06, 4.5181e-07, 0.0},
}};

// CIE D65, relative spectral power, 380–780 nm every 10 nm (CIE 15:2004, Table T.1).
constexpr std::array<double, kSpectrumSamples> kD65 = {
    49.9755, 54.6482, 82.7549, 91.4860, 93.4318, 86.6823, 104.865, 117.008, 117.812, 114.861, 115.923, 108.811, 109.354, 107.802,
    104.790, 107.689, 104.405, 104.046, 100.000, 96.3342, 95.7880, 88.6856, 90.0062, 89.5991, 87.6987, 83.2886, 83.6992, 80.0268,
    80.2146, 82.2778, 78.2842, 69.7213, 71.6091, 74.3490, 61.6040, 69.8856, 75.0870, 63.5927, 46.4182, 66.8054, 63.3828};

// Robertson (1968) isotemperature lines: reciprocal temperature (MK⁻¹), u, v (CIE 1960), slope t.
struct RobertsonRow {
  double mired, u, v, t;
};
constexpr std::array<RobertsonRow, 31> kRobertson = {{
    {0, 0.18006, 0.26352, -0.24341},   {10, 0.18066, 0.26589, -0.25479},  {20, 0.18133, 0.26846, -0.26876},
    {30, 0.18208, 0.27119, -0.28539},  {40, 0.18293, 0.27407, -0.30470},  {50, 0.18388, 0.27709, -0.32675},
    {60, 0.18494, 0.28021, -0.35156},  {70, 0.18611, 0.28342, -0.37915},  {80, 0.18740, 0.28668, -0.40955},
    {90, 0.18880, 0.28997, -0.44278},  {100, 0.19032, 0.29326, -0.47888}, {125, 0.19462, 0.30141, -0.58204},
    {150, 0.19962, 0.30921, -0.70471}, {175, 0.20525, 0.31647, -0.84901}, {200, 0.21142, 0.32312, -1.0182},
    {225, 0.21807, 0.32909, -1.2168},  {250, 0.22511, 0.33439, -1.4512},  {275, 0.23247, 0.33904, -1.7298},
    {300, 0.24010, 0.34308, -2.0637},  {325, 0.24792, 0.34655, -2.4681},  {350, 0.25591, 0.34951, -2.9641},
    {375, 0.26400, 0.35200, -3.5814},  {400, 0.27218, 0.35407, -4.3633},  {425, 0.28039, 0.35577, -5.3762},
    {450, 0.28863, 0.35714, -6.7262},  {475, 0.29685, 0.35823, -8.5955},  {500, 0.30505, 0.35907, -11.324},
    {525, 0.31320, 0.35968, -15.628},  {550, 0.32129, 0.36011, -23.325},  {575, 0.32931, 0.36038, -40.770},
    {600, 0.33724, 0.36051, -116.45},
}};

struct GridCmf {
  Spectrum x, y, z;     // CMFs on the grid
  Spectrum wx, wy, wz;  // CMFs × trapezoid weights (nm), so XYZ is a dot product
};

const GridCmf& grid_cmf() {
  static const GridCmf g = [] {
    GridCmf r;
    for (int i = 0; i < kSpectrumSamples; ++i) {
      const double l = wavelength_nm(i);
      const auto idx = static_cast<std::size_t>(std::lround((l - kCie1931_5nm[0].wavelength_nm) / 5.0));
      r.x[i] = kCie1931_5nm[idx].xbar;
      r.y[i] = kCie1931_5nm[idx].ybar;
      r.z[i] = kCie1931_5nm[idx].zbar;
      const double w = (i == 0 || i == kSpectrumSamples - 1) ? 0.5 * kLambdaStepNm : kLambdaStepNm;
      r.wx[i] = w * r.x[i];
      r.wy[i] = w * r.y[i];
      r.wz[i] = w * r.z[i];
    }
    return r;
  }();
  return g;
}

}  // namespace

std::span<const CmfRow> cie1931_2deg_5nm() {
  return kCie1931_5nm;
}
const Spectrum& cmf_x() {
  return grid_cmf().x;
}
const Spectrum& cmf_y() {
  return grid_cmf().y;
}
const Spectrum& cmf_z() {
  return grid_cmf().z;
}
const Spectrum& xyz_weights(int c) {
  const GridCmf& g = grid_cmf();
  return c == 0 ? g.wx : c == 1 ? g.wy : g.wz;
}

Xyz spectrum_to_xyz(const Spectrum& s) {
  const GridCmf& g = grid_cmf();
  Xyz r;
  for (int i = 0; i < kSpectrumSamples; ++i) {
    r.X += g.wx[i] * s[i];
    r.Y += g.wy[i] * s[i];
    r.Z += g.wz[i] * s[i];
  }
  return r;
}

double luminous(const Spectrum& s) {
  const GridCmf& g = grid_cmf();
  double y = 0;
  for (int i = 0; i < kSpectrumSamples; ++i) y += g.wy[i] * s[i];
  return kMaxLuminousEfficacy_lm_W * y;
}

const Eigen::Matrix3d& linear_srgb_from_xyz() {
  // Standard derivation (e.g. Wyszecki & Stiles; IEC 61966-2-1 Annex): columns of the
  // RGB→XYZ matrix are the primaries' XYZ (Y = 1) scaled so that RGB (1,1,1) maps to the white.
  static const Eigen::Matrix3d m = [] {
    const double prim[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};  // Rec. 709 R, G, B
    const double wx = 0.3127, wy = 0.3290;                                 // D65
    Eigen::Matrix3d p;
    for (int c = 0; c < 3; ++c) {
      const double x = prim[c][0], y = prim[c][1];
      p(0, c) = x / y;
      p(1, c) = 1.0;
      p(2, c) = (1.0 - x - y) / y;
    }
    const Eigen::Vector3d white(wx / wy, 1.0, (1.0 - wx - wy) / wy);
    const Eigen::Vector3d scale = p.partialPivLu().solve(white);
    const Eigen::Matrix3d xyz_from_rgb = p * scale.asDiagonal();
    return Eigen::Matrix3d(xyz_from_rgb.inverse());
  }();
  return m;
}

Vec3 xyz_to_linear_srgb(const Xyz& xyz) {
  return linear_srgb_from_xyz() * Vec3(xyz.X, xyz.Y, xyz.Z);
}

Vec3 spectrum_to_linear_srgb(const Spectrum& s) {
  return xyz_to_linear_srgb(spectrum_to_xyz(s));
}

std::optional<Vec2> chromaticity_xy(const Xyz& xyz) {
  const double sum = xyz.X + xyz.Y + xyz.Z;
  if (!(sum > 0) || !std::isfinite(sum)) return std::nullopt;
  return Vec2(xyz.X / sum, xyz.Y / sum);
}

Vec2 uv1960_from_xy(const Vec2& xy) {
  // CIE 1960 UCS: u = 4x/(−2x + 12y + 3), v = 6y/(−2x + 12y + 3).
  const double d = -2.0 * xy.x() + 12.0 * xy.y() + 3.0;
  return Vec2(4.0 * xy.x() / d, 6.0 * xy.y() / d);
}

std::optional<double> cct_robertson_K(const Vec2& xy) {
  if (!xy.allFinite()) return std::nullopt;
  const Vec2 uv = uv1960_from_xy(xy);
  // Signed distance to each isotemperature line (Robertson 1968, eq. for d_i); the CCT lies
  // between the two adjacent lines where the sign changes, interpolated linearly in mired.
  double d_prev = 0;
  for (std::size_t i = 0; i < kRobertson.size(); ++i) {
    const RobertsonRow& r = kRobertson[i];
    const double d = ((uv.y() - r.v) - r.t * (uv.x() - r.u)) / std::sqrt(1.0 + r.t * r.t);
    if (i > 0 && (d_prev > 0) != (d > 0)) {
      const RobertsonRow& p = kRobertson[i - 1];
      const double f = d_prev / (d_prev - d);
      const double mired = p.mired + f * (r.mired - p.mired);
      if (!(mired > 0)) return std::nullopt;  // beyond infinite temperature
      return 1e6 / mired;
    }
    d_prev = d;
  }
  return std::nullopt;
}

double planck_radiance_W_m2_sr_nm(double wavelength_nm, double temperature_K) {
  constexpr double h = 6.62607015e-34;    // J·s (exact, SI 2019)
  constexpr double c = 299792458.0;       // m/s (exact)
  constexpr double k = 1.380649e-23;      // J/K (exact, SI 2019)
  const double l = wavelength_nm * 1e-9;  // metres
  const double per_m = 2.0 * h * c * c / std::pow(l, 5) / std::expm1(h * c / (l * k * temperature_K));
  return per_m * 1e-9;  // W·m⁻²·sr⁻¹·m⁻¹ → per nm
}

Spectrum planck_spectrum(double temperature_K) {
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) s[i] = planck_radiance_W_m2_sr_nm(wavelength_nm(i), temperature_K);
  return s;
}

Spectrum cie_d65() {
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) s[i] = kD65[static_cast<std::size_t>(i)];
  return s;
}

}  // namespace skyband
