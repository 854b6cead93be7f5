#pragma once
// The options and counters of the ε-truncated specular sky march (specular_sky.h; seed §3,
// method.md §4), on their own so that a caller that only configures the march (the renderer)
// does not compile it.
#include <cstddef>

namespace skyband {

struct SpecularSkyOptions {
  double epsilon = 1e-3;            // truncation threshold, relative to G_max (seed's ε)
  double alpha_step_per_m = 2.0;    // α cells ≤ alpha_step_per_m · m ...
  double max_alpha_step_rad = 0.1;  // ... and ≤ this (sky variation under wide lobes)
  double delta_step_per_m = 2.0;    // δ pieces ≤ delta_step_per_m · m ...
  double max_delta_step_rad = 0.2;  // ... and ≤ this
  double single_line_per_m = 0.5;   // a band ≤ this · m wide in δ is one line (seed eq. 7)
  double min_compression = 0.02;    // floor of N·V in the lobe's width across the plane of incidence
  int stop_after = 2;               // consecutive cells (lines) below ε that end a march (sweep)
  double lobe_window_per_m = 7.0;   // lines are integrated only within this · m of Q in α: step 4
  double mirror_below_m = 0.005;    // m below this: perfect mirror (single look-up)
};

struct SpecularSkyStats {
  std::size_t radiance_evals = 0;  // sky radiance evaluations
  std::size_t lines = 0;           // sample lines integrated
};

}  // namespace skyband
