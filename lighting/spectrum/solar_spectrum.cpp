#include "lighting/spectrum/solar_spectrum.h"

namespace skyband {

Spectrum astm_g173_extraterrestrial_10nm() {
  // reference-notes §2.5 table, column E0 (ASTM G173-03 ETR 10-nm bin means), 380–780 nm.
  static constexpr double kEtr[kSpectrumSamples] = {
      1.0125, 1.1472, 1.7276, 1.7305, 1.6887, 1.6125, 1.9120, 2.0347, 2.0204, 2.0221, 1.9338, 1.9581, 1.9169, 1.8298,
      1.8685, 1.8931, 1.8515, 1.8504, 1.8341, 1.8345, 1.8147, 1.7816, 1.7533, 1.6965, 1.6819, 1.6465, 1.6048, 1.5214,
      1.5562, 1.5113, 1.4740, 1.4482, 1.4102, 1.3678, 1.3419, 1.3143, 1.2830, 1.2676, 1.2367, 1.2082, 1.1874};
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) s[i] = kEtr[i];
  return s;
}

}  // namespace skyband
