#include "lighting/spectrum/spectrum.h"

#include <algorithm>

namespace skyband {

Spectrum resample(std::span<const double> wavelengths_nm, std::span<const double> values) {
  Spectrum s;
  const std::size_t n = std::min(wavelengths_nm.size(), values.size());
  if (n == 0) return s;
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const double l = wavelength_nm(i);
    if (l <= wavelengths_nm[0]) {
      s[i] = values[0];
      continue;
    }
    if (l >= wavelengths_nm[n - 1]) {
      s[i] = values[n - 1];
      continue;
    }
    const auto it = std::upper_bound(wavelengths_nm.begin(), wavelengths_nm.begin() + static_cast<std::ptrdiff_t>(n), l);
    const std::size_t k = static_cast<std::size_t>(it - wavelengths_nm.begin());
    const double t = (l - wavelengths_nm[k - 1]) / (wavelengths_nm[k] - wavelengths_nm[k - 1]);
    s[i] = values[k - 1] + t * (values[k] - values[k - 1]);
  }
  return s;
}

}  // namespace skyband
