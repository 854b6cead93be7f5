#pragma once
// Sky view factor and sky exposure for many points, by the method chosen in
// geometry/visibility/sky_visibility.h: by default exact at every point (the exact horizon where the scene is a
// column scene from the point, the exact union of the occluders' projections elsewhere).
#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "geometry/bands/band_visibility.h"
#include "geometry/mesh/scene.h"

namespace skyband {

enum class SkyFactorsMethod {
  automatic,  // the exact horizon where valid, the exact visible sky elsewhere
  exact,      // the exact visible sky (geometry/exact/exact_sky.h) everywhere
  bands,      // the band method everywhere (identical to compute_band_sky_factors, band_visibility.h)
};

struct SkyFactorsRun {
  std::vector<SkyFactors> factors;  // in input order
  std::size_t by_horizon = 0;       // points computed by the exact horizon
  std::size_t by_exact = 0;         // points computed by the exact visible sky
  std::size_t by_bands = 0;         // points computed by the band method
  std::size_t column_solids = 0;    // the scene's classification (geometry/horizon/column_scene.h)
  std::size_t other_components = 0;
};

// Deterministic: each point is computed alone, so the result does not depend on `threads`
// (0 = all cores). `progress(done, total)` is called from one thread.
SkyFactorsRun compute_sky_factors(const Scene& scene, std::span<const QueryPoint> points, const VisibilityOptions& options,
                                  SkyFactorsMethod method, int threads = 0,
                                  const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace skyband
