#include "geometry/horizon/horizon_envelope.h"

#include <algorithm>

namespace skyband {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Unit directions of the bin edges, t = b / kBinsPerUnit, b = 0 … kBins.
struct BinEdges {
  std::array<double, HorizonEnvelope::kBins + 1> x, y;
  BinEdges() {
    for (int b = 0; b <= HorizonEnvelope::kBins; ++b) diamond_direction(double(b) / HorizonEnvelope::kBinsPerUnit, x[b], y[b]);
  }
};
const BinEdges& bin_edges() {
  static const BinEdges e;
  return e;
}

}  // namespace

HorizonEnvelope::HorizonEnvelope() {
  const BinEdges& e = bin_edges();
  for (int g = 0; g < kCoarseBins; ++g) {
    const int b = g * kFinePerCoarse;
    segments_[g].assign(1, Piece{double(b) / kBinsPerUnit, e.x[b], e.y[b], kHorizon, 0.0, 0.0});
  }
  reset();
}

void HorizonEnvelope::reset() {
  const BinEdges& e = bin_edges();
  circle_.assign(2, {0.0, 0.0});  // the horizon; kBlocked's entry is never read
  for (const std::uint16_t g : touched_) {
    const int b = g * kFinePerCoarse;
    segments_[g].assign(1, Piece{double(b) / kBinsPerUnit, e.x[b], e.y[b], kHorizon, 0.0, 0.0});
    is_touched_[g] = false;
  }
  touched_.clear();
  bin_min_.fill(0.0);
  coarse_min_.fill(0.0);
  raised_ = false;
}

std::size_t HorizonEnvelope::run_count() const {
  std::size_t n = 0;
  for_each_run([&](double, double, std::uint32_t) { ++n; });
  return n;
}

bool HorizonEnvelope::bin_at_least(int b, double lo, double hi, double bound) const {
  // On each piece's part in [lo, hi] the minimum is at one of its ends; the value at lo or hi
  // itself is computed only where the piece's end values do not decide.
  const std::vector<Piece>& pieces = segments_[b / kFinePerCoarse];
  const auto at_least_at = [&](const Piece& q, double t) {
    if (std::min(q.v0, q.v1) >= bound) return true;
    double wx, wy;
    diamond_direction(t, wx, wy);
    return value(q.circle, wx, wy) >= bound;
  };
  const std::size_t i = piece_at(pieces, lo);
  if (!at_least_at(pieces[i], lo)) return false;
  std::size_t k = i;
  for (; k + 1 < pieces.size() && pieces[k + 1].t0 < hi; ++k)  // piece k ends inside the range
    if (pieces[k].v1 < bound || (k != i && pieces[k].v0 < bound)) return false;
  if (k != i && pieces[k].v0 < bound) return false;  // piece k holds hi
  return at_least_at(pieces[k], hi);
}

void HorizonEnvelope::insert_range(std::uint32_t c, double t0, double w0x, double w0y, double t1, double w1x, double w1y) {
  if (t0 > t1) {
    std::swap(t0, t1);
    std::swap(w0x, w1x);
    std::swap(w0y, w1y);
  }
  if (t1 - t0 < 2) {
    if (t0 < t1) insert(c, t0, t1, w0x, w0y, w1x, w1y);
  } else if (t1 - t0 > 2) {
    insert(c, t1, 4.0, w1x, w1y, 1.0, 0.0);
    if (t0 > 0) insert(c, 0.0, t0, 1.0, 0.0, w0x, w0y);
  }
  // exactly 2 apart: the arc passes over the point (a vertical great circle); not an occluder
  // arc of a triangle the method accepts.
}

void HorizonEnvelope::insert_half_turn(std::uint32_t c, double t0, double tmid, double t1) {
  // Two quarter-turn-or-less parts, so each is shorter than π.
  const double cuts[3] = {t0, tmid, t1};
  for (int k = 0; k < 2; ++k) {
    const double a = cuts[k], b = cuts[k + 1];
    double ax, ay, bx, by;
    diamond_direction(a, ax, ay);
    diamond_direction(b, bx, by);
    if (a < b)
      insert(c, a, b, ax, ay, bx, by);
    else {
      insert(c, a, 4.0, ax, ay, 1.0, 0.0);
      if (b > 0) insert(c, 0.0, b, 1.0, 0.0, bx, by);
    }
  }
}

// [ta, tb] ⊂ [0, 4], ta < tb, cut at the segment edges.
void HorizonEnvelope::insert(std::uint32_t c, double ta, double tb, double wax, double way, double wbx, double wby) {
  const BinEdges& e = bin_edges();
  constexpr double kSegmentsPerUnit = kCoarseBins / 4.0;  // a power of two: segment edges are exact
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
      insert_in_segment(g, c, u0, u1, from_edge ? e.x[b] : wax, from_edge ? e.y[b] : way, to_edge ? e.x[b_end] : wbx,
                        to_edge ? e.y[b_end] : wby);
  }
}

std::size_t HorizonEnvelope::piece_at(const std::vector<Piece>& pieces, double t) {
  std::size_t lo = 0, n = pieces.size();  // pieces[lo].t0 ≤ t (the first starts at the segment's start)
  while (n > 1) {                         // branch-free: the outcome of each step is unpredictable
    const std::size_t half = n / 2;
    lo = pieces[lo + half].t0 <= t ? lo + half : lo;
    n -= half;
  }
  return lo;
}

// Recomputes the exact minima of the fine bins of segment g meeting [lo, hi] from its pieces (a
// piece's part in a bin has its minimum at one of its ends), and the segment's minimum. Piece by
// piece, each bin edge's value computed once: a near facade's arc spans hundreds of bins.
void HorizonEnvelope::update_bins(int g, double lo, double hi) {
  const BinEdges& e = bin_edges();
  const std::vector<Piece>& pieces = segments_[g];
  const int first_bin = g * kFinePerCoarse, last_bin = first_bin + kFinePerCoarse - 1;
  const int b0 = std::clamp(int(lo * kBinsPerUnit), first_bin, last_bin);
  const int b1 = std::clamp(int(hi * kBinsPerUnit), first_bin, last_bin);
  std::fill(bin_min_.begin() + b0, bin_min_.begin() + b1 + 1, kInf);
  const double range_end = double(b1 + 1) / kBinsPerUnit;
  for (std::size_t j = piece_at(pieces, double(b0) / kBinsPerUnit); j < pieces.size() && pieces[j].t0 < range_end; ++j) {
    const Piece& q = pieces[j];
    if (q.circle == kBlocked) continue;
    const double q_end = j + 1 < pieces.size() ? pieces[j + 1].t0 : double(last_bin + 1) / kBinsPerUnit;
    // The piece's part in the range: from its start (or bin b0's start) to its end (or the range's).
    const bool starts_inside = q.t0 >= double(b0) / kBinsPerUnit;
    int b = starts_inside ? int(q.t0 * kBinsPerUnit) : b0;
    double left = starts_inside ? q.v0 : value(q.circle, e.x[b0], e.y[b0]);
    for (; b <= b1 && double(b + 1) / kBinsPerUnit < q_end; ++b) {  // bins whose end lies inside the piece
      const double edge = value(q.circle, e.x[b + 1], e.y[b + 1]);
      bin_min_[b] = std::min({bin_min_[b], left, edge});
      left = edge;
    }
    if (b <= b1) bin_min_[b] = std::min({bin_min_[b], left, q.v1});  // the bin holding its end
  }
  // The segment's minimum, in four independent chains (std::min_element is a serial loop).
  const double* m = bin_min_.data() + first_bin;
  double m0 = m[0], m1 = m[1], m2 = m[2], m3 = m[3];
  for (int k = 4; k < kFinePerCoarse; k += 4)
    m0 = std::min(m0, m[k]), m1 = std::min(m1, m[k + 1]), m2 = std::min(m2, m[k + 2]), m3 = std::min(m3, m[k + 3]);
  coarse_min_[g] = std::min(std::min(m0, m1), std::min(m2, m3));
}

// Raises segment g's envelope to circle c over [ta, tb] inside the segment.
void HorizonEnvelope::insert_in_segment(int g, std::uint32_t c, double ta, double tb, double wax, double way, double wbx,
                                        double wby) {
  std::vector<Piece>& pieces = segments_[g];
  const int end_bin = (g + 1) * kFinePerCoarse;
  const double bin_end = double(end_bin) / kBinsPerUnit;  // the segment's end
  const double end_x = bin_edges().x[end_bin], end_y = bin_edges().y[end_bin];
  const std::size_t first = piece_at(pieces, ta);
  // At most two pieces per piece overlapped, its head and tail, and the neighbours on each side.
  if (scratch_.size() < 2 * pieces.size() + 4) scratch_.resize(2 * pieces.size() + 4);
  std::size_t ns = 0;  // pieces in scratch_
  // The new pieces of [lo, hi) go to scratch, starting with the piece before the range (so that
  // it can join the first new one).
  const std::size_t lo = first > 0 ? first - 1 : first;
  if (first > 0) scratch_[ns++] = pieces[first - 1];
  bool changed = false;
  double changed_lo = tb, changed_hi = ta;  // where the envelope rose
  double u0 = ta, w0x = wax, w0y = way;
  double c0 = value(c, w0x, w0y);  // the new arc at u0
  std::size_t j = first;
  for (; j < pieces.size() && pieces[j].t0 < tb; ++j) {
    const Piece q = pieces[j];
    const std::uint32_t pc = q.circle;
    const bool last = j + 1 == pieces.size();
    const double s1 = last ? bin_end : pieces[j + 1].t0;
    double p0 = q.v0;  // the envelope at u0
    if (q.t0 < u0) {   // head outside [ta, tb]
      p0 = value(pc, w0x, w0y);
      scratch_[ns++] = Piece{q.t0, q.wx, q.wy, pc, q.v0, p0};
    }
    double u1, w1x, w1y, p1;  // the overlap's end, and the envelope there
    if (tb < s1) {
      u1 = tb, w1x = wbx, w1y = wby;
      p1 = value(pc, w1x, w1y);
    } else {
      u1 = s1, p1 = q.v1;
      if (last)
        w1x = end_x, w1y = end_y;
      else
        w1x = pieces[j + 1].wx, w1y = pieces[j + 1].wy;
    }
    const double c1 = value(c, w1x, w1y);
    const double e0 = c0 - p0, e1 = c1 - p1;
    // Both are great-circle arcs over less than π: their difference (linear in the unit
    // direction) changes sign at most once, where the chord between w0 and w1 crosses zero.
    if (!(e0 > 0 || e1 > 0)) {
      scratch_[ns++] = Piece{u0, w0x, w0y, pc, p0, p1};
    } else if (e0 >= 0 && e1 >= 0) {
      scratch_[ns++] = Piece{u0, w0x, w0y, c, c0, c1};
      changed = true;
      changed_lo = std::min(changed_lo, u0);
      changed_hi = u1;
    } else {
      const double l = e0 / (e0 - e1);
      double cx = (1 - l) * w0x + l * w1x, cy = (1 - l) * w0y + l * w1y;
      const double r = 1.0 / std::sqrt(cx * cx + cy * cy);
      cx *= r;
      cy *= r;
      const double tc = std::clamp(diamond_angle(cx, cy), u0, u1);
      const double vc = value(c, cx, cy);  // = the old arc's value there, to rounding
      if (e0 > 0) {
        scratch_[ns++] = Piece{u0, w0x, w0y, c, c0, vc};
        scratch_[ns++] = Piece{tc, cx, cy, pc, vc, p1};
        changed_lo = std::min(changed_lo, u0);
        changed_hi = tc;
      } else {
        scratch_[ns++] = Piece{u0, w0x, w0y, pc, p0, vc};
        scratch_[ns++] = Piece{tc, cx, cy, c, vc, c1};
        changed_lo = std::min(changed_lo, tc);
        changed_hi = u1;
      }
      changed = true;
    }
    if (u1 < s1) scratch_[ns++] = Piece{u1, w1x, w1y, pc, p1, q.v1};  // tail outside [ta, tb]
    u0 = u1;
    w0x = w1x;
    w0y = w1y;
    c0 = c1;
  }
  if (!changed) return;
  raised_ = true;
  if (!is_touched_[g]) {
    is_touched_[g] = true;
    touched_.push_back(std::uint16_t(g));
  }
  // Merge: drop empty pieces and join neighbours on the same circle, including the pieces just
  // before and after the replaced range.
  std::size_t hi = j;  // replaced [lo, hi)
  if (hi < pieces.size()) scratch_[ns++] = pieces[hi++];
  const double final_end = hi < pieces.size() ? pieces[hi].t0 : bin_end;
  std::size_t n = 0;
  for (std::size_t k = 0; k < ns; ++k) {
    const double end = k + 1 < ns ? scratch_[k + 1].t0 : final_end;
    if (end <= scratch_[k].t0) continue;  // empty
    if (n > 0 && scratch_[n - 1].circle == scratch_[k].circle) {
      scratch_[n - 1].v1 = scratch_[k].v1;  // joins the previous
      continue;
    }
    scratch_[n++] = scratch_[k];
  }
  // Splice scratch in place of [lo, hi).
  const std::size_t replaced = hi - lo;
  if (n > replaced)
    pieces.insert(pieces.begin() + std::ptrdiff_t(hi), n - replaced, Piece{});
  else if (n < replaced)
    pieces.erase(pieces.begin() + std::ptrdiff_t(lo + n), pieces.begin() + std::ptrdiff_t(hi));
  std::copy(scratch_.begin(), scratch_.begin() + std::ptrdiff_t(n), pieces.begin() + std::ptrdiff_t(lo));
  update_bins(g, changed_lo, changed_hi);
}

}  // namespace skyband
