#pragma once
// Extraterrestrial solar spectral irradiance on skyband's grid.
#include "lighting/spectrum/spectrum.h"

namespace skyband {

// ASTM G173-03 extraterrestrial spectrum (ETR), W·m⁻²·nm⁻¹ at 1 AU, as 10-nm bin means over
// [λ, λ+10) nm for λ = 380, 390, ..., 780 (the values of Bruneton's kSolarIrradiance, re-derived
// from pvlib's ASTMG173.csv, reference-notes §2.5). Each mean is used as the grid sample at λ,
// i.e. shifted by half a bin (5 nm); the 10-nm means smooth the Fraunhofer lines, as a 41-sample
// spectrum must.
Spectrum astm_g173_extraterrestrial_10nm();

}  // namespace skyband
