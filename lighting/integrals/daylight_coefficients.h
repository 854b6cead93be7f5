#pragma once
// Daylight coefficients of a point: the weights w_j with which the point's sky irradiance under
// any sky is Σ_j w_j·L_j, L_j the sky's radiance at the nodes j of a coarse stereographic grid
// (the parametrisation of sky_radiance_grid.h, kDaylightCoefficientCells² cells over [−1, 1]²,
// bilinear between nodes; nodes outside the unit disk hold the sky's linear extension across the
// horizon, 2·L(rim) − L(mirror), clamped at 0). With them a year of hourly skies costs one dot
// product per hour and point, after one geometry pass.
//
//   w_j = ∫_visible φ_j(ω) (n·ω) dω = Σ_b w_b Σ_visible ∫ φ_j(ω(α, δ_b)) sin²α dα   (seed eq. 1)
//
// over the point's band lines (an exact region is cut along them, geometry/bands/sample_lines.h, with
// the line count doubled until the lines' SVF is within the tolerance of the exact one), each
// visible interval by 4-point Gauss–Legendre on pieces ≤ 0.05 rad. The hat functions φ_j have
// kinks at the cell edges, so the quadrature is second order there: the sky irradiance of an
// open horizontal face comes out within ~10⁻³ of the exact integral of the interpolated sky,
// which the caller removes hour by hour by normalising on that face (climate_irradiation.h).
#include <span>
#include <vector>

#include "geometry/bands/band_visibility.h"
#include "geometry/core/vec3.h"
#include "geometry/visibility/visible_sky.h"

namespace skyband {

inline constexpr int kDaylightCoefficientCells = 24;
// Exact regions are cut along at least this many lines, doubled at most this often (a distant low
// skyline that the lines' SVF misses by more than the tolerance at 256 lines stays so: the hourly
// values are then within the δ discretisation of 256 lines; the period's sums do not use them).
inline constexpr int kDaylightCoefficientLines = 64;
inline constexpr int kDaylightCoefficientDoublings = 2;
inline constexpr int kDaylightCoefficientNodes = (kDaylightCoefficientCells + 1) * (kDaylightCoefficientCells + 1);

// How node j's radiance is taken from a sky: L_j = max(0, a·L(d_a) + b·L(d_b)) (b = 0 inside the disk).
struct DaylightNode {
  Vec3 da, db;
  double a = 1, b = 0;
};
const std::vector<DaylightNode>& daylight_nodes();

// The point's coefficients (kDaylightCoefficientNodes values, sr) into `out`. Band-method skies
// use their own lines; exact regions are cut along max(visibility.bands, 64) lines, doubled (at
// most twice) to `visibility.tolerance`.
void daylight_coefficients(const VisibleSky& sky, const VisibilityOptions& visibility, std::span<float> out);

}  // namespace skyband
