#pragma once
// A two-channel sky integrated over a point's visible sky, whichever method computed it
// (geometry/visibility/visible_sky.h): E_k = ∫_visible c_k(ω) (n·ω) dω for the channels c_k of a projected
// sky grid (sky_radiance_grid.h) — one moment's sky or a time-integrated one.
#include <vector>

#include "geometry/exact/sky_fan.h"
#include "geometry/visibility/visible_sky.h"
#include "lighting/integrals/sky_column_table.h"
#include "lighting/sky/sky_radiance_grid.h"

namespace skyband {

// A sky ready for every method: the projected grid (for the band method's lines) and its column
// tables (for the exact methods' regions: sky_column_table.h). The grid must outlive it.
struct SkyTables {
  const ProjectedSkyGrid& grid;
  SkyColumnTable columns;
  SkyTables(const ProjectedSkyGrid& g, int threads) : grid(g), columns(g, threads) {}
};

// Both channels of the sky integrated over a point's visible sky: along the band lines
// (Gauss–Legendre pieces ≤ max_step_rad), or in azimuth over the exact region's signed fan with the
// column tables (pieces ≤ a quarter of it: the one-dimensional quadrature is cheap, and the arcs'
// elevation e₀(φ) can be steep). `fan` is scratch.
void sky_channels(const VisibleSky& sky, const SkyTables& tables, double max_step_rad, std::vector<SkyFanTriangle>& fan,
                  double out[2]);

// The same integral for an unobstructed horizontal face, by the exact methods' quadrature
// (exact[]) and by the band method's (bands[]): the reference an open horizontal point reproduces
// bit for bit, for ratios and calibrations.
struct OpenSky {
  double exact[2], bands[2];
  OpenSky(const SkyTables& tables, const VisibilityOptions& visibility, double max_step_rad);
  const double* of(const VisibleSky& sky) const { return sky.exact() ? exact : bands; }
};

}  // namespace skyband
