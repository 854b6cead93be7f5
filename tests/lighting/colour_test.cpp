#define BOOST_TEST_MODULE colour
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "lighting/spectrum/colour.h"
#include "shared_data.h"

namespace tt = boost::test_tools;
using namespace skyband;

namespace {
std::vector<CmfRow> read_shared_cmf() {
  std::ifstream in(SKYBAND_SHARED_DATA "/spectra/cie1931_2deg_5nm.txt");
  BOOST_REQUIRE(in.good());
  std::vector<CmfRow> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    CmfRow r{};
    ss >> r.wavelength_nm >> r.xbar >> r.ybar >> r.zbar;
    BOOST_REQUIRE(!ss.fail());
    rows.push_back(r);
  }
  return rows;
}
}  // namespace

BOOST_AUTO_TEST_CASE(embedded_cmf_table_matches_shared_data, *skyband::test::needs_shared_data()) {
  // The embedded table must be the published CIE table, digit for digit (both are decimal
  // literals parsed by the same strtod rules, so equality is exact).
  const auto file = read_shared_cmf();
  const auto emb = cie1931_2deg_5nm();
  BOOST_REQUIRE_EQUAL(file.size(), emb.size());
  for (std::size_t i = 0; i < file.size(); ++i) {
    BOOST_TEST(emb[i].wavelength_nm == file[i].wavelength_nm);
    BOOST_TEST(emb[i].xbar == file[i].xbar);
    BOOST_TEST(emb[i].ybar == file[i].ybar);
    BOOST_TEST(emb[i].zbar == file[i].zbar);
  }
}

BOOST_AUTO_TEST_CASE(srgb_matrix_matches_iec_61966_2_1) {
  // Published matrix (IEC 61966-2-1:1999, eq. for linear RGB from XYZ), given to 4 decimals:
  // our matrix is derived from primaries + white, so agreement to rounding (5e-4) checks it.
  const double pub[3][3] = {{3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
  const auto& m = linear_srgb_from_xyz();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) BOOST_TEST(std::abs(m(r, c) - pub[r][c]) < 5e-4, "m(" << r << "," << c << ")=" << m(r, c));
}

BOOST_AUTO_TEST_CASE(equal_energy_spectrum_is_achromatic) {
  // The CMFs are normalised so that equal-energy illuminant E has x = y = 1/3 (CIE 15). Over
  // 380–780 nm at 10 nm, the truncation and sampling shift xy by < 1e-3.
  const auto xy = chromaticity_xy(spectrum_to_xyz(Spectrum::constant(1.0)));
  BOOST_REQUIRE(xy.has_value());
  BOOST_TEST(std::abs(xy->x() - 1.0 / 3.0) < 1e-3);
  BOOST_TEST(std::abs(xy->y() - 1.0 / 3.0) < 1e-3);
}

BOOST_AUTO_TEST_CASE(luminous_efficacy_of_flat_spectrum, *skyband::test::needs_shared_data()) {
  // Independent computation: trapezoid ∫ȳ over the full 5-nm shared table (360–830 nm). The grid
  // only spans 380–780 at 10 nm; ȳ outside is < 1.2e-4 of its peak, sampling error ≈ 1e-4, so
  // 0.2% covers both.
  const auto rows = read_shared_cmf();
  double integral = 0;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) integral += 0.5 * (rows[i].ybar + rows[i + 1].ybar) * 5.0;
  BOOST_TEST(luminous(Spectrum::constant(1.0)) == 683.0 * integral, tt::tolerance(2e-3));
  BOOST_TEST(!chromaticity_xy(Xyz{}).has_value());
}

BOOST_AUTO_TEST_CASE(d65_white_point_and_cct) {
  // Published D65: xy = (0.31271, 0.32902) (CIE 15:2004 Table T.3), CCT 6504 K. Our 10-nm,
  // 380–780 nm sums move xy by ~1e-4; 5e-4 is the allowance. CCT within 1%, the allowance
  // for the same sums.
  const Xyz xyz = spectrum_to_xyz(cie_d65());
  const auto xy = chromaticity_xy(xyz);
  BOOST_REQUIRE(xy.has_value());
  BOOST_TEST(std::abs(xy->x() - 0.31271) < 5e-4);
  BOOST_TEST(std::abs(xy->y() - 0.32902) < 5e-4);
  const auto cct = cct_robertson_K(*xy);
  BOOST_REQUIRE(cct.has_value());
  BOOST_TEST(*cct == 6504.0, tt::tolerance(0.01));
  // D65 is the sRGB white: equal R, G, B (within the same 1e-3-level chromaticity slack → 1%).
  const Vec3 rgb = xyz_to_linear_srgb(xyz);
  BOOST_TEST(rgb.x() == rgb.y(), tt::tolerance(0.01));
  BOOST_TEST(rgb.z() == rgb.y(), tt::tolerance(0.01));
  BOOST_TEST(rgb.y() == xyz.Y, tt::tolerance(0.01));
}

BOOST_AUTO_TEST_CASE(planck_cct_recovered) {
  // Independent computation: Planck's law gives the spectrum of a black body at T; its CCT must
  // be T. 1% (brief) covers Robertson's table interpolation (< 0.1%) and 10-nm sampling.
  for (double T : {2500.0, 3000.0, 4000.0, 5000.0, 5778.0, 6500.0, 8000.0, 10000.0}) {
    const auto xy = chromaticity_xy(spectrum_to_xyz(planck_spectrum(T)));
    BOOST_REQUIRE(xy.has_value());
    const auto cct = cct_robertson_K(*xy);
    BOOST_REQUIRE(cct.has_value());
    BOOST_TEST(*cct == T, tt::tolerance(0.01));
  }
  // Below 1667 K (600 MK⁻¹, the table's end) there is no answer rather than a wrong one.
  const auto xy_cold = chromaticity_xy(spectrum_to_xyz(planck_spectrum(1200.0)));
  BOOST_TEST(!cct_robertson_K(*xy_cold).has_value());
}

BOOST_AUTO_TEST_CASE(planck_closed_form_value) {
  // Evaluated by hand (SI 2019 exact h, c, k): at λ = 500 nm, T = 5778 K, hc/(λkT) = 4.98019,
  // 2hc²/λ⁵ = 3.81134e15 W·m⁻³·sr⁻¹, so L = 3.81134e15/(e^4.98019 − 1)·1e-9 = 26375.67
  // W·m⁻²·sr⁻¹·nm⁻¹ (7 significant digits → 1e-6).
  BOOST_TEST(planck_radiance_W_m2_sr_nm(500.0, 5778.0) == 26375.67, tt::tolerance(1e-6));
  // Wien's displacement law (λ_max·T = 2.897772e6 nm·K): the 10-nm grid maximum of a 5000 K
  // body lies within one step of 579.6 nm.
  const Spectrum s = planck_spectrum(5000.0);
  int imax = 0;
  for (int i = 1; i < kSpectrumSamples; ++i)
    if (s[i] > s[imax]) imax = i;
  BOOST_TEST(std::abs(wavelength_nm(imax) - 2.897772e6 / 5000.0) <= 10.0);
}
