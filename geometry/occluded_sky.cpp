#include "geometry/occluded_sky.h"

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

constexpr std::uint32_t kInitial[2] = {OccludedSky::kGround, OccludedSky::kHorizon};

// Values within this relative distance of each other at a sub-range's end count as equal there (a
// crossing computed to rounding lands within it).
constexpr double kSnap = 1e-14;

}  // namespace

OccludedSky::OccludedSky() {
  for (int g = 0; g < kCoarseBins; ++g) is_touched_[g] = true, touched_.push_back(std::uint16_t(g));
  reset();
}

void OccludedSky::reset() {
  const BinEdges& e = bin_edges();
  circle_.assign(3, {0.0, 0.0});  // kGround and kZenith are never read; kHorizon is tan e = 0
  for (const std::uint16_t g : touched_) {
    const int b = g * kFinePerCoarse;
    Segment& s = segments_[g];
    s.pool.assign(kInitial, kInitial + 2);
    s.pieces.assign(1, Piece{double(b) / kBinsPerUnit, e.x[b], e.y[b], 0.0, 0.0, kInf, kInf, 0, 2});
    std::fill(gmin_.begin() + b, gmin_.begin() + b + kFinePerCoarse, 0.0);
    std::fill(cmax_.begin() + b, cmax_.begin() + b + kFinePerCoarse, kInf);
    std::fill(flo_.begin() + b, flo_.begin() + b + kFinePerCoarse, kInf);
    std::fill(fhi_.begin() + b, fhi_.begin() + b + kFinePerCoarse, -kInf);
    coarse_gmin_[g] = 0.0;
    coarse_cmax_[g] = kInf;
    coarse_flo_[g] = kInf;
    coarse_fhi_[g] = -kInf;
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
    for (const Piece& q : s.pieces)
      if (q.n > 2) return true;
  return false;
}

void OccludedSky::end_of(int g, std::size_t j, double& t1, double& wx, double& wy) const {
  const Segment& s = segments_[g];
  if (j + 1 < s.pieces.size()) {
    const Piece& n = s.pieces[j + 1];
    t1 = n.t0, wx = n.wx, wy = n.wy;
  } else {
    const int b = (g + 1) * kFinePerCoarse;
    t1 = double(b) / kBinsPerUnit, wx = bin_edges().x[b], wy = bin_edges().y[b];
  }
}

std::size_t OccludedSky::piece_at(const std::vector<Piece>& pieces, double t) {
  std::size_t lo = 0, n = pieces.size();  // pieces[lo].t0 ≤ t (the first starts at the segment's start)
  while (n > 1) {
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

void OccludedSky::insert_range(std::uint32_t lo, std::uint32_t hi, double ta, double tb, double wax, double way,
                               double wbx, double wby) {
  const BinEdges& e = bin_edges();
  const int g0 = std::min(kCoarseBins - 1, int(ta * kSegmentsPerUnit));
  int g1 = int(tb * kSegmentsPerUnit);
  if (double(g1) == tb * kSegmentsPerUnit) --g1;  // tb on a segment edge
  g1 = std::clamp(g1, g0, kCoarseBins - 1);
  for (int g = g0; g <= g1; ++g) {
    const int b = g * kFinePerCoarse, b_end = b + kFinePerCoarse;
    const double s0 = double(g) / kSegmentsPerUnit, s1 = double(g + 1) / kSegmentsPerUnit;
    const bool from_edge = s0 > ta, to_edge = s1 < tb;
    const double u0 = from_edge ? s0 : ta, u1 = to_edge ? s1 : tb;
    if (u0 < u1)
      insert_in_segment(g, lo, hi, u0, u1, from_edge ? e.x[b] : wax, from_edge ? e.y[b] : way,
                        to_edge ? e.x[b_end] : wbx, to_edge ? e.y[b_end] : wby);
  }
}

int OccludedSky::compare(std::uint32_t x, std::uint32_t y, double ax, double ay, double bx, double by) const {
  if (x == y) return 0;
  if (x == kGround || y == kZenith) return -1;
  if (y == kGround || x == kZenith) return 1;
  const auto& cx = circle_[x];
  const auto& cy = circle_[y];
  if (cx[0] == cy[0] && cx[1] == cy[1]) return 0;
  const auto diff = [&](double wx, double wy) {
    const double vx = cx[0] * wx + cx[1] * wy, vy = cy[0] * wx + cy[1] * wy;
    const double d = vx - vy;
    return std::abs(d) <= kSnap * (std::abs(vx) + std::abs(vy)) ? 0.0 : d;
  };
  const double da = diff(ax, ay), db = diff(bx, by);
  if (da >= 0 && db >= 0) return da > 0 || db > 0 ? 1 : 0;
  if (da <= 0 && db <= 0) return -1;
  // Opposite signs at the two ends: a crossing inside that the cut missed by rounding; decide in
  // the middle.
  double mx = ax + bx, my = ay + by;
  const double r = 1.0 / std::sqrt(mx * mx + my * my);
  mx *= r, my *= r;
  const double dm = (cx[0] - cy[0]) * mx + (cx[1] - cy[1]) * my;
  return dm > 0 ? 1 : dm < 0 ? -1 : 0;
}

void OccludedSky::unite_sub_range(std::span<const std::uint32_t> b, std::uint32_t lo, std::uint32_t hi, double s0,
                                  double s0x, double s0y, double s1, double s1x, double s1y) {
  (void)s1;
  const std::size_t off = scratch_ids_.size();
  const auto keep = [&] {
    scratch_ids_.insert(scratch_ids_.end(), b.begin(), b.end());
    scratch_.push_back(NewPiece{s0, s0x, s0y, std::uint32_t(off), std::uint32_t(b.size())});
  };
  if (compare(lo, hi, s0x, s0y, s1x, s1y) >= 0) {  // empty here (lo = hi, or lo > hi by rounding)
    keep();
    return;
  }
  // i: boundaries before lo, k: before hi, where a boundary equal to lo or hi counts as before it
  // when it is a lower bound (even index): closed intervals, touching ones merge.
  const std::size_t n = b.size();
  std::size_t i = 0;
  while (i < n) {
    const int c = compare(b[i], lo, s0x, s0y, s1x, s1y);
    if (c < 0 || (c == 0 && (i & 1) == 0)) ++i;
    else break;
  }
  std::size_t k = i;
  while (k < n) {
    const int c = compare(b[k], hi, s0x, s0y, s1x, s1y);
    if (c < 0 || (c == 0 && (k & 1) == 0)) ++k;
    else break;
  }
  if ((i & 1) && (k & 1) && i == k) {  // inside one interval already
    keep();
    return;
  }
  scratch_ids_.insert(scratch_ids_.end(), b.begin(), b.begin() + std::ptrdiff_t(i));
  if ((i & 1) == 0) scratch_ids_.push_back(lo);
  if ((k & 1) == 0) scratch_ids_.push_back(hi);
  scratch_ids_.insert(scratch_ids_.end(), b.begin() + std::ptrdiff_t(k), b.end());
  scratch_.push_back(NewPiece{s0, s0x, s0y, std::uint32_t(off), std::uint32_t(scratch_ids_.size() - off)});
  changed_ = true;
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

void OccludedSky::finish_piece(Piece& q, const std::uint32_t* ids, double t1x, double t1y) const {
  q.g0 = value(ids[1], q.wx, q.wy);
  q.g1 = value(ids[1], t1x, t1y);
  q.cmax = kInf;
  q.flo = kInf;
  if (q.n == 2 && ids[1] == kZenith) q.cmax = -kInf;  // blocked: everything covered
  if (q.n >= 4) {
    q.flo = circle_max(ids[2], q.t0, q.wx, q.wy, t1x, t1y);
    if (ids[q.n - 1] == kZenith) q.cmax = q.n == 4 ? q.flo : circle_max(ids[q.n - 2], q.t0, q.wx, q.wy, t1x, t1y);
  }
}

// Unites [lo, hi] over [ta, tb] inside segment g.
void OccludedSky::insert_in_segment(int g, std::uint32_t lo, std::uint32_t hi, double ta, double tb, double wax,
                                    double way, double wbx, double wby) {
  Segment& s = segments_[g];
  std::vector<Piece>& pieces = s.pieces;
  const std::size_t first = piece_at(pieces, ta);
  scratch_.clear();
  scratch_ids_.clear();
  const bool was_changed = changed_;
  changed_ = false;
  const auto copy = [&](double t0, double wx, double wy, const Piece& q) {
    const std::size_t off = scratch_ids_.size();
    scratch_ids_.insert(scratch_ids_.end(), s.pool.begin() + q.off, s.pool.begin() + q.off + q.n);
    scratch_.push_back(NewPiece{t0, wx, wy, std::uint32_t(off), q.n});
  };
  const std::size_t lo_piece = first > 0 ? first - 1 : first;
  if (first > 0) copy(pieces[first - 1].t0, pieces[first - 1].wx, pieces[first - 1].wy, pieces[first - 1]);
  double u0 = ta, w0x = wax, w0y = way;
  std::size_t j = first;
  for (; j < pieces.size() && pieces[j].t0 < tb; ++j) {
    const Piece q = pieces[j];
    double s1, e1x, e1y;
    end_of(g, j, s1, e1x, e1y);
    if (q.t0 < u0) copy(q.t0, q.wx, q.wy, q);  // head outside [ta, tb]
    double u1, w1x, w1y;
    if (tb < s1) u1 = tb, w1x = wbx, w1y = wby;
    else u1 = s1, w1x = e1x, w1y = e1y;
    const std::span<const std::uint32_t> b(s.pool.data() + q.off, q.n);
    // Quick case: hi at or below the grounded interval's top at both ends (so all over).
    const double vh0 = value(hi, w0x, w0y), vh1 = value(hi, w1x, w1y);
    const double vb0 = q.t0 == u0 ? q.g0 : value(b[1], w0x, w0y);
    const double vb1 = u1 == s1 ? q.g1 : value(b[1], w1x, w1y);
    if (vh0 <= vb0 && vh1 <= vb1) {
      if (q.t0 >= u0) copy(u0, w0x, w0y, q);  // (else the head copied above continues over it)
    } else {
      // Cut where lo or hi crosses a boundary (or each other).
      cuts_.clear();
      const auto cut = [&](std::uint32_t x, std::uint32_t y) {
        if (x <= kZenith || y <= kZenith || x == y) return;
        const auto& cx = circle_[x];
        const auto& cy = circle_[y];
        const double d0 = (cx[0] - cy[0]) * w0x + (cx[1] - cy[1]) * w0y;
        const double d1 = (cx[0] - cy[0]) * w1x + (cx[1] - cy[1]) * w1y;
        if (!((d0 < 0 && d1 > 0) || (d0 > 0 && d1 < 0))) return;
        const double l = d0 / (d0 - d1);
        const double x_ = (1 - l) * w0x + l * w1x, y_ = (1 - l) * w0y + l * w1y;
        const double tc = diamond_angle(x_, y_);
        if (tc > u0 && tc < u1) cuts_.push_back(tc);
      };
      for (const std::uint32_t c : b) {
        cut(lo, c);
        cut(hi, c);
      }
      cut(lo, hi);
      std::sort(cuts_.begin(), cuts_.end());
      cuts_.erase(std::unique(cuts_.begin(), cuts_.end()), cuts_.end());
      double a0 = u0, a0x = w0x, a0y = w0y;
      for (std::size_t c = 0; c <= cuts_.size(); ++c) {
        double a1, a1x, a1y;
        if (c < cuts_.size()) {
          a1 = cuts_[c];
          diamond_direction(a1, a1x, a1y);
        } else {
          a1 = u1, a1x = w1x, a1y = w1y;
        }
        unite_sub_range(b, lo, hi, a0, a0x, a0y, a1, a1x, a1y);
        a0 = a1, a0x = a1x, a0y = a1y;
      }
    }
    if (u1 < s1) copy(u1, w1x, w1y, q);  // tail outside [ta, tb]
    u0 = u1, w0x = w1x, w0y = w1y;
  }
  const bool this_changed = changed_;
  changed_ = was_changed || this_changed;
  if (!this_changed) return;
  if (!is_touched_[g]) {
    is_touched_[g] = true;
    touched_.push_back(std::uint16_t(g));
  }
  std::size_t hi_piece = j;  // replaced [lo_piece, hi_piece)
  if (hi_piece < pieces.size()) {
    copy(pieces[hi_piece].t0, pieces[hi_piece].wx, pieces[hi_piece].wy, pieces[hi_piece]);
    ++hi_piece;
  }
  const double final_end = hi_piece < pieces.size() ? pieces[hi_piece].t0 : double((g + 1) * kFinePerCoarse) / kBinsPerUnit;
  // Merge: drop empty pieces and join neighbours with the same boundaries.
  std::size_t n = 0;
  for (std::size_t k = 0; k < scratch_.size(); ++k) {
    const double end = k + 1 < scratch_.size() ? scratch_[k + 1].t0 : final_end;
    if (end <= scratch_[k].t0) continue;  // empty
    if (n > 0) {
      const NewPiece& p = scratch_[n - 1];
      const NewPiece& c = scratch_[k];
      if (p.n == c.n && std::equal(scratch_ids_.begin() + p.off, scratch_ids_.begin() + p.off + p.n, scratch_ids_.begin() + c.off))
        continue;  // joins the previous
    }
    scratch_[n++] = scratch_[k];
  }
  // Rebuild the pool when it has grown past four times what the pieces hold.
  std::size_t live = 0;
  for (const Piece& q : pieces) live += q.n;
  if (s.pool.size() > 4 * live + 64) {
    std::vector<std::uint32_t> pool;
    pool.reserve(2 * live);
    for (Piece& q : pieces) {
      const std::uint32_t off = std::uint32_t(pool.size());
      pool.insert(pool.end(), s.pool.begin() + q.off, s.pool.begin() + q.off + q.n);
      q.off = off;
    }
    s.pool.swap(pool);
  }
  // Splice scratch in place of [lo_piece, hi_piece).
  const std::size_t replaced = hi_piece - lo_piece;
  if (n > replaced) pieces.insert(pieces.begin() + std::ptrdiff_t(hi_piece), n - replaced, Piece{});
  else if (n < replaced) pieces.erase(pieces.begin() + std::ptrdiff_t(lo_piece + n), pieces.begin() + std::ptrdiff_t(hi_piece));
  for (std::size_t k = 0; k < n; ++k) {
    const NewPiece& np = scratch_[k];
    Piece& q = pieces[lo_piece + k];
    q.t0 = np.t0, q.wx = np.wx, q.wy = np.wy, q.n = np.n;
    q.off = std::uint32_t(s.pool.size());
    s.pool.insert(s.pool.end(), scratch_ids_.begin() + np.off, scratch_ids_.begin() + np.off + np.n);
  }
  for (std::size_t k = 0; k < n; ++k) {
    Piece& q = pieces[lo_piece + k];
    double t1, e1x, e1y;
    end_of(g, lo_piece + k, t1, e1x, e1y);
    finish_piece(q, s.pool.data() + q.off, e1x, e1y);
    if (q.n > 2 || q.cmax < kInf) ++uppers_;
  }
  update_bins(g, pieces[lo_piece].t0, final_end);
}

// Recomputes the fine bins of segment g meeting [lo, hi): the exact minimum of B₁ (a piece's part
// in a bin has its minimum at one of its ends: B₁ ≥ 0, and tan e is concave along an arc shorter
// than π where it is ≥ 0), the same of the first floating interval's top B₃, and the pieces'
// bounds of its bottom B₂ and of the lowest ceiling's bottom.
void OccludedSky::update_bins(int g, double lo, double hi) {
  const BinEdges& e = bin_edges();
  const Segment& s = segments_[g];
  const std::vector<Piece>& pieces = s.pieces;
  const int first_bin = g * kFinePerCoarse, last_bin = first_bin + kFinePerCoarse - 1;
  const int b0 = std::clamp(int(lo * kBinsPerUnit), first_bin, last_bin);
  int b1 = std::clamp(int(hi * kBinsPerUnit), first_bin, last_bin);
  if (double(b1) == hi * kBinsPerUnit && b1 > b0) --b1;
  std::fill(gmin_.begin() + b0, gmin_.begin() + b1 + 1, kInf);
  std::fill(cmax_.begin() + b0, cmax_.begin() + b1 + 1, -kInf);
  std::fill(flo_.begin() + b0, flo_.begin() + b1 + 1, -kInf);
  std::fill(fhi_.begin() + b0, fhi_.begin() + b1 + 1, kInf);
  const double range_end = double(b1 + 1) / kBinsPerUnit;
  for (std::size_t j = piece_at(pieces, double(b0) / kBinsPerUnit); j < pieces.size() && pieces[j].t0 < range_end; ++j) {
    const Piece& q = pieces[j];
    const std::uint32_t top = s.pool[q.off + 1];
    const std::uint32_t ftop = q.n >= 4 ? s.pool[q.off + 3] : kGround;  // kGround: no floating interval
    double q_end, ex, ey;
    end_of(g, j, q_end, ex, ey);
    const bool starts_inside = q.t0 >= double(b0) / kBinsPerUnit;
    int b = starts_inside ? int(q.t0 * kBinsPerUnit) : b0;
    double left = starts_inside ? q.g0 : value(top, e.x[b], e.y[b]);
    double fleft = starts_inside ? value(ftop, q.wx, q.wy) : value(ftop, e.x[b], e.y[b]);
    const auto account = [&](int bin, double right, double fright) {
      gmin_[bin] = std::min({gmin_[bin], left, right});
      fhi_[bin] = std::min({fhi_[bin], fleft, fright});
      flo_[bin] = std::max(flo_[bin], q.flo);
      cmax_[bin] = std::max(cmax_[bin], q.cmax);
    };
    for (; b <= b1 && double(b + 1) / kBinsPerUnit < q_end; ++b) {  // bins whose end lies inside the piece
      const double edge = value(top, e.x[b + 1], e.y[b + 1]), fedge = value(ftop, e.x[b + 1], e.y[b + 1]);
      account(b, edge, fedge);
      left = edge, fleft = fedge;
    }
    if (b <= b1) account(b, q.g1, value(ftop, ex, ey));  // the bin holding its end
  }
  double gm = kInf, cm = -kInf, fl = -kInf, fh = kInf;
  for (int b = first_bin; b <= last_bin; ++b) {
    gm = std::min(gm, gmin_[b]), cm = std::max(cm, cmax_[b]);
    fl = std::max(fl, flo_[b]), fh = std::min(fh, fhi_[b]);
  }
  coarse_gmin_[g] = gm;
  coarse_cmax_[g] = cm;
  coarse_flo_[g] = fl;
  coarse_fhi_[g] = fh;
}

bool OccludedSky::grounded_at_least(int b, double lo, double hi, double bound) const {
  const Segment& s = segments_[b / kFinePerCoarse];
  const std::vector<Piece>& pieces = s.pieces;
  const auto at_least_at = [&](const Piece& q, double t) {
    if (std::min(q.g0, q.g1) >= bound) return true;
    double wx, wy;
    diamond_direction(t, wx, wy);
    return value(s.pool[q.off + 1], wx, wy) >= bound;
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
    if (coarse_gmin_[g] >= top ||
        (uppers && (coarse_cmax_[g] <= bottom || (coarse_flo_[g] <= bottom && coarse_fhi_[g] >= top))))
      continue;
    const int f0 = std::max(b0 + 1, g * kFinePerCoarse), f1 = std::min(b1 - 1, g * kFinePerCoarse + kFinePerCoarse - 1);
    for (int b = f0; b <= f1; ++b)
      if (!bin_ok(b)) return false;
  }
  if (!bin_ok(b0) && !grounded_at_least(b0, lo, std::min(hi, double(b0 + 1) / kBinsPerUnit), top)) return false;
  return b1 == b0 || bin_ok(b1) || grounded_at_least(b1, double(b1) / kBinsPerUnit, hi, top);
}

}  // namespace skyband
