#pragma once
// The upper envelope, over azimuth, of great-circle arcs seen from a point: the horizon of the
// exact horizon method (geometry/horizon/horizon_svf.h).
//
// Azimuth is kept as a "diamond angle" t ∈ [0, 4) (no trigonometry in the hot loop). A great
// circle through the point that is not vertical is stored by its slope coefficients (a, b): along
// a unit horizontal direction w its elevation e has tan e = a·w_x + b·w_y. The envelope is a list
// of pieces, each one circle over a range of t, cut at the edges of 32 segments (coarse bins):
// an insertion shifts and searches only the pieces of the segments it covers. Each of 1024 fine
// bins (32 per segment) keeps the exact minimum of the envelope over it, and each segment the
// least of its bins', so a range test reads bin minima first and pieces only in its end bins.
//
// Why 32 segments of 32 bins (callgrind inside HorizonSvf::compute, instructions per point,
// bench_svf --large-only on the 1M-triangle city / --small-only on the 10k one): segments × bins
// per segment of 64 × 16 / 32 × 32 / 32 × 16 / 16 × 32 / 16 × 64 take 1.05 / 1.04 / 1.09 / 1.09 /
// 1.08 M and 233 / 219 / 205 / 201 / 226 k; 32 × 32 is the best compromise for both. Pieces cut
// per fine bin instead of per segment cost ~1.5× (a near facade's insertion then rewrites
// hundreds of bins).
//
// Exactness: the values are constructions (rounding-level errors, and the result is continuous in
// them). Range tests are conservative: a piece's minimum over any part of it is at one of the
// part's ends (c·w is concave along an arc shorter than π where it is ≥ 0), so bin minima are
// exact minima of the stored envelope.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "geometry/core/pseudo_angle.h"  // diamond_angle, diamond_direction

namespace skyband {

// Azimuth range [lo, hi] (diamond angles, lo ≤ hi, hi may exceed 4: through t = 0) of an xy box
// seen from outside it, the box given by its offsets x0 ≤ x1, y0 ≤ y1 from the point (not all
// containing 0): from its first corner counter-clockwise to its last, which depend on where the
// point lies around it. Less than a half turn.
inline void box_azimuth_range(double x0, double x1, double y0, double y1, double& lo, double& hi) {
  double sx, sy, ex, ey;
  if (y0 > 0) {  // box above the point
    sx = x1, sy = x1 > 0 ? y0 : y1;
    ex = x0, ey = x0 < 0 ? y0 : y1;
  } else if (y1 < 0) {  // below
    sx = x0, sy = x0 < 0 ? y1 : y0;
    ex = x1, ey = x1 > 0 ? y1 : y0;
  } else if (x0 > 0) {  // right, straddling y = 0
    sx = x0, sy = y0, ex = x0, ey = y1;
  } else {  // left, straddling y = 0
    sx = x1, sy = y1, ex = x1, ey = y0;
  }
  lo = diamond_angle(sx, sy);
  hi = diamond_angle(ex, ey);
  if (hi < lo) hi += 4;
}

class HorizonEnvelope {
 public:
  static constexpr int kFinePerCoarse = 32;  // a multiple of 4
  static constexpr int kCoarseBins = 32;
  static constexpr int kBins = kCoarseBins * kFinePerCoarse;
  static constexpr double kBinsPerUnit = kBins / 4.0;  // a power of two: bin edges are exact
  // Circle ids: 0 the horizon (tan e = 0), 1 "blocked" (no sky: behind a vertical face).
  static constexpr std::uint32_t kHorizon = 0, kBlocked = 1;

  HorizonEnvelope();

  // The horizon all round; forgets every circle but the two above.
  void reset();
  // A circle with tan e = a·w_x + b·w_y; returns its id.
  std::uint32_t add_circle(double a, double b) {
    circle_.push_back({a, b});
    return std::uint32_t(circle_.size() - 1);
  }
  // tan(elevation) of circle c along the unit horizontal direction w (+∞ for kBlocked).
  double value(std::uint32_t c, double wx, double wy) const {
    if (c == kBlocked) return std::numeric_limits<double>::infinity();
    return circle_[c][0] * wx + circle_[c][1] * wy;
  }

  // Raises the envelope to circle c over the range between diamond angles t0 and t1 the shorter
  // way (less than 2 apart, or more than 2 through t = 0), whose unit directions are w0 and w1.
  // Exactly 2 apart (an arc over the point) inserts nothing.
  void insert_range(std::uint32_t c, double t0, double w0x, double w0y, double t1, double w1x, double w1y);
  // Raises it to circle c over exactly half a turn, from t0 counter-clockwise through tmid to t1.
  void insert_half_turn(std::uint32_t c, double t0, double tmid, double t1);
  // Whether an insertion has raised the envelope since reset() or clear_raised().
  bool raised() const { return raised_; }
  void clear_raised() { raised_ = false; }

  // Is the envelope ≥ bound (tan of elevation) all over the azimuth range [lo, hi] (0 ≤ lo ≤ hi;
  // hi may exceed 4: wraps)? Conservative in the stored envelope: exact from bin minima and, in
  // the end bins where those do not decide, from the pieces.
  bool hidden_below(double lo, double hi, double bound) const {
    if (hi > 4.0) return hidden_below(lo, 4.0, bound) && hidden_below(0.0, hi - 4.0, bound);
    const int b0 = std::min(kBins - 1, int(lo * kBinsPerUnit)), b1 = std::min(kBins - 1, int(hi * kBinsPerUnit));
    // The bins wholly inside the range first (a minimum below the bound decides), then the two
    // end bins, from their pieces where their minimum does not decide.
    for (int g = b0 / kFinePerCoarse; g <= b1 / kFinePerCoarse; ++g) {
      if (coarse_min_[g] >= bound) continue;
      const int f0 = std::max(b0 + 1, g * kFinePerCoarse), f1 = std::min(b1 - 1, g * kFinePerCoarse + kFinePerCoarse - 1);
      for (int b = f0; b <= f1; ++b)
        if (bin_min_[b] < bound) return false;
    }
    if (bin_min_[b0] < bound && !bin_at_least(b0, lo, std::min(hi, double(b0 + 1) / kBinsPerUnit), bound)) return false;
    return b1 == b0 || bin_min_[b1] >= bound || bin_at_least(b1, double(b1) / kBinsPerUnit, hi, bound);
  }

  // Calls f(t0, t1, circle) for the envelope's maximal runs of one circle, in order of t from 0
  // to 4 (runs of kBlocked included).
  template <class F>
  void for_each_run(F&& f) const {
    double start = 0.0;
    std::uint32_t c = segments_[0].front().circle;
    for (const std::vector<Piece>& pieces : segments_)
      for (const Piece& q : pieces)
        if (q.circle != c) {
          if (q.t0 > start) f(start, q.t0, c);
          start = q.t0;
          c = q.circle;
        }
    f(start, 4.0, c);
  }
  std::size_t run_count() const;

 private:
  struct Piece {
    double t0;      // start; the piece ends where the next of its segment begins, or at the segment's end
    double wx, wy;  // unit horizontal direction at t0
    std::uint32_t circle;
    double v0, v1;  // tan e at the start and the end (its minimum over the piece is one of them)
  };
  static std::size_t piece_at(const std::vector<Piece>& pieces, double t);
  bool bin_at_least(int b, double lo, double hi, double bound) const;
  void insert(std::uint32_t c, double ta, double tb, double wax, double way, double wbx, double wby);
  void insert_in_segment(int g, std::uint32_t c, double ta, double tb, double wax, double way, double wbx, double wby);
  void update_bins(int g, double lo, double hi);

  std::vector<std::array<double, 2>> circle_;
  // The pieces of each coarse bin ("segment"), sorted by t0, the first at the segment's start.
  std::array<std::vector<Piece>, kCoarseBins> segments_;
  std::array<double, kBins> bin_min_{};           // exact minimum of the envelope over each fine bin
  std::array<double, kCoarseBins> coarse_min_{};  // the least of its fine bins' minima
  std::vector<std::uint16_t> touched_;            // segments changed since reset()
  std::array<bool, kCoarseBins> is_touched_{};
  std::vector<Piece> scratch_;
  bool raised_ = false;
};

}  // namespace skyband
