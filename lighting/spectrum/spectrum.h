#pragma once
// Sampled spectra on skyband's fixed wavelength grid: 380–780 nm every 10 nm (41 samples, the
// resolution the sky model and materials share: ≤ 10 nm over at least 380–780 nm).
// A Spectrum holds whatever spectral quantity its name says (W·m⁻²·nm⁻¹, W·m⁻²·sr⁻¹·nm⁻¹,
// a reflectance, an optical depth...); the unit lives in the variable's name or comment.
#include <array>
#include <cmath>
#include <cstddef>
#include <span>

namespace skyband {

inline constexpr int kSpectrumSamples = 41;
inline constexpr double kLambdaMinNm = 380.0;
inline constexpr double kLambdaStepNm = 10.0;
inline constexpr double kLambdaMaxNm = kLambdaMinNm + kLambdaStepNm * (kSpectrumSamples - 1);

inline constexpr double wavelength_nm(int i) {
  return kLambdaMinNm + kLambdaStepNm * i;
}

struct Spectrum {
  std::array<double, kSpectrumSamples> v{};

  static Spectrum constant(double c) {
    Spectrum s;
    s.v.fill(c);
    return s;
  }
  double& operator[](int i) { return v[static_cast<std::size_t>(i)]; }
  double operator[](int i) const { return v[static_cast<std::size_t>(i)]; }

  Spectrum& operator+=(const Spectrum& o) {
    for (int i = 0; i < kSpectrumSamples; ++i) (*this)[i] += o[i];
    return *this;
  }
  Spectrum& operator-=(const Spectrum& o) {
    for (int i = 0; i < kSpectrumSamples; ++i) (*this)[i] -= o[i];
    return *this;
  }
  Spectrum& operator*=(const Spectrum& o) {
    for (int i = 0; i < kSpectrumSamples; ++i) (*this)[i] *= o[i];
    return *this;
  }
  Spectrum& operator*=(double k) {
    for (auto& x : v) x *= k;
    return *this;
  }
  friend Spectrum operator+(Spectrum a, const Spectrum& b) { return a += b; }
  friend Spectrum operator-(Spectrum a, const Spectrum& b) { return a -= b; }
  friend Spectrum operator*(Spectrum a, const Spectrum& b) { return a *= b; }
  friend Spectrum operator*(Spectrum a, double k) { return a *= k; }
  friend Spectrum operator*(double k, Spectrum a) { return a *= k; }

  // Trapezoid integral over the grid, ∫ s(λ) dλ (unit × nm).
  double integral_nm() const {
    double sum = 0;
    for (int i = 0; i + 1 < kSpectrumSamples; ++i) sum += 0.5 * ((*this)[i] + (*this)[i + 1]) * kLambdaStepNm;
    return sum;
  }
  bool all_finite() const {
    for (double x : v)
      if (!std::isfinite(x)) return false;
    return true;
  }
};

// Linear interpolation of a tabulated spectrum (ascending wavelengths) onto the grid; values
// outside the table are clamped to its end values.
Spectrum resample(std::span<const double> wavelengths_nm, std::span<const double> values);

}  // namespace skyband
