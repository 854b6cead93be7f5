#include "geometry/exact/occluded_sky.h"

#include <algorithm>

namespace skyband {

namespace {

// Unit directions of the bin edges, t = b / kBinsPerUnit, b = 0 … kBins.
struct BinEdges {
  std::array<double, OccludedSky::kBins + 1> x, y;
  BinEdges() {
    for (int b = 0; b <= OccludedSky::kBins; ++b) diamond_direction(double(b) / OccludedSky::kBinsPerUnit, x[b], y[b]);
  }
};
const BinEdges& bin_edges() {
  static const BinEdges e;
  return e;
}

// Values within this relative distance of each other at a sub-range's end count as equal there (a
// crossing computed to rounding lands within it).
constexpr double kSnap = 1e-14;

}  // namespace

const double* const OccludedSky::edge_x_ = bin_edges().x.data();
const double* const OccludedSky::edge_y_ = bin_edges().y.data();

OccludedSky::OccludedSky() {
  for (int g = 0; g < kCoarseBins; ++g) is_touched_[g] = true, touched_.push_back(std::uint16_t(g));
  reset();
}

void OccludedSky::reset() {
  circle_.assign(3, {0.0, 0.0});  // kGround and kZenith are never read; kHorizon is tan e = 0
  for (const std::uint16_t g : touched_) {
    const int b = g * kFinePerCoarse;
    Segment& s = segments_[g];
    s.pool.clear();
    s.uppers = 0;
    s.pieces.assign(1, Piece{double(b) / kBinsPerUnit, edge_x_[b], edge_y_[b], 0.0, 0.0, kInf, kInf, kHorizon, 0, 2});
    std::fill(gmin_.begin() + b, gmin_.begin() + b + kFinePerCoarse, 0.0);
    std::fill(ohi_.begin() + b, ohi_.begin() + b + kFinePerCoarse, 0.0);
    coarse_ohi_[g] = 0.0;
    std::fill(cmax_.begin() + b, cmax_.begin() + b + kFinePerCoarse, kInf);
    std::fill(flo_.begin() + b, flo_.begin() + b + kFinePerCoarse, kInf);
    std::fill(fhi_.begin() + b, fhi_.begin() + b + kFinePerCoarse, -kInf);
    coarse_gmin_[g] = 0.0;
    coarse_cmax_[g] = kInf;
    coarse_flo_[g] = kInf;
    coarse_fhi_[g] = -kInf;
    dirty_lo_[g] = kInf, dirty_hi_[g] = -kInf;
    is_touched_[g] = false;
  }
  touched_.clear();
  changed_ = false;
  uppers_ = 0;
}

std::size_t OccludedSky::piece_count() const {
  std::size_t n = 0;
  for (const Segment& s : segments_) n += s.pieces.size();
  return n;
}

bool OccludedSky::has_upper_intervals() const {
  for (const Segment& s : segments_)
    if (s.uppers > 0) return true;
  return false;
}

std::size_t OccludedSky::piece_at(const std::vector<Piece>& pieces, double t) {
  std::size_t lo = 0, n = pieces.size();  // pieces[lo].t0 ≤ t (the first starts at the segment's start)
  while (n > 1) {                         // branch-free: the outcome of each step is unpredictable
    const std::size_t half = n / 2;
    lo = pieces[lo + half].t0 <= t ? lo + half : lo;
    n -= half;
  }
  return lo;
}

void OccludedSky::insert(std::uint32_t lo, std::uint32_t hi, double t0, double w0x, double w0y, double t1, double w1x,
                         double w1y) {
  if (t0 > t1) {
    std::swap(t0, t1);
    std::swap(w0x, w1x);
    std::swap(w0y, w1y);
  }
  if (t1 - t0 < 2) {
    if (t0 < t1) insert_range(lo, hi, t0, t1, w0x, w0y, w1x, w1y);
  } else if (t1 - t0 > 2) {
    insert_range(lo, hi, t1, 4.0, w1x, w1y, 1.0, 0.0);
    if (t0 > 0) insert_range(lo, hi, 0.0, t0, 1.0, 0.0, w0x, w0y);
  }
  // exactly 2 apart: no shorter way; callers split half turns (insert_half_turn).
}

void OccludedSky::insert_half_turn(std::uint32_t lo, std::uint32_t hi, double t0, double tmid, double t1) {
  const double cuts[3] = {t0, tmid, t1};
  for (int k = 0; k < 2; ++k) {
    double ax, ay, bx, by;
    diamond_direction(cuts[k], ax, ay);
    diamond_direction(cuts[k + 1], bx, by);
    insert(lo, hi, cuts[k], ax, ay, cuts[k + 1], bx, by);
  }
}

void OccludedSky::insert_full_turn(std::uint32_t lo, std::uint32_t hi) {
  for (int k = 0; k < 4; ++k) {
    double ax, ay, bx, by;
    diamond_direction(k, ax, ay);
    diamond_direction(k + 1, bx, by);
    insert_range(lo, hi, k, k + 1, ax, ay, bx, by);
  }
}

void OccludedSky::insert_range(std::uint32_t lo, std::uint32_t hi, double ta, double tb, double wax, double way, double wbx,
                               double wby) {
  const int g0 = std::min(kCoarseBins - 1, int(ta * kSegmentsPerUnit));
  int g1 = int(tb * kSegmentsPerUnit);
  if (double(g1) == tb * kSegmentsPerUnit) --g1;  // tb on a segment edge
  g1 = std::clamp(g1, g0, kCoarseBins - 1);
  for (int g = g0; g <= g1; ++g) {
    const int b = g * kFinePerCoarse, b_end = b + kFinePerCoarse;
    const double s0 = double(g) / kSegmentsPerUnit, s1 = double(g + 1) / kSegmentsPerUnit;
    const bool from_edge = s0 > ta, to_edge = s1 < tb;
    const double u0 = from_edge ? s0 : ta, u1 = to_edge ? s1 : tb;
    if (!(u0 < u1)) continue;
    const double x0 = from_edge ? edge_x_[b] : wax, y0 = from_edge ? edge_y_[b] : way;
    const double x1 = to_edge ? edge_x_[b_end] : wbx, y1 = to_edge ? edge_y_[b_end] : wby;
    insert_in_segment(g, lo, hi, u0, u1, x0, y0, x1, y1);
  }
}

int OccludedSky::order(std::uint32_t x, std::uint32_t y, double xa, double ya, double xb, double yb, double ax, double ay,
                       double bx, double by) const {
  if (x == y) return 0;
  if (x == kGround || y == kZenith) return -1;
  if (y == kGround || x == kZenith) return 1;
  const auto snap = [](double d, double u, double v) { return std::abs(d) <= kSnap * (std::abs(u) + std::abs(v)) ? 0.0 : d; };
  const double da = snap(xa - ya, xa, ya), db = snap(xb - yb, xb, yb);
  if (da >= 0 && db >= 0) return da > 0 || db > 0 ? 1 : 0;
  if (da <= 0 && db <= 0) return -1;
  // Opposite signs at the two ends: a crossing inside that the cut missed by rounding; decide in
  // the middle.
  double mx = ax + bx, my = ay + by;
  const double r = 1.0 / std::sqrt(mx * mx + my * my);
  mx *= r, my *= r;
  const double dm = value(x, mx, my) - value(y, mx, my);
  return dm > 0 ? 1 : dm < 0 ? -1 : 0;
}

bool OccludedSky::unite_sub_range(std::span<const std::uint32_t> b, const Piece& q, std::uint32_t lo, std::uint32_t hi, double s0,
                                  double s0x, double s0y, const double* va, const double* vb, double s1x, double s1y) {
  const std::size_t n = b.size();
  const auto keep = [&] { scratch_.push_back(NewPiece{s0, s0x, s0y, q.top, q.off, q.n, true}); };
  // va, vb: the values of b[0..n), lo, hi at the sub-range's two ends.
  const auto cmp = [&](std::uint32_t x, std::size_t ix, std::uint32_t y, std::size_t iy) {
    return order(x, y, va[ix], va[iy], vb[ix], vb[iy], s0x, s0y, s1x, s1y);
  };
  if (cmp(lo, n, hi, n + 1) >= 0) {  // empty here (lo = hi, or lo > hi by rounding)
    keep();
    return false;
  }
  // i: boundaries before lo, k: before hi, where a boundary equal to lo or hi counts as before it
  // when it is a lower bound (even index): closed intervals, touching ones merge.
  std::size_t i = 0;
  while (i < n) {
    const int c = cmp(b[i], i, lo, n);
    if (c < 0 || (c == 0 && (i & 1) == 0))
      ++i;
    else
      break;
  }
  std::size_t k = i;
  while (k < n) {
    const int c = cmp(b[k], k, hi, n + 1);
    if (c < 0 || (c == 0 && (k & 1) == 0))
      ++k;
    else
      break;
  }
  if ((i & 1) && (k & 1) && i == k) {  // inside one interval already
    keep();
    return false;
  }
  const std::size_t off = scratch_ids_.size();
  scratch_ids_.insert(scratch_ids_.end(), b.begin(), b.begin() + std::ptrdiff_t(i));
  if ((i & 1) == 0) scratch_ids_.push_back(lo);
  if ((k & 1) == 0) scratch_ids_.push_back(hi);
  scratch_ids_.insert(scratch_ids_.end(), b.begin() + std::ptrdiff_t(k), b.end());
  const auto m = std::uint32_t(scratch_ids_.size() - off);
  const std::uint32_t top = scratch_ids_[off + 1];
  if (m == 2) scratch_ids_.resize(off);  // {kGround, top}: kept inline
  scratch_.push_back(NewPiece{s0, s0x, s0y, top, std::uint32_t(off), m, false});
  changed_ = true;
  return true;
}

double OccludedSky::circle_max(std::uint32_t c, double t0, double w0x, double w0y, double w1x, double w1y) const {
  if (c <= kZenith) return value(c, w0x, w0y);
  double m = std::max(value(c, w0x, w0y), value(c, w1x, w1y));
  // tan e = a·w_x + b·w_y peaks at w ∥ (a, b), where it is |(a, b)|.
  const double a = circle_[c][0], b = circle_[c][1];
  if (a != 0 || b != 0) {
    const double tp = diamond_angle(a, b);
    double t1 = diamond_angle(w1x, w1y);
    if (t1 <= t0) t1 += 4;  // the segment ending at t = 4
    if (tp >= t0 && tp <= t1) m = std::max(m, std::sqrt(a * a + b * b));
  }
  return m;
}

void OccludedSky::finish_piece(const Segment& s, Piece& q, double t1x, double t1y) const {
  q.g0 = value(q.top, q.wx, q.wy);
  q.g1 = value(q.top, t1x, t1y);
  q.cmax = kInf;
  q.flo = kInf;
  if (q.n == 2) {
    if (q.top == kZenith) q.cmax = -kInf;  // blocked: everything covered
    return;
  }
  const std::uint32_t* ids = s.pool.data() + q.off;
  q.flo = circle_max(ids[2], q.t0, q.wx, q.wy, t1x, t1y);
  if (ids[q.n - 1] == kZenith) q.cmax = q.n == 4 ? q.flo : circle_max(ids[q.n - 2], q.t0, q.wx, q.wy, t1x, t1y);
}

// Replaces pieces [lo_piece, hi_piece) of segment g by the first n of scratch_ (merged already),
// finishes them and marks the bins over [chg_lo, chg_hi] out of date.
void OccludedSky::splice(int g, std::size_t lo_piece, std::size_t hi_piece, std::size_t n, double chg_lo, double chg_hi) {
  Segment& s = segments_[g];
  std::vector<Piece>& pieces = s.pieces;
  ++splices_;
  if (!is_touched_[g]) {
    is_touched_[g] = true;
    touched_.push_back(std::uint16_t(g));
  }
  for (std::size_t k = lo_piece; k < hi_piece; ++k) s.uppers -= pieces[k].n > 2;
  const std::size_t replaced = hi_piece - lo_piece;
  if (n > replaced)
    pieces.insert(pieces.begin() + std::ptrdiff_t(hi_piece), n - replaced, Piece{});
  else if (n < replaced)
    pieces.erase(pieces.begin() + std::ptrdiff_t(lo_piece + n), pieces.begin() + std::ptrdiff_t(hi_piece));
  for (std::size_t k = 0; k < n; ++k) {
    const NewPiece& np = scratch_[k];
    Piece& q = pieces[lo_piece + k];
    q.t0 = np.t0, q.wx = np.wx, q.wy = np.wy, q.top = np.top, q.n = np.n, q.off = 0;
    if (np.n > 2) {
      ++s.uppers;
      if (np.pooled) {
        q.off = np.off;
      } else {
        q.off = std::uint32_t(s.pool.size());
        s.pool.insert(s.pool.end(), scratch_ids_.begin() + np.off, scratch_ids_.begin() + np.off + np.n);
      }
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    Piece& q = pieces[lo_piece + k];
    double t1, e1x, e1y;
    end_of(g, lo_piece + k, t1, e1x, e1y);
    finish_piece(s, q, e1x, e1y);
    if (q.n > 2 || q.cmax < kInf) ++uppers_;
  }
  // Rebuild the pool when it holds far more than the pieces use.
  if (s.pool.size() > 8 * pieces.size() + 64) {
    std::vector<std::uint32_t>& pool = pool_scratch_;
    pool.clear();
    for (Piece& q : pieces) {
      if (q.n <= 2) continue;
      const std::uint32_t off = std::uint32_t(pool.size());
      pool.insert(pool.end(), s.pool.begin() + q.off, s.pool.begin() + q.off + q.n);
      q.off = off;
    }
    s.pool.swap(pool);
  }
  dirty_lo_[g] = std::min(dirty_lo_[g], chg_lo);
  dirty_hi_[g] = std::max(dirty_hi_[g], chg_hi);
}

// The grounded case: every piece of segment g is {kGround, B₁} and the new interval reaches down
// to B₁ over [ta, tb], so only B₁ := max(B₁, hi) changes — on each piece at most once (two arcs
// over less than π differ by a function linear in the unit direction).
void OccludedSky::raise_in_segment(int g, std::uint32_t hi, double ta, double tb, double wax, double way, double wbx,
                                   double wby) {
  Segment& s = segments_[g];
  std::vector<Piece>& pieces = s.pieces;
  const std::size_t first = piece_at(pieces, ta);
  // First pass: hi against B₁ at both ends of each overlap; most insertions change nothing.
  raise_.clear();
  bool changed = false;
  {
    double u0 = ta, w0x = wax, w0y = way;
    double c0 = value(hi, w0x, w0y);
    for (std::size_t j = first; j < pieces.size() && pieces[j].t0 < tb; ++j) {
      const Piece& q = pieces[j];
      double s1, e1x, e1y;
      end_of(g, j, s1, e1x, e1y);
      const double p0 = q.t0 < u0 ? value(q.top, w0x, w0y) : q.g0;
      double u1, w1x, w1y, p1;
      if (tb < s1) {
        u1 = tb, w1x = wbx, w1y = wby;
        p1 = value(q.top, w1x, w1y);
      } else {
        u1 = s1, w1x = e1x, w1y = e1y, p1 = q.g1;
      }
      const double c1 = value(hi, w1x, w1y);
      // hi − B₁ at both ends; 0 where both are the same circle (the zenith: ∞ − ∞ would be NaN).
      const double e0 = hi == q.top ? 0.0 : c0 - p0, e1 = hi == q.top ? 0.0 : c1 - p1;
      raise_.push_back(Overlap{u0, w0x, w0y, u1, w1x, w1y, s1, e0, e1});
      changed = changed || e0 > 0 || e1 > 0;
      u0 = u1, w0x = w1x, w0y = w1y, c0 = c1;
    }
  }
  if (!changed) return;
  changed_ = true;
  scratch_.clear();
  const auto piece = [&](double t0, double wx, double wy, std::uint32_t top) {
    scratch_.push_back(NewPiece{t0, wx, wy, top, 0, 2, false});
  };
  const std::size_t lo_piece = first > 0 ? first - 1 : first;
  if (first > 0) piece(pieces[first - 1].t0, pieces[first - 1].wx, pieces[first - 1].wy, pieces[first - 1].top);
  double chg_lo = tb, chg_hi = ta;
  std::size_t j = first;
  for (const Overlap& o : raise_) {
    const Piece& q = pieces[j++];
    if (q.t0 < o.u0) piece(q.t0, q.wx, q.wy, q.top);  // head outside [ta, tb]
    const double e0 = o.e0, e1 = o.e1;
    if (!(e0 > 0 || e1 > 0)) {
      piece(o.u0, o.w0x, o.w0y, q.top);
    } else if (e0 >= 0 && e1 >= 0) {
      piece(o.u0, o.w0x, o.w0y, hi);
      chg_lo = std::min(chg_lo, o.u0), chg_hi = std::max(chg_hi, o.u1);
    } else {
      const double l = e0 / (e0 - e1);
      double cx = (1 - l) * o.w0x + l * o.w1x, cy = (1 - l) * o.w0y + l * o.w1y;
      const double r = 1.0 / std::sqrt(cx * cx + cy * cy);
      cx *= r, cy *= r;
      const double tc = std::clamp(diamond_angle(cx, cy), o.u0, o.u1);
      if (e0 > 0) {
        piece(o.u0, o.w0x, o.w0y, hi);
        piece(tc, cx, cy, q.top);
        chg_lo = std::min(chg_lo, o.u0), chg_hi = std::max(chg_hi, tc);
      } else {
        piece(o.u0, o.w0x, o.w0y, q.top);
        piece(tc, cx, cy, hi);
        chg_lo = std::min(chg_lo, tc), chg_hi = std::max(chg_hi, o.u1);
      }
    }
    if (o.u1 < o.s1) piece(o.u1, o.w1x, o.w1y, q.top);  // tail outside [ta, tb]
  }
  std::size_t hi_piece = j;
  if (hi_piece < pieces.size()) {
    piece(pieces[hi_piece].t0, pieces[hi_piece].wx, pieces[hi_piece].wy, pieces[hi_piece].top);
    ++hi_piece;
  }
  const double final_end = hi_piece < pieces.size() ? pieces[hi_piece].t0 : double((g + 1) * kFinePerCoarse) / kBinsPerUnit;
  std::size_t n = 0;
  for (std::size_t k = 0; k < scratch_.size(); ++k) {
    const double end = k + 1 < scratch_.size() ? scratch_[k + 1].t0 : final_end;
    if (end <= scratch_[k].t0) continue;                            // empty
    if (n > 0 && scratch_[n - 1].top == scratch_[k].top) continue;  // joins the previous
    scratch_[n++] = scratch_[k];
  }
  splice(g, lo_piece, hi_piece, n, chg_lo, chg_hi);
}

// Unites [lo, hi] over [ta, tb] inside segment g.
void OccludedSky::insert_in_segment(int g, std::uint32_t lo, std::uint32_t hi, double ta, double tb, double wax, double way,
                                    double wbx, double wby) {
  Segment& s = segments_[g];
  std::vector<Piece>& pieces = s.pieces;
  const std::size_t first = piece_at(pieces, ta);
  if (s.uppers == 0) {
    // Grounded-only segment: when lo reaches down to B₁ over every overlapped piece (at both ends of
    // each overlap: then all over it), the envelope's update does it.
    bool grounded = lo == kGround;
    if (!grounded) {
      grounded = true;
      double u0 = ta, w0x = wax, w0y = way;
      for (std::size_t j = first; grounded && j < pieces.size() && pieces[j].t0 < tb; ++j) {
        const Piece& q = pieces[j];
        double s1, e1x, e1y;
        end_of(g, j, s1, e1x, e1y);
        double u1, w1x, w1y;
        if (tb < s1)
          u1 = tb, w1x = wbx, w1y = wby;
        else
          u1 = s1, w1x = e1x, w1y = e1y;
        const double b0 = q.t0 == u0 ? q.g0 : value(q.top, w0x, w0y);
        const double b1 = u1 == s1 ? q.g1 : value(q.top, w1x, w1y);
        grounded = value(lo, w0x, w0y) <= b0 && value(lo, w1x, w1y) <= b1;
        u0 = u1, w0x = w1x, w0y = w1y;
      }
    }
    if (grounded) return raise_in_segment(g, hi, ta, tb, wax, way, wbx, wby);
  }
  scratch_.clear();
  scratch_ids_.clear();
  const bool was_changed = changed_;
  changed_ = false;
  double chg_lo = tb, chg_hi = ta;  // where the union grew
  const auto copy = [&](double t0, double wx, double wy, const Piece& q) {
    scratch_.push_back(NewPiece{t0, wx, wy, q.top, q.off, q.n, true});
  };
  const std::size_t lo_piece = first > 0 ? first - 1 : first;
  if (first > 0) copy(pieces[first - 1].t0, pieces[first - 1].wx, pieces[first - 1].wy, pieces[first - 1]);
  double u0 = ta, w0x = wax, w0y = way;
  std::uint32_t two[2];
  std::size_t j = first;
  for (; j < pieces.size() && pieces[j].t0 < tb; ++j) {
    const Piece q = pieces[j];
    double s1, e1x, e1y;
    end_of(g, j, s1, e1x, e1y);
    if (q.t0 < u0) copy(q.t0, q.wx, q.wy, q);  // head outside [ta, tb]
    double u1, w1x, w1y;
    if (tb < s1)
      u1 = tb, w1x = wbx, w1y = wby;
    else
      u1 = s1, w1x = e1x, w1y = e1y;
    const std::span<const std::uint32_t> b = ids_of(s, q, two);
    // Quick case: hi at or below the grounded interval's top at both ends (so all over).
    const double vh0 = value(hi, w0x, w0y), vh1 = value(hi, w1x, w1y);
    const double vb0 = q.t0 == u0 ? q.g0 : value(q.top, w0x, w0y);
    const double vb1 = u1 == s1 ? q.g1 : value(q.top, w1x, w1y);
    if (vh0 <= vb0 && vh1 <= vb1) {
      if (q.t0 >= u0) copy(u0, w0x, w0y, q);  // (else the head copied above continues over it)
    } else if (q.n == 2 && value(lo, w0x, w0y) <= vb0 && value(lo, w1x, w1y) <= vb1) {
      // The grounded interval alone, and the new one reaches down into it: B₁ := max(B₁, hi),
      // which changes side at most once (as in raise_in_segment).
      const double e0 = vh0 - vb0, e1 = vh1 - vb1;
      const auto piece = [&](double t0, double wx, double wy, std::uint32_t top) {
        scratch_.push_back(NewPiece{t0, wx, wy, top, 0, 2, false});
      };
      if (e0 >= 0 && e1 >= 0) {
        piece(u0, w0x, w0y, hi);
        chg_lo = std::min(chg_lo, u0), chg_hi = std::max(chg_hi, u1);
      } else {
        const double l = e0 / (e0 - e1);
        double cx = (1 - l) * w0x + l * w1x, cy = (1 - l) * w0y + l * w1y;
        const double r = 1.0 / std::sqrt(cx * cx + cy * cy);
        cx *= r, cy *= r;
        const double tc = std::clamp(diamond_angle(cx, cy), u0, u1);
        if (e0 > 0) {
          piece(u0, w0x, w0y, hi);
          piece(tc, cx, cy, q.top);
          chg_lo = std::min(chg_lo, u0), chg_hi = std::max(chg_hi, tc);
        } else {
          piece(u0, w0x, w0y, q.top);
          piece(tc, cx, cy, hi);
          chg_lo = std::min(chg_lo, tc), chg_hi = std::max(chg_hi, u1);
        }
      }
      changed_ = true;
    } else {
      // The boundaries', lo's and hi's values at the overlap's ends (ground and zenith: ∓∞).
      const std::size_t n = b.size();
      ends_.resize(2 * (n + 2));
      double* v0 = ends_.data();
      double* v1 = v0 + (n + 2);
      for (std::size_t k = 0; k < n; ++k) v0[k] = value(b[k], w0x, w0y), v1[k] = value(b[k], w1x, w1y);
      v0[n] = value(lo, w0x, w0y), v1[n] = value(lo, w1x, w1y);
      v0[n + 1] = vh0, v1[n + 1] = vh1;
      // Quick case: [lo, hi] strictly inside one interval [B₂ⱼ, B₂ⱼ₊₁] at both ends (so all over,
      // as a difference of two arcs changes sign at most once): nothing changes.
      bool inside = false;
      for (std::size_t k = 1; k < n && !inside; k += 2)
        inside = v0[k - 1] < v0[n] && v1[k - 1] < v1[n] && v0[n + 1] < v0[k] && v1[n + 1] < v1[k];
      if (inside) {
        if (q.t0 >= u0) copy(u0, w0x, w0y, q);
        if (u1 < s1) copy(u1, w1x, w1y, q);
        u0 = u1, w0x = w1x, w0y = w1y;
        continue;
      }
      // Cut where lo or hi crosses a boundary (or each other): opposite signs at the two ends.
      cuts_.clear();
      const auto cut = [&](std::uint32_t x, std::size_t ix, std::uint32_t y, std::size_t iy) {
        if (x <= kZenith || y <= kZenith || x == y) return;
        const double d0 = v0[ix] - v0[iy], d1 = v1[ix] - v1[iy];
        if (!((d0 < 0 && d1 > 0) || (d0 > 0 && d1 < 0))) return;
        if (std::abs(d0) <= kSnap * (std::abs(v0[ix]) + std::abs(v0[iy])) ||
            std::abs(d1) <= kSnap * (std::abs(v1[ix]) + std::abs(v1[iy])))
          return;  // touching at an end, to rounding: no crossing inside
        const double l = d0 / (d0 - d1);
        const double x_ = (1 - l) * w0x + l * w1x, y_ = (1 - l) * w0y + l * w1y;
        const double tc = diamond_angle(x_, y_);
        if (tc > u0 && tc < u1) cuts_.push_back(tc);
      };
      for (std::size_t k = 0; k < n; ++k) {
        cut(lo, n, b[k], k);
        cut(hi, n + 1, b[k], k);
      }
      cut(lo, n, hi, n + 1);
      if (cuts_.empty()) {
        if (unite_sub_range(b, q, lo, hi, u0, w0x, w0y, v0, v1, w1x, w1y))
          chg_lo = std::min(chg_lo, u0), chg_hi = std::max(chg_hi, u1);
      } else {
        std::sort(cuts_.begin(), cuts_.end());
        cuts_.erase(std::unique(cuts_.begin(), cuts_.end()), cuts_.end());
        double a0 = u0, a0x = w0x, a0y = w0y;
        cut_vals_.resize(2 * (n + 2));
        double* va = cut_vals_.data();
        double* vb = va + (n + 2);
        std::copy(v0, v0 + n + 2, va);
        for (std::size_t c = 0; c <= cuts_.size(); ++c) {
          double a1, a1x, a1y;
          if (c < cuts_.size()) {
            a1 = cuts_[c];
            diamond_direction(a1, a1x, a1y);
            for (std::size_t k = 0; k < n; ++k) vb[k] = value(b[k], a1x, a1y);
            vb[n] = value(lo, a1x, a1y), vb[n + 1] = value(hi, a1x, a1y);
          } else {
            a1 = u1, a1x = w1x, a1y = w1y;
            std::copy(v1, v1 + n + 2, vb);
          }
          if (unite_sub_range(b, q, lo, hi, a0, a0x, a0y, va, vb, a1x, a1y))
            chg_lo = std::min(chg_lo, a0), chg_hi = std::max(chg_hi, a1);
          a0 = a1, a0x = a1x, a0y = a1y;
          std::swap(va, vb);
        }
      }
    }
    if (u1 < s1) copy(u1, w1x, w1y, q);  // tail outside [ta, tb]
    u0 = u1, w0x = w1x, w0y = w1y;
  }
  const bool this_changed = changed_;
  changed_ = was_changed || this_changed;
  if (!this_changed) return;
  std::size_t hi_piece = j;  // replaced [lo_piece, hi_piece)
  if (hi_piece < pieces.size()) {
    copy(pieces[hi_piece].t0, pieces[hi_piece].wx, pieces[hi_piece].wy, pieces[hi_piece]);
    ++hi_piece;
  }
  const double final_end = hi_piece < pieces.size() ? pieces[hi_piece].t0 : double((g + 1) * kFinePerCoarse) / kBinsPerUnit;
  // Merge: drop empty pieces and join neighbours with the same boundaries.
  const auto same = [&](const NewPiece& p, const NewPiece& c) {
    if (p.n != c.n || p.top != c.top) return false;
    if (p.n == 2) return true;
    const std::uint32_t* a = (p.pooled ? s.pool.data() : scratch_ids_.data()) + p.off;
    const std::uint32_t* b = (c.pooled ? s.pool.data() : scratch_ids_.data()) + c.off;
    return std::equal(a, a + p.n, b);
  };
  std::size_t n = 0;
  for (std::size_t k = 0; k < scratch_.size(); ++k) {
    const double end = k + 1 < scratch_.size() ? scratch_[k + 1].t0 : final_end;
    if (end <= scratch_[k].t0) continue;                        // empty
    if (n > 0 && same(scratch_[n - 1], scratch_[k])) continue;  // joins the previous
    scratch_[n++] = scratch_[k];
  }
  splice(g, lo_piece, hi_piece, n, chg_lo, chg_hi);
}

// Recomputes the fine bins of segment g meeting [lo, hi]: the exact minimum of B₁ (a piece's part
// in a bin has its minimum at one of its ends: B₁ ≥ 0, and tan e is concave along an arc shorter
// than π where it is ≥ 0), the same of the first floating interval's top B₃, and the pieces'
// bounds of its bottom B₂ and of the lowest ceiling's bottom.
void OccludedSky::update_bins(int g, double lo, double hi) const {
  const Segment& s = segments_[g];
  const std::vector<Piece>& pieces = s.pieces;
  const int first_bin = g * kFinePerCoarse, last_bin = first_bin + kFinePerCoarse - 1;
  const int b0 = std::clamp(int(lo * kBinsPerUnit), first_bin, last_bin);
  int b1 = std::clamp(int(hi * kBinsPerUnit), first_bin, last_bin);
  if (double(b1) == hi * kBinsPerUnit && b1 > b0) --b1;
  const bool uppers = s.uppers > 0;
  std::fill(gmin_.begin() + b0, gmin_.begin() + b1 + 1, kInf);
  if (uppers) {
    std::fill(ohi_.begin() + b0, ohi_.begin() + b1 + 1, kInf);
    std::fill(cmax_.begin() + b0, cmax_.begin() + b1 + 1, -kInf);
    std::fill(flo_.begin() + b0, flo_.begin() + b1 + 1, -kInf);
    std::fill(fhi_.begin() + b0, fhi_.begin() + b1 + 1, kInf);
  }
  const double range_end = double(b1 + 1) / kBinsPerUnit;
  for (std::size_t j = piece_at(pieces, double(b0) / kBinsPerUnit); j < pieces.size() && pieces[j].t0 < range_end; ++j) {
    const Piece& q = pieces[j];
    double q_end, ex, ey;
    end_of(g, j, q_end, ex, ey);
    const bool starts_inside = q.t0 >= double(b0) / kBinsPerUnit;
    int b = starts_inside ? int(q.t0 * kBinsPerUnit) : b0;
    double left = starts_inside ? q.g0 : value(q.top, edge_x_[b], edge_y_[b]);
    if (!uppers) {  // B₁ only (the envelope's bins)
      for (; b <= b1 && double(b + 1) / kBinsPerUnit < q_end; ++b) {
        const double edge = value(q.top, edge_x_[b + 1], edge_y_[b + 1]);
        gmin_[b] = std::min({gmin_[b], left, edge});
        left = edge;
      }
      if (b <= b1) gmin_[b] = std::min({gmin_[b], left, q.g1});
      continue;
    }
    const std::uint32_t ftop = q.n >= 4 ? s.pool[q.off + 3] : kGround;  // kGround: no floating interval
    const bool floating = ftop != kGround;
    // If every gap closed: the top of the highest interval below the zenith (under a ceiling, of
    // the one below it).
    const std::uint32_t* ids = s.pool.data() + q.off;
    const std::uint32_t otop = q.n < 4 ? q.top : ids[q.n - 1] != kZenith ? ids[q.n - 1] : ids[q.n - 3];
    double fleft = !floating ? -kInf : starts_inside ? value(ftop, q.wx, q.wy) : value(ftop, edge_x_[b], edge_y_[b]);
    double oleft = starts_inside ? value(otop, q.wx, q.wy) : value(otop, edge_x_[b], edge_y_[b]);
    const auto account = [&](int bin, double right, double fright, double oright) {
      gmin_[bin] = std::min({gmin_[bin], left, right});
      ohi_[bin] = std::min({ohi_[bin], oleft, oright});
      fhi_[bin] = std::min({fhi_[bin], fleft, fright});
      flo_[bin] = std::max(flo_[bin], q.flo);
      cmax_[bin] = std::max(cmax_[bin], q.cmax);
    };
    for (; b <= b1 && double(b + 1) / kBinsPerUnit < q_end; ++b) {  // bins whose end lies inside the piece
      const double edge = value(q.top, edge_x_[b + 1], edge_y_[b + 1]);
      const double fedge = floating ? value(ftop, edge_x_[b + 1], edge_y_[b + 1]) : -kInf;
      const double oedge = value(otop, edge_x_[b + 1], edge_y_[b + 1]);
      account(b, edge, fedge, oedge);
      left = edge, fleft = fedge, oleft = oedge;
    }
    if (b <= b1) account(b, q.g1, floating ? value(ftop, ex, ey) : -kInf, value(otop, ex, ey));  // the bin holding its end
  }
  const double* m = gmin_.data() + first_bin;
  double m0 = m[0], m1 = m[1], m2 = m[2], m3 = m[3];
  for (int k = 4; k < kFinePerCoarse; k += 4)
    m0 = std::min(m0, m[k]), m1 = std::min(m1, m[k + 1]), m2 = std::min(m2, m[k + 2]), m3 = std::min(m3, m[k + 3]);
  coarse_gmin_[g] = std::min(std::min(m0, m1), std::min(m2, m3));
  if (!uppers) {
    std::copy(gmin_.begin() + b0, gmin_.begin() + b1 + 1, ohi_.begin() + b0);
    coarse_ohi_[g] = coarse_gmin_[g];
    // No floating interval or ceiling in the segment: the bins outside [b0, b1] hold none already
    // (their pieces did not change since they were last brought up to date).
    std::fill(cmax_.begin() + b0, cmax_.begin() + b1 + 1, kInf);
    std::fill(flo_.begin() + b0, flo_.begin() + b1 + 1, kInf);
    std::fill(fhi_.begin() + b0, fhi_.begin() + b1 + 1, -kInf);
    coarse_cmax_[g] = kInf, coarse_flo_[g] = kInf, coarse_fhi_[g] = -kInf;
    return;
  }
  double cm = -kInf, fl = -kInf, fh = kInf, oh = kInf;
  for (int b = first_bin; b <= last_bin; ++b)
    cm = std::max(cm, cmax_[b]), fl = std::max(fl, flo_[b]), fh = std::min(fh, fhi_[b]), oh = std::min(oh, ohi_[b]);
  coarse_ohi_[g] = oh;
  coarse_cmax_[g] = cm;
  coarse_flo_[g] = fl;
  coarse_fhi_[g] = fh;
}

bool OccludedSky::hidden_if_gaps_close(double lo, double hi, double top) const {
  if (hi > 4.0) return hidden_if_gaps_close(lo, 4.0, top) && hidden_if_gaps_close(0.0, hi - 4.0, top);
  const int b0 = std::min(kBins - 1, int(lo * kBinsPerUnit)), b1 = std::min(kBins - 1, int(hi * kBinsPerUnit));
  for (int g = b0 / kFinePerCoarse; g <= b1 / kFinePerCoarse; ++g) {
    ensure_bins(g);
    if (coarse_ohi_[g] >= top) continue;
    const int f0 = std::max(b0, g * kFinePerCoarse), f1 = std::min(b1, g * kFinePerCoarse + kFinePerCoarse - 1);
    for (int b = f0; b <= f1; ++b)
      if (ohi_[b] < top) return false;
  }
  return true;
}

bool OccludedSky::grounded_at_least(int b, double lo, double hi, double bound) const {
  const Segment& s = segments_[b / kFinePerCoarse];
  const std::vector<Piece>& pieces = s.pieces;
  const auto at_least_at = [&](const Piece& q, double t) {
    if (std::min(q.g0, q.g1) >= bound) return true;
    double wx, wy;
    diamond_direction(t, wx, wy);
    return value(q.top, wx, wy) >= bound;
  };
  const std::size_t i = piece_at(pieces, lo);
  if (!at_least_at(pieces[i], lo)) return false;
  std::size_t k = i;
  for (; k + 1 < pieces.size() && pieces[k + 1].t0 < hi; ++k)  // piece k ends inside the range
    if (pieces[k].g1 < bound || (k != i && pieces[k].g0 < bound)) return false;
  if (k != i && pieces[k].g0 < bound) return false;  // piece k holds hi
  return at_least_at(pieces[k], hi);
}

bool OccludedSky::hidden(double lo, double hi, double top, double bottom) const {
  if (hi > 4.0) return hidden(lo, 4.0, top, bottom) && hidden(0.0, hi - 4.0, top, bottom);
  const int b0 = std::min(kBins - 1, int(lo * kBinsPerUnit)), b1 = std::min(kBins - 1, int(hi * kBinsPerUnit));
  const bool uppers = uppers_ > 0;
  const auto bin_ok = [&](int b) {
    return gmin_[b] >= top || (uppers && (cmax_[b] <= bottom || (flo_[b] <= bottom && fhi_[b] >= top)));
  };
  for (int g = b0 / kFinePerCoarse; g <= b1 / kFinePerCoarse; ++g) {
    ensure_bins(g);
    if (coarse_gmin_[g] >= top || (uppers && (coarse_cmax_[g] <= bottom || (coarse_flo_[g] <= bottom && coarse_fhi_[g] >= top))))
      continue;
    const int f0 = std::max(b0 + 1, g * kFinePerCoarse), f1 = std::min(b1 - 1, g * kFinePerCoarse + kFinePerCoarse - 1);
    for (int b = f0; b <= f1; ++b)
      if (!bin_ok(b)) return false;
  }
  if (!bin_ok(b0) && !grounded_at_least(b0, lo, std::min(hi, double(b0 + 1) / kBinsPerUnit), top)) return false;
  return b1 == b0 || bin_ok(b1) || grounded_at_least(b1, double(b1) / kBinsPerUnit, hi, top);
}

}  // namespace skyband
