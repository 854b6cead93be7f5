#pragma once
// An exact visible sky (geometry/visibility/visible_sky.h) cut along the band method's sample lines, so that
// the consumers of the visibility cache (the renderer's diffuse look-up tables and specular
// march, method.md §3) take their α-intervals from the exact region instead of the band method's
// own geometry pass.
//
// A sample line at δ is the half great circle ω(α) = cos α·x + sin α·(cos δ·h + sin δ·z), α ∈ [0, π]
// (geometry/bands/band_frame.h). Over the azimuths of one piece of the region the line meets each
// boundary circle at most once (two great circles meet in one antipodal pair, one of which is on
// the line's upper half), so the line's visible α-intervals within the piece lie between the
// crossings; each stretch between consecutive crossings is classified at its middle by counting
// the piece's boundaries below it (visible when the count is even: B₀ is the nadir, the sky is
// visible between B₁ and B₂, B₃ and B₄, …). Pieces meet the line over consecutive α ranges.
//
// Only the δ discretisation is approximate. The lines sit at the weight medians of equal-weight
// bands (seed eq. 1), and their number is doubled, from the requested count, until the lines'
// SVF and sky exposure (geometry/bands/sky_integral.h) agree with the region's exact values to within
// half the tolerance — a measured error, not an estimate — or the doubling limit is reached.
#include <vector>

#include "geometry/bands/band_frame.h"
#include "geometry/bands/visibility_cache.h"
#include "geometry/visibility/visible_sky.h"

namespace skyband {

// The visible α-intervals (sorted, disjoint, within [0, π]) of the sample line at δ ∈ [0, π] of
// `frame` in the exact region `sky`. Appends to `out`.
void visible_on_sample_line(const VisibleSky& sky, const BandFrame& frame, double delta_rad, std::vector<VisibleInterval>& out);

struct SampleLineOptions {
  int bands = 32;           // initial number of equal-weight bands (≥ 1)
  double tolerance = 5e-4;  // target for |SVF − exact| and |exposure − exact|; 0: no doubling
  int max_doublings = 6;    // the band count is doubled at most this many times
};

// The cache entry of one point with an exact visible sky: its sample lines (each band one line at
// its weight median, exposure weight the band's δ-width) and their visible intervals. Returns the
// number of bands used.
int sample_lines_of(const VisibleSky& sky, const SampleLineOptions& options, VisibilityCache::PointResult& out);

}  // namespace skyband
