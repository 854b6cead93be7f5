#pragma once
// The band frame of a calculation point (method.md §2; reference-notes §1.1, §1.3).
//
// Axis x is horizontal and lies in the face plane: x = normalize(n × z); h = z × x is the
// horizontal projection of the normal, so n = cos β·h + sin β·z with β ∈ [−π/2, π/2] the
// elevation of the normal above the horizon (β = π/2: horizontal face looking up; β = 0: wall).
// For a horizontal face x is the fixed azimuth kHorizontalAxisAzimuth (any horizontal direction
// is valid; a generic one avoids lining up with axis-aligned street grids).
//
// A sky direction on the sample plane at angle δ ∈ [0, π] is
//     ω(α, δ) = cos α·x + sin α·(cos δ·h + sin δ·z),   α ∈ [0, π],
// dω = sin α dα dδ, and n·ω = sin α·cos(δ − β). The face sees the sky for δ ∈ [δ_min, δ_max] =
// [max(0, β − π/2), min(π, β + π/2)]. The δ-weight cos(δ − β) is uniform in s = sin(δ − β), so
// equal-weight bands are equal steps in s over [s_min, s_max] = [sin(δ_min − β), sin(δ_max − β)];
// total weight W = s_max − s_min (2 for a horizontal face, 1 for a wall).
#include <vector>

#include "geometry/core/vec3.h"

namespace skyband {

// Azimuth of x for horizontal faces, radians counter-clockwise from +x (east) in the world frame.
inline constexpr double kHorizontalAxisAzimuth = 0.3;

struct BandFrame {
  Vec3 x;                    // pencil axis (unit, horizontal, in the face plane)
  Vec3 h;                    // z × x (unit, horizontal)
  Vec3 z{0, 0, 1};           // up
  Vec3 normal;               // unit face normal
  double beta_rad = 0;       // elevation of the normal, n = cos β·h + sin β·z
  double delta_min_rad = 0;  // sky seen by the face: δ ∈ [delta_min, delta_max]
  double delta_max_rad = 0;
  double s_min = 0;  // sin(δ_min − β)
  double s_max = 0;  // sin(δ_max − β)

  // Total δ-weight W = ∫ cos(δ − β) dδ over the visible δ range (= s_max − s_min).
  double total_weight() const { return s_max - s_min; }
  // δ of the point with cumulative weight s ∈ [s_min, s_max]: δ = β + asin(s).
  double delta_at(double s) const;
  // Unit direction ω(α, δ).
  Vec3 direction(double alpha_rad, double delta_rad) const;
  // (α, δ) of a unit direction; δ ∈ (−π, π] (sky directions with ω·z ≥ 0 have δ ∈ [0, π]).
  void angles_of(const Vec3& dir, double& alpha_rad, double& delta_rad) const;

  // Frame of a point with (not necessarily unit, non-zero, finite) normal.
  static BandFrame make(const Vec3& normal);
};

// One band: the δ-interval [s0, s1] in weight space represented by the sample plane at its
// weight median (seed: d_l = 1/N; method.md §2 "equal-weight bands").
struct Band {
  double s0 = 0, s1 = 0;  // weight-space edges, s = sin(δ − β)
  double weight() const { return s1 - s0; }
  double s_centre() const { return 0.5 * (s0 + s1); }
};

// N equal-weight bands covering the face's sky.
std::vector<Band> equal_weight_bands(const BandFrame& frame, int band_count);

}  // namespace skyband
