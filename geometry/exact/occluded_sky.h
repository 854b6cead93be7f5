#pragma once
// The occluded sky of a point: the exact union of the occluders' projections onto the sphere of
// directions around the point, kept over azimuth (the exact visible sky of any triangle soup,
// geometry/exact/exact_sky.h).
//
// Seen from a point P, a planar convex occluder not containing P covers, in each azimuth of its
// azimuth range, one closed interval of elevations between two of its edges' great-circle arcs;
// an occluder over or under P (its xy projection holds P's) covers up to the zenith or down to the
// nadir in every azimuth. So in every azimuth the occluded sky is a finite union of closed
// elevation intervals, each bounded by great circles through P. This class keeps that union over
// a "diamond angle" of azimuth t ∈ [0, 4) (geometry/horizon/horizon_envelope.h: strictly monotone, no
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

#include "geometry/core/pseudo_angle.h"  // diamond_angle, diamond_direction
#include "geometry/horizon/horizon_envelope.h"

namespace skyband {

class OccludedSky {
 public:
  static constexpr int kCoarseBins = 32;
  static constexpr int kFinePerCoarse = 32;
  static constexpr int kBins = kCoarseBins * kFinePerCoarse;
  static constexpr double kBinsPerUnit = kBins / 4.0;  // a power of two: bin edges are exact
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
  std::size_t circle_count() const { return circle_.size(); }

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
  std::size_t splices() const { return splices_; }  // insertions into a segment that changed it (statistics)
  void clear_changed() { changed_ = false; }

  // Conservative: is everything with tan e in [bottom, top] over the azimuth range [lo, hi]
  // (0 ≤ lo ≤ hi, hi may exceed 4: wraps) already occluded — below the grounded interval's top or
  // above the lowest ceiling's bottom in every bin? bottom ≤ 0 means "from below the horizon".
  bool hidden(double lo, double hi, double top, double bottom) const;
  // Not conservative: would everything with tan e ≤ top over [lo, hi] be occluded if every gap
  // below the highest interval (under a ceiling, below the one beneath it) closed? A gap under a
  // terrain triangle or a wall standing on a terrain above the point's height usually closes once
  // the nearer surface is in; the walk defers what this hides and checks it against the union as it
  // is when the queue runs dry (exact_sky.cpp).
  bool hidden_if_gaps_close(double lo, double hi, double top) const;

  // Calls f(t0, w0x, w0y, t1, w1x, w1y, boundaries) for every piece in order of t (boundaries: the
  // sorted circle ids B₀ = kGround, B₁, …, an even count).
  template <class F>
  void for_each_piece(F&& f) const {
    std::uint32_t two[2];
    for (int g = 0; g < kCoarseBins; ++g) {
      const Segment& s = segments_[g];
      for (std::size_t j = 0; j < s.pieces.size(); ++j) {
        const Piece& q = s.pieces[j];
        double t1, w1x, w1y;
        end_of(g, j, t1, w1x, w1y);
        f(q.t0, q.wx, q.wy, t1, w1x, w1y, ids_of(s, q, two));
      }
    }
  }
  std::size_t piece_count() const;
  // Whether some piece has more than the grounded interval (a gap below an occluder or a ceiling).
  bool has_upper_intervals() const;

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  struct Piece {
    double t0;             // start; it ends where the next piece of its segment starts, or at the segment's end
    double wx, wy;         // unit horizontal direction at t0
    double g0, g1;         // tan e of the grounded interval's top (B₁) at the start and the end
    double flo;            // an upper bound of the first floating interval's bottom (B₂) over the piece (+∞: none)
    double cmax;           // an upper bound of the lowest ceiling's bottom over the piece (+∞: no ceiling)
    std::uint32_t top;     // B₁
    std::uint32_t off, n;  // n boundaries: {kGround, top} when n = 2, else pool[off .. off + n)
  };
  struct Segment {
    std::vector<Piece> pieces;
    std::vector<std::uint32_t> pool;
    int uppers = 0;  // pieces with n > 2
  };
  // A piece under construction (insertion scratch).
  struct NewPiece {
    double t0, wx, wy;
    std::uint32_t top;
    std::uint32_t off, n;  // n > 2: in the segment's pool (pooled: an unchanged list) or in scratch_ids_
    bool pooled;
  };
  static std::span<const std::uint32_t> ids_of(const Segment& s, const Piece& q, std::uint32_t (&two)[2]) {
    if (q.n == 2) {
      two[0] = kGround, two[1] = q.top;
      return {two, 2};
    }
    return {s.pool.data() + q.off, q.n};
  }

  void end_of(int g, std::size_t j, double& t1, double& wx, double& wy) const {
    const Segment& s = segments_[g];
    if (j + 1 < s.pieces.size()) {
      const Piece& n = s.pieces[j + 1];
      t1 = n.t0, wx = n.wx, wy = n.wy;
    } else {
      const int b = (g + 1) * kFinePerCoarse;
      t1 = double(b) / kBinsPerUnit, wx = edge_x_[b], wy = edge_y_[b];
    }
  }
  static std::size_t piece_at(const std::vector<Piece>& pieces, double t);
  void insert_range(std::uint32_t lo, std::uint32_t hi, double ta, double tb, double wax, double way, double wbx, double wby);
  void insert_in_segment(int g, std::uint32_t lo, std::uint32_t hi, double ta, double tb, double wax, double way, double wbx,
                         double wby);
  // Unites [lo, hi] into one sub-range [s0, s1] of a piece whose boundaries are `b`, where no
  // circle crosses another; appends the resulting piece to scratch_. Whether the union grew.
  // va and vb hold the values of b's circles, then lo's and hi's, at its two ends.
  bool unite_sub_range(std::span<const std::uint32_t> b, const Piece& q, std::uint32_t lo, std::uint32_t hi, double s0,
                       double s0x, double s0y, const double* va, const double* vb, double s1x, double s1y);
  // The grounded-only insertion (no piece of segment g has more than the grounded interval, and
  // [lo, hi] reaches down into it over the whole range): the envelope's update, B₁ := max(B₁, hi).
  void raise_in_segment(int g, std::uint32_t hi, double ta, double tb, double wax, double way, double wbx, double wby);
  void splice(int g, std::size_t lo_piece, std::size_t hi_piece, std::size_t n, double chg_lo, double chg_hi);
  // −1, 0, +1: circle x below, equal to or above circle y over a sub-range without crossings, from
  // their values at its two ends (xa, ya at direction a; xb, yb at b).
  int order(std::uint32_t x, std::uint32_t y, double xa, double ya, double xb, double yb, double ax, double ay, double bx,
            double by) const;
  void finish_piece(const Segment& s, Piece& q, double t1x, double t1y) const;
  void update_bins(int g, double lo, double hi) const;
  // The bins of segment g brought up to date (they are recomputed lazily, when a range test reads
  // them: most insertions are followed by others in the same segments first).
  void ensure_bins(int g) const {
    if (dirty_lo_[g] <= dirty_hi_[g]) {
      update_bins(g, dirty_lo_[g], dirty_hi_[g]);
      dirty_lo_[g] = kInf, dirty_hi_[g] = -kInf;
    }
  }
  bool grounded_at_least(int b, double lo, double hi, double bound) const;

  static const double* const edge_x_;  // unit directions of the bin edges (kBins + 1)
  static const double* const edge_y_;
  std::vector<std::uint32_t> pool_scratch_;  // a segment's pool being rebuilt (swapped with it)
  std::vector<std::array<double, 2>> circle_;
  std::array<Segment, kCoarseBins> segments_;
  mutable std::array<double, kBins> gmin_{};  // exact minimum of B₁ over each fine bin
  mutable std::array<double, kBins> cmax_{};  // upper bound of the lowest ceiling's bottom (+∞: none somewhere)
  mutable std::array<double, kBins> flo_{};   // upper bound of the first floating interval's bottom (+∞: none somewhere)
  mutable std::array<double, kBins> fhi_{};   // exact minimum of its top (−∞: none somewhere)
  mutable std::array<double, kBins>
      ohi_{};  // minimum of the first floating interval's top where there is one (not a ceiling), else of B₁
  mutable std::array<double, kCoarseBins> coarse_gmin_{};
  mutable std::array<double, kCoarseBins> coarse_ohi_{};
  mutable std::array<double, kCoarseBins> coarse_cmax_{};
  mutable std::array<double, kCoarseBins> coarse_flo_{};
  mutable std::array<double, kCoarseBins> coarse_fhi_{};
  mutable std::array<double, kCoarseBins> dirty_lo_{}, dirty_hi_{};  // where the bins are out of date
  std::vector<std::uint16_t> touched_;
  std::array<bool, kCoarseBins> is_touched_{};
  std::vector<NewPiece> scratch_;
  struct Overlap {  // raise_in_segment's first pass: one overlapped piece
    double u0, w0x, w0y, u1, w1x, w1y, s1, e0, e1;
  };
  std::vector<Overlap> raise_;
  std::vector<std::uint32_t> scratch_ids_;
  std::vector<double> cuts_;
  std::vector<double> ends_, cut_vals_;  // boundary values at an overlap's ends and at its cuts
  bool changed_ = false;
  std::size_t splices_ = 0;
  int uppers_ = 0;  // pieces with more than the grounded interval were made since reset() (enables their tests)
  // An upper bound of circle c's tan e over a piece (its peak where that lies inside).
  double circle_max(std::uint32_t c, double t0, double w0x, double w0y, double w1x, double w1y) const;
};

}  // namespace skyband
