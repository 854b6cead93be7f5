#pragma once
// The occluded sky of a point: the exact union of the occluders' projections onto the sphere of
// directions around the point, kept over azimuth (the exact visible sky of any triangle soup,
// geometry/exact_sky.h).
//
// Seen from a point P, a planar convex occluder not containing P covers, in each azimuth of its
// azimuth range, one closed interval of elevations between two of its edges' great-circle arcs;
// an occluder over or under P (its xy projection holds P's) covers up to the zenith or down to the
// nadir in every azimuth. So in every azimuth the occluded sky is a finite union of closed
// elevation intervals, each bounded by great circles through P. This class keeps that union over
// a "diamond angle" of azimuth t ∈ [0, 4) (geometry/horizon_envelope.h: strictly monotone, no
// trigonometry) as sorted *pieces*: in a piece the bounding circles do not cross, so the union is
// one sorted list of boundary circles B₀ < B₁ < … (the intervals [B₀, B₁], [B₂, B₃], …).
//
// A circle is stored by its slope coefficients (a, b): along a unit horizontal direction w its
// elevation e has tan e = a·w_x + b·w_y. Two special circles bound every list: kGround (tan e =
// −∞, the nadir) and kZenith (+∞); B₀ is always kGround, because the sky below the point's
// horizontal is never sky: the union starts as [kGround, kHorizon] all round. So B₁ ≥ 0 is the top
// of the *grounded* interval — the horizon when every occluder in that azimuth rises from below the
// point's height, as walls do — and the sky is visible between B₁ and B₂ (or the zenith) and in
// every further gap: under an overhang, a bridge or a balcony.
//
// Insertion of an interval [L, H] over an azimuth range cuts the pieces it overlaps where L or H
// crosses one of their circles (two great-circle arcs over less than π cross at most once, where
// their difference — linear in the unit direction — changes sign), then unites per sub-range by
// counting (closed intervals: touching ones merge, so two triangles sharing an edge, whose arcs
// are bit-identical, leave no gap). Pieces are cut at the edges of 32 segments, so an insertion
// shifts only the pieces of the segments it covers; 1024 fine bins keep, for culling, the exact
// minimum of the grounded interval's top and an upper bound of the lowest ceiling (an interval
// reaching the zenith) over each bin.
//
// Exactness: circle values and crossings are constructions (rounding-level errors; the visible
// sky is continuous in them, so no decision among nearly equal arcs changes its measure by more
// than their difference). Range tests for culling are conservative.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "geometry/horizon_envelope.h"  // diamond_angle, diamond_direction

namespace skyband {

class OccludedSky {
 public:
  static constexpr int kCoarseBins = 32;
  static constexpr int kFinePerCoarse = 32;
  static constexpr int kBins = kCoarseBins * kFinePerCoarse;
  static constexpr double kBinsPerUnit = kBins / 4.0;          // a power of two: bin edges are exact
  static constexpr double kSegmentsPerUnit = kCoarseBins / 4.0;
  // Circle ids: the nadir, the zenith and the point's horizontal plane.
  static constexpr std::uint32_t kGround = 0, kZenith = 1, kHorizon = 2;

  OccludedSky();

  // [kGround, kHorizon] all round; forgets every circle but the three above.
  void reset();
  // A circle with tan e = a·w_x + b·w_y; returns its id.
  std::uint32_t add_circle(double a, double b) {
    circle_.push_back({a, b});
    return std::uint32_t(circle_.size() - 1);
  }
  double value(std::uint32_t c, double wx, double wy) const {
    if (c <= kZenith) return c == kGround ? -kInf : kInf;
    return circle_[c][0] * wx + circle_[c][1] * wy;
  }
  const std::array<double, 2>& coefficients(std::uint32_t c) const { return circle_[c]; }

  // Unites the interval between circles lo and hi (lo ≤ hi over the range; where rounding makes
  // lo > hi nothing is added) over the azimuth range from t0 counter-clockwise to t1, the shorter
  // way (less than 2 apart, or more than 2 through t = 0); w0, w1 their unit directions.
  void insert(std::uint32_t lo, std::uint32_t hi, double t0, double w0x, double w0y, double t1, double w1x, double w1y);
  // The same over exactly half a turn, from t0 counter-clockwise through tmid to t1.
  void insert_half_turn(std::uint32_t lo, std::uint32_t hi, double t0, double tmid, double t1);
  // The same all round (four quarter turns).
  void insert_full_turn(std::uint32_t lo, std::uint32_t hi);
  // Whether an insertion has changed the union since reset() or clear_changed().
  bool changed() const { return changed_; }
  void clear_changed() { changed_ = false; }

  // Conservative: is everything with tan e in [bottom, top] over the azimuth range [lo, hi]
  // (0 ≤ lo ≤ hi, hi may exceed 4: wraps) already occluded — below the grounded interval's top or
  // above the lowest ceiling's bottom in every bin? bottom ≤ 0 means "from below the horizon".
  bool hidden(double lo, double hi, double top, double bottom) const;

  // Calls f(t0, w0x, w0y, t1, w1x, w1y, boundaries) for every piece in order of t (boundaries: the
  // sorted circle ids B₀ = kGround, B₁, …, an even count).
  template <class F>
  void for_each_piece(F&& f) const {
    for (int g = 0; g < kCoarseBins; ++g) {
      const Segment& s = segments_[g];
      for (std::size_t j = 0; j < s.pieces.size(); ++j) {
        const Piece& q = s.pieces[j];
        double t1, w1x, w1y;
        end_of(g, j, t1, w1x, w1y);
        f(q.t0, q.wx, q.wy, t1, w1x, w1y, std::span<const std::uint32_t>(s.pool.data() + q.off, q.n));
      }
    }
  }
  std::size_t piece_count() const;
  // Whether some piece has more than the grounded interval (a gap below an occluder or a ceiling).
  bool has_upper_intervals() const;

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  struct Piece {
    double t0;      // start; it ends where the next piece of its segment starts, or at the segment's end
    double wx, wy;  // unit horizontal direction at t0
    double g0, g1;  // tan e of the grounded interval's top (B₁) at the start and the end
    double flo;     // an upper bound of the first floating interval's bottom (B₂) over the piece (+∞: none)
    double cmax;    // an upper bound of the lowest ceiling's bottom over the piece (+∞: no ceiling)
    std::uint32_t off, n;  // boundaries: pool[off .. off + n)
  };
  struct Segment {
    std::vector<Piece> pieces;
    std::vector<std::uint32_t> pool;
  };
  // A piece under construction (insertion scratch).
  struct NewPiece {
    double t0, wx, wy;
    std::uint32_t off, n;  // in scratch_ids_
  };

  void end_of(int g, std::size_t j, double& t1, double& wx, double& wy) const;
  static std::size_t piece_at(const std::vector<Piece>& pieces, double t);
  void insert_range(std::uint32_t lo, std::uint32_t hi, double ta, double tb, double wax, double way, double wbx,
                    double wby);
  void insert_in_segment(int g, std::uint32_t lo, std::uint32_t hi, double ta, double tb, double wax, double way,
                         double wbx, double wby);
  // Unites [lo, hi] into one sub-range [s0, s1] of a piece whose boundaries are `b`, where no
  // circle crosses another; appends the resulting piece(s) to scratch_.
  void unite_sub_range(std::span<const std::uint32_t> b, std::uint32_t lo, std::uint32_t hi, double s0, double s0x,
                       double s0y, double s1, double s1x, double s1y);
  // −1, 0, +1: circle x below, equal to or above circle y over a sub-range without crossings,
  // from their values at its two ends.
  int compare(std::uint32_t x, std::uint32_t y, double ax, double ay, double bx, double by) const;
  void finish_piece(Piece& q, const std::uint32_t* ids, double t1x, double t1y) const;
  void update_bins(int g, double lo, double hi);
  bool grounded_at_least(int b, double lo, double hi, double bound) const;

  std::vector<std::array<double, 2>> circle_;
  std::array<Segment, kCoarseBins> segments_;
  std::array<double, kBins> gmin_{};            // exact minimum of B₁ over each fine bin
  std::array<double, kBins> cmax_{};            // upper bound of the lowest ceiling's bottom (+∞: none somewhere)
  std::array<double, kBins> flo_{};             // upper bound of the first floating interval's bottom (+∞: none somewhere)
  std::array<double, kBins> fhi_{};             // exact minimum of its top (−∞: none somewhere)
  std::array<double, kCoarseBins> coarse_gmin_{};
  std::array<double, kCoarseBins> coarse_cmax_{};
  std::array<double, kCoarseBins> coarse_flo_{};
  std::array<double, kCoarseBins> coarse_fhi_{};
  std::vector<std::uint16_t> touched_;
  std::array<bool, kCoarseBins> is_touched_{};
  std::vector<NewPiece> scratch_;
  std::vector<std::uint32_t> scratch_ids_;
  std::vector<double> cuts_;
  bool changed_ = false;
  int uppers_ = 0;  // pieces with more than the grounded interval were made since reset() (enables their tests)
  // An upper bound of circle c's tan e over a piece (its peak where that lies inside).
  double circle_max(std::uint32_t c, double t0, double w0x, double w0y, double w1x, double w1y) const;
};

}  // namespace skyband
