#pragma once
// e^{−x} for x ≥ 0 without a libm call, for the hot loop of the specular march (the Beckmann
// factor exp(−tan²θ_h/m²) is evaluated ~1,000 times per glossy pixel).
//
//     e^{−x} = e^{−k·h} · e^{−f},   k = ⌊x/h⌋, f = x − k·h ∈ [0, h), h = 1/64,
//
// with e^{−k·h} from a table and e^{−f} from its Taylor polynomial to degree 4, whose
// remainder is ≤ f⁵/120 < 2.7·10⁻¹¹ relative. Outside [0, 64) it calls std::exp: the march's
// stop tests compare tiny values (a line whose G is 10⁻³⁰ but still rising keeps the sweep going),
// so no value may be flushed to 0 that std::exp would not. fast_exp_test checks it.
#include <array>
#include <cmath>

namespace skyband {

namespace fast_exp_detail {
inline constexpr int kSteps = 64;                 // table steps per unit of x
inline constexpr int kEntries = 64 * kSteps + 1;  // x ∈ [0, 64]
inline const std::array<double, kEntries>& table() {
  static const std::array<double, kEntries> t = [] {
    std::array<double, kEntries> a{};
    for (int k = 0; k < kEntries; ++k) a[static_cast<std::size_t>(k)] = std::exp(-static_cast<double>(k) / kSteps);
    return a;
  }();
  return t;
}
}  // namespace fast_exp_detail

inline double exp_neg(double x) {
  using namespace fast_exp_detail;
  if (!(x >= 0.0 && x < static_cast<double>(kEntries - 1) / kSteps)) return std::exp(-x);  // also NaN
  const double s = x * kSteps;
  const int k = static_cast<int>(s);
  const double f = (s - k) / kSteps;
  const double poly = 1.0 - f * (1.0 - f * (0.5 - f * (1.0 / 6.0 - f * (1.0 / 24.0))));
  return table()[static_cast<std::size_t>(k)] * poly;
}

}  // namespace skyband
