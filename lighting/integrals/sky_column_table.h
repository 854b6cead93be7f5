#pragma once
// Irradiance through an exact horizon in one dimension: per-sky "column" tables.
//
// With the visible sky of a point bounded below by an elevation e₀(φ) in each azimuth (the exact
// horizon, geometry/exact/sky_fan.h) and n·ω = n_z sin e + cos e (n_x cos φ + n_y sin φ), dω = cos e de dφ:
//
//   E = ∫_visible L(ω) (n·ω) dω = ∫ dφ [ n_z S(φ, e₀(φ)) + (n_x cos φ + n_y sin φ) C(φ, e₀(φ)) ],
//   S(φ, e) = ∫_e^{π/2} L(φ, e') sin e' cos e' de',   C(φ, e) = ∫_e^{π/2} L(φ, e') cos² e' de'.
//
// S and C depend on the sky only, so they are tabulated once per sky (per projected sky grid) on
// a 0.25° × 0.25° azimuth–elevation grid (2-node Gauss–Legendre per cell from the top down), and
// each point needs a one-dimensional quadrature in azimuth with bilinear look-ups — the paper's
// per-band tables (seed eq. 1) turned to vertical bands, which the exact horizon makes exact in
// elevation. Channels as the projected grid's (here 2: W·m⁻² and lx per sr).
#include <span>
#include <vector>

#include "geometry/exact/sky_fan.h"
#include "lighting/sky/sky_radiance_grid.h"

namespace skyband {

class SkyColumnTable {
 public:
  static constexpr int kAzimuthCells = 1440;   // 0.25°
  static constexpr int kElevationCells = 360;  // 0.25°, horizon to zenith
  static constexpr int kChannels = 2;

  // Tabulates S and C of a 2-channel projected sky grid (`threads` workers, 0 = all cores).
  SkyColumnTable(const ProjectedSkyGrid& grid, int threads = 0);

  // E over the fan (out[0..2), the grid's channel units × sr), Gauss–Legendre in azimuth on
  // pieces of at most max_step_rad per fan triangle.
  void integrate_fan(std::span<const SkyFanTriangle> fan, const Vec3& normal, double out[kChannels],
                     double max_step_rad = 0.05) const;

 private:
  // The four table entries around (φ ∈ ℝ, e ∈ [0, π/2]) and the bilinear weights' fractions.
  struct Cell {
    const float *a, *b, *c, *d;  // (i0, j0), (i1, j0), (i0, j0 + 1), (i1, j0 + 1)
    double fu, fv;
  };
  Cell cell(double phi, double e) const;
  // Bilinear S and C in a cell, both channels.
  static void lookup(const Cell& q, double s[kChannels], double c[kChannels]);
  // [elevation node][column][S0, S1, C0, C1]: elevation-major, so that the look-ups of a point's
  // azimuth quadrature, which move along azimuth at slowly changing elevations, stay in cache
  // (column-major, each look-up would read two columns 11.5 kB apart in a 16.6 MB table, and the
  // look-ups would take a third of `skyband irradiance`'s time on the 10k city). Single precision
  // (relative rounding 6·10⁻⁸, against the quadrature's ~10⁻⁵ and the sky model's ~10⁻³): half the
  // memory and ~8 % more points/s than double; sums are taken in double.
  std::vector<float> data_;
};

}  // namespace skyband
