#pragma once
// Horizon profiles of calculation points: the elevation of the horizon at regular azimuths, the
// profile PV tools take (pvlib's horizon shading, PVGIS- and PVsyst-style horizon files).
//
// The profile of a point is that of its surroundings, whatever its face: it is computed from the
// point's evaluated position (1 µm in front of its face, VisibilityOptions::surface_offset_m) as
// if its normal pointed up, by the exact union (geometry/exact/exact_sky.h), and is in each azimuth the
// highest occluded elevation (VisibleSky::horizon_elevation): above it the sky is visible up to
// the zenith. Where sky shows below an occluder (under a balcony, a bridge or an eave) the profile
// is the occluder's top — that sky does not count, as a sun path below the overhang is taken as
// shaded; a point under a roof has 90° all round. The face's own wall counts where the point is
// on a wall: behind it the profile is 90°.
#include <cstddef>
#include <functional>
#include <span>

#include "geometry/bands/band_visibility.h"
#include "geometry/mesh/scene.h"

namespace skyband {

// The finest azimuth step (degrees): 36,000 azimuths per point, far below the angular size of any
// building edge a profile is read for, and a bound on the rows written per point.
inline constexpr double kMinHorizonStepDeg = 0.01;

// Azimuths k·step_deg (degrees clockwise from north, k = 0 … while < 360). Throws InputError
// unless kMinHorizonStepDeg ≤ step_deg ≤ 360.
std::size_t horizon_azimuth_count(double step_deg);

// The profiles in blocks of consecutive points, in input order: consume(first, count, elevations)
// with elevations[(i − first)·m + k] the elevation (degrees above the horizontal) of point i at
// azimuth k·step_deg, m = horizon_azimuth_count(step_deg). Memory O(block) (at most 4096 points and
// ~2²² elevations), whatever the number of points; each block is computed on `threads` workers (0 = all cores). `progress(done,
// total)`.
void for_each_horizon_profile(const Scene& scene, std::span<const QueryPoint> points, const VisibilityOptions& options,
                              double step_deg, int threads, const std::function<void(std::size_t, std::size_t)>& progress,
                              const std::function<void(std::size_t, std::size_t, std::span<const double>)>& consume);

}  // namespace skyband
