#include "render/specular_reuse.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "geometry/core/thread_arena.h"

namespace skyband {

namespace {

constexpr double kNormalTolerance = 1e-6;  // 1 − n₁·n₂
constexpr double kPlaneTolerance_m = 1e-3;

bool same_plane(const SurfaceSample& a, const SurfaceSample& b) {
  return a.material_slot == b.material_slot && a.normal.dot(b.normal) >= 1.0 - kNormalTolerance &&
         std::abs(a.normal.dot(b.position - a.position)) <= kPlaneTolerance_m;
}

Xyz bilinear(const Xyz (&c)[4], double fx, double fy) {
  const double wt[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
  Xyz r;
  for (int j = 0; j < 4; ++j) {
    r.X += wt[j] * c[j].X;
    r.Y += wt[j] * c[j].Y;
    r.Z += wt[j] * c[j].Z;
  }
  return r;
}

// Whether the corners' bilinear interpolation at (fx, fy) matches `actual` within tolerance × the
// largest magnitude of the five values, in each of X, Y, Z.
bool predicts(const Xyz (&c)[4], double fx, double fy, const Xyz& actual, double tolerance) {
  const Xyz p = bilinear(c, fx, fy);
  const double pv[3] = {p.X, p.Y, p.Z}, av[3] = {actual.X, actual.Y, actual.Z};
  for (int ch = 0; ch < 3; ++ch) {
    double mag = std::abs(av[ch]);
    for (const Xyz& x : c) mag = std::max(mag, std::abs(ch == 0 ? x.X : ch == 1 ? x.Y : x.Z));
    if (std::abs(pv[ch] - av[ch]) > tolerance * mag) return false;
  }
  return true;
}

// The state of one shading call: what is known exactly, and the recursion over one block.
class Reuse {
 public:
  Reuse(const GeometryPass& pass, double tolerance, const std::function<bool(std::size_t)>& glossy,
        const std::function<int(std::size_t)>& reuse_class, const std::function<Xyz(std::size_t)>& exact, std::vector<Xyz>& out)
      : pass_(pass),
        tolerance_(tolerance),
        glossy_(glossy),
        class_(reuse_class),
        exact_(exact),
        out_(out),
        done_(pass.surfaces.size(), 0) {}

  // The surface of sample i of pixel (col, row); kBackground outside the image (so blocks that
  // overhang the image are never smooth and get split down to the image).
  std::uint32_t at(int col, int row, std::size_t i) const {
    if (col < 0 || row < 0 || col >= pass_.width || row >= pass_.height) return GeometryPass::kBackground;
    return pass_
        .sample_surface[(static_cast<std::size_t>(row) * static_cast<std::size_t>(pass_.width) + static_cast<std::size_t>(col)) *
                            static_cast<std::size_t>(pass_.samples) +
                        i];
  }
  bool glossy(std::uint32_t k) const { return k != GeometryPass::kBackground && glossy_(k); }
  // March surface k once (callers guarantee that no other thread touches k meanwhile).
  // A sample a neighbouring block interpolated (on that block's left or top edge) and that this
  // block needs as a corner or check point is marched after all (counted in `reverted`): the
  // checks compare with exact values only.
  void ensure(std::uint32_t k, std::size_t& marched) {
    if (!glossy(k) || done_[k] == kExact) return;
    if (done_[k] == kInterpolated) ++reverted_;
    out_[k] = exact_(k);
    done_[k] = kExact;
    ++marched;
  }
  // Pixels [xa, xb) × [ya, yb) of sample index i; marches its corners (xa|xb, ya|yb) first.
  void refine(int xa, int xb, int ya, int yb, std::size_t i, int min_block, std::size_t& marched, std::size_t& interpolated);
  // A 4 × 4 block at (xa, ya) that is not smooth: its upper and lower 4 × 2 halves (else its
  // left and right 2 × 4 halves) are tried as blocks of their own, with the same test on their
  // corners and the two midpoints of their long edges (all on the block's 3 × 3 lattice of
  // marched points); what no half interpolates is marched. Where a window edge crosses a block
  // of wall, the half of wall keeps its interpolation.
  void halves(int xa, int ya, std::size_t i, std::size_t& marched, std::size_t& interpolated);
  // Every owned pixel of [xa, xb) × [ya, yb) exactly.
  void all_exact(int xa, int xb, int ya, int yb, std::size_t i, std::size_t& marched) {
    for (int row = ya; row < yb; ++row)
      for (int col = xa; col < xb; ++col) ensure(at(col, row, i), marched);
  }

 private:
  const GeometryPass& pass_;
  double tolerance_;
  const std::function<bool(std::size_t)>& glossy_;
  const std::function<int(std::size_t)>& class_;
  const std::function<Xyz(std::size_t)>& exact_;
  std::vector<Xyz>& out_;
  static constexpr std::uint8_t kExact = 1, kInterpolated = 2;
  std::vector<std::uint8_t> done_;  // out_[k] is the exact march (kExact) or an interpolation
  std::atomic<std::size_t> reverted_{0};

 public:
  std::size_t reverted() const { return reverted_.load(); }
};

void Reuse::refine(int xa, int xb, int ya, int yb, std::size_t i, int min_block, std::size_t& marched,
                   std::size_t& interpolated) {
  const int xm = (xa + xb) / 2, ym = (ya + yb) / 2;
  const std::uint32_t corner[4] = {at(xa, ya, i), at(xb, ya, i), at(xa, yb, i), at(xb, yb, i)};
  // Corners on the right or bottom edge may lie in a sibling block processed later (siblings
  // run in row-major order within one task) or in a neighbouring top-level block (processed in
  // another round, never concurrently).
  for (std::uint32_t k : corner) ensure(k, marched);
  const std::uint32_t centre = at(xm, ym, i);
  // The check points: the centre and the four edge midpoints (the children's corners, marched
  // anyway if the block is split).
  const std::uint32_t mid[5] = {centre, at(xm, ya, i), at(xa, ym, i), at(xb, ym, i), at(xm, yb, i)};
  const double fxm = double(xm - xa) / (xb - xa), fym = double(ym - ya) / (yb - ya);
  const double fx[5] = {fxm, fxm, 0.0, 1.0, fxm}, fy[5] = {fym, 0.0, fym, fym, 1.0};
  const int cls = glossy(centre) ? class_(centre) : -1;
  // Whether sample k may take the centre's interpolation.
  const auto alike = [&](std::uint32_t k) {
    return glossy(k) && same_plane(pass_.surfaces[centre], pass_.surfaces[k]) && class_(k) == cls;
  };
  bool smooth = cls >= 0;
  for (int j = 0; smooth && j < 4; ++j) smooth = alike(corner[j]);
  for (int j = 1; smooth && j < 5; ++j) smooth = alike(mid[j]);
  Xyz c[4];
  if (smooth) {
    for (int j = 0; j < 4; ++j) c[j] = out_[corner[j]];
    for (int j = 0; smooth && j < 5; ++j) {
      ensure(mid[j], marched);
      smooth = predicts(c, fx[j], fy[j], out_[mid[j]], tolerance_);
    }
  }
  if (smooth) {
    for (int row = ya; row < yb; ++row)
      for (int col = xa; col < xb; ++col) {
        const std::uint32_t k = at(col, row, i);
        if (!glossy(k) || done_[k]) continue;
        if (alike(k)) {
          out_[k] = bilinear(c, double(col - xa) / (xb - xa), double(row - ya) / (yb - ya));
          done_[k] = kInterpolated;
          ++interpolated;
        } else {
          ensure(k, marched);
        }
      }
    return;
  }
  if (xa >= pass_.width || ya >= pass_.height) return;  // wholly outside the image
  if (xb - xa <= min_block || yb - ya <= min_block) {
    if (xb - xa == 4 && yb - ya == 4)
      halves(xa, ya, i, marched, interpolated);
    else
      all_exact(xa, std::min(xb, pass_.width), ya, std::min(yb, pass_.height), i, marched);
    return;
  }
  // Split in four (each child marches its corners first).
  refine(xa, xm, ya, ym, i, min_block, marched, interpolated);
  refine(xm, xb, ya, ym, i, min_block, marched, interpolated);
  refine(xa, xm, ym, yb, i, min_block, marched, interpolated);
  refine(xm, xb, ym, yb, i, min_block, marched, interpolated);
}

void Reuse::halves(int xa, int ya, std::size_t i, std::size_t& marched, std::size_t& interpolated) {
  constexpr int kSize = 4;
  const int xb = xa + kSize, yb = ya + kSize, xm = xa + kSize / 2, ym = ya + kSize / 2;
  for (int y : {ya, ym, yb})
    for (int x : {xa, xm, xb}) ensure(at(x, y, i), marched);
  bool taken[kSize][kSize] = {};  // [row − ya][col − xa]: interpolated by a half
  // Rectangle [x0, x1] × [y0, y1] with its three check points (the midpoints of its long edges,
  // on the lattice, and its centre, marched here: the short direction is checked too); true if
  // it was smooth and interpolated.
  const auto try_half = [&](int x0, int x1, int y0, int y1, const int(&check_x)[3], const int(&check_y)[3]) {
    const std::uint32_t corner[4] = {at(x0, y0, i), at(x1, y0, i), at(x0, y1, i), at(x1, y1, i)};
    const std::uint32_t check[3] = {at(check_x[0], check_y[0], i), at(check_x[1], check_y[1], i), at(check_x[2], check_y[2], i)};
    const std::uint32_t ref = check[0];
    const int cls = glossy(ref) ? class_(ref) : -1;
    if (cls < 0) return false;
    const auto alike = [&](std::uint32_t k) {
      return glossy(k) && same_plane(pass_.surfaces[ref], pass_.surfaces[k]) && class_(k) == cls;
    };
    for (std::uint32_t k : corner)
      if (!alike(k)) return false;
    if (!alike(check[1]) || !alike(check[2])) return false;
    Xyz c[4];
    for (int j = 0; j < 4; ++j) c[j] = out_[corner[j]];
    for (int j = 0; j < 3; ++j) {
      ensure(check[j], marched);
      if (!predicts(c, double(check_x[j] - x0) / (x1 - x0), double(check_y[j] - y0) / (y1 - y0), out_[check[j]], tolerance_))
        return false;
    }
    for (int row = y0; row < y1; ++row)
      for (int col = x0; col < x1; ++col) {
        const std::uint32_t k = at(col, row, i);
        if (!glossy(k) || done_[k] || !alike(k)) continue;
        out_[k] = bilinear(c, double(col - x0) / (x1 - x0), double(row - y0) / (y1 - y0));
        done_[k] = kInterpolated;
        taken[row - ya][col - xa] = true;
        ++interpolated;
      }
    return true;
  };
  bool any = try_half(xa, xb, ya, ym, {xm, xm, xm}, {ya, ym, ya + 1});
  any = try_half(xa, xb, ym, yb, {xm, xm, xm}, {ym, yb, ym + 1}) || any;
  if (!any) {
    try_half(xa, xm, ya, yb, {xa, xm, xa + 1}, {ym, ym, ym});
    try_half(xm, xb, ya, yb, {xm, xb, xm + 1}, {ym, ym, ym});
  }
  for (int row = ya; row < std::min(yb, pass_.height); ++row)
    for (int col = xa; col < std::min(xb, pass_.width); ++col)
      if (!taken[row - ya][col - xa]) ensure(at(col, row, i), marched);
}

}  // namespace

SpecularReuseStats shade_specular_with_reuse(const GeometryPass& pass, int block, double tolerance,
                                             const std::function<bool(std::size_t)>& glossy,
                                             const std::function<int(std::size_t)>& reuse_class,
                                             const std::function<Xyz(std::size_t)>& exact, int threads, std::vector<Xyz>& out) {
  const int w = pass.width, h = pass.height;
  const std::size_t spp = static_cast<std::size_t>(pass.samples);
  Reuse r(pass, tolerance, glossy, reuse_class, exact, out);
  std::atomic<std::size_t> n_exact{0}, n_interp{0};
  // Block sizes: the top level `block` rounded down to min_block·2^j; min_block = 4 (below that
  // a block's exact samples are as many as its interpolated ones).
  constexpr int kMinBlock = 4;
  int top = kMinBlock;
  while (top * 2 <= block) top *= 2;
  const bool reuse = block >= kMinBlock && tolerance > 0.0;
  if (!reuse) {
    run_with_threads(threads, [&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, h, 1), [&](const tbb::blocked_range<int>& rows) {
        std::size_t marched = 0;
        for (int row = rows.begin(); row != rows.end(); ++row)
          for (std::size_t i = 0; i < spp; ++i) r.all_exact(0, w, row, row + 1, i, marched);
        n_exact += marched;
      });
    });
    return {n_exact.load(), 0};
  }
  // Top-level blocks cover the image; those overhanging its right or bottom edge are split.
  const int nx = (w - 1 + top - 1) / top, ny = (h - 1 + top - 1) / top;
  // Each top-level block refines itself: it writes (interpolates) only its own pixels
  // [x0, x0 + top) × [y0, y0 + top) and marches, on demand, the corners and check points it
  // needs, including those on its right and bottom edges, which belong to its neighbours. Blocks
  // run in four rounds by the parity of (bx, by): blocks of one round share no sample (not even a
  // corner), so no task marches or reads a sample another may write, and every round sees the
  // samples the earlier rounds marched in a fixed order: the result does not depend on the thread
  // count. (Marching every other pixel of every block edge up front, as before, cost ~9,400
  // samples on the paper figure, most of them on edges of blocks that were smooth.)
  for (int round = 0; round < 4; ++round) {
    const int px = round % 2, py = round / 2;
    const int cols = (nx - px + 1) / 2, rows = (ny - py + 1) / 2;  // blocks of this round
    run_with_threads(threads, [&] {
      // One task per block: their costs differ widely (a block of open wall is one check, one
      // cut by windows is marched at a third of its pixels).
      tbb::parallel_for(tbb::blocked_range<int>(0, cols * rows, 1), [&](const tbb::blocked_range<int>& blocks) {
        std::size_t marched = 0, interpolated = 0;
        for (int j = blocks.begin(); j != blocks.end(); ++j) {
          const int bx = 2 * (j % cols) + px, by = 2 * (j / cols) + py;
          for (std::size_t i = 0; i < spp; ++i)
            r.refine(bx * top, (bx + 1) * top, by * top, (by + 1) * top, i, kMinBlock, marched, interpolated);
        }
        n_exact += marched;
        n_interp += interpolated;
      });
    });
  }
  return {n_exact.load(), n_interp.load() - r.reverted()};
}

}  // namespace skyband
