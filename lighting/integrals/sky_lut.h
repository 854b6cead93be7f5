#pragma once
// Per-band sky look-up tables (seed eq. 1; method.md §2; reference-notes §1.4):
//     E_l(α) = ∫_0^α L(ω(α', δ_l)) sin²α' dα',   α ∈ [0, π]
// tabulated for every sample plane δ_l of one band frame and every wavelength sample, so that a
// visible interval [α0, α1] of band l costs two look-ups and the diffuse sky irradiance of a
// cached point is
//     E(λ) = Σ_b w_b Σ_visible [E_b(α1) − E_b(α0)]           W·m⁻²·nm⁻¹
// (w_b = s1 − s0 the band's δ-weight). L is in W·m⁻²·sr⁻¹·nm⁻¹, E_l in the same unit × rad.
//
// Accuracy: each α cell is integrated with 4-point Gauss–Legendre (error ~h⁸·|f⁽⁸⁾|, negligible
// for smooth skies) and E_l is interpolated linearly between nodes, with error ≤ h²/8·max|f'|,
// f = L sin²α: for the default 360 cells (h = 0.5°) that is 9.5·10⁻⁶·max|f'| (≈ 10⁻⁵ L_z for
// the CIE overcast sky), far below the band discretisation error (reference-notes §1.7).
//
// The tables depend only on the frame orientation (axis x, normal) and the band layout, never on
// the point (the sky is at infinity), so SkyLutCache keys them on the quantised frame + the
// bands' δ: a building with a few face orientations builds a few tables per sky.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <unordered_map>
#include <vector>

#include "geometry/bands/band_frame.h"
#include "geometry/bands/visibility_cache.h"
#include "lighting/spectrum/spectrum.h"

namespace skyband {

// Sky radiance in a world direction (unit, z up): out = L(λ, ω) in W·m⁻²·sr⁻¹·nm⁻¹.
using SkyRadianceFn = std::function<void(const Vec3& world_dir, Spectrum& radiance_W_m2_sr_nm)>;

class SkyLut {
 public:
  // Tables for the sample planes `line_deltas_rad` of `frame`, `alpha_cells` equal α cells.
  SkyLut(const BandFrame& frame, std::span<const double> line_deltas_rad, const SkyRadianceFn& sky, int alpha_cells = 360);

  std::size_t line_count() const { return lines_; }
  int alpha_cells() const { return cells_; }
  double line_delta_rad(std::size_t line) const { return deltas_[line]; }
  // Values per node: kSpectrumSamples for a spectral table, the weight count for a projected one.
  int channels() const { return channels_; }

  // The table of the linear functionals P_k[E_l] = Σ_i w_k(λ_i)·E_l(λ_i), one channel per
  // weight spectrum (e.g. CIE XYZ weights times an albedo: the table then integrates straight to
  // a colour). Exact: projection commutes with the quadrature and the interpolation. Spectral
  // tables only (else std::logic_error).
  SkyLut project(std::span<const Spectrum> weights) const;

  // Spectral tables only (else std::logic_error): out = E_l(α) (α clamped to [0, π]).
  void primitive(std::size_t line, double alpha_rad, Spectrum& out) const;
  // acc += weight·(E_l(α1) − E_l(α0)).
  void add_interval(std::size_t line, double alpha0_rad, double alpha1_rad, double weight, Spectrum& acc) const;
  // Any table: acc[k] += weight·(E_l(α1) − E_l(α0))[k], k < channels().
  void add_interval(std::size_t line, double alpha0_rad, double alpha1_rad, double weight, double* acc) const;
  // The same for a table of N == channels() channels, inline with the channel loop unrolled (the
  // renderer's diffuse pass: ~5·10⁷ intervals per image); the same expression, so the same bits.
  template <int N>
  void add_interval_n(std::size_t line, double alpha0_rad, double alpha1_rad, double weight, double* acc) const {
    accumulate(line, alpha0_rad, alpha1_rad, weight, acc, N);
  }

 private:
  SkyLut() = default;
  const double* row(std::size_t line, int node) const {
    return &table_[(line * static_cast<std::size_t>(cells_ + 1) + static_cast<std::size_t>(node)) *
                   static_cast<std::size_t>(channels_)];
  }
  // acc[i] += weight·(E_l(α1) − E_l(α0))[i], i < nc == channels(): the one body of both
  // add_interval forms (inlined with a constant nc, the channel loop unrolls).
  void accumulate(std::size_t line, double alpha0_rad, double alpha1_rad, double weight, double* acc, std::size_t nc) const {
    if (alpha0_rad <= 0.0 && alpha1_rad >= kPi) {  // the whole line (locate clamps to [0, π] alike)
      const double* w = &whole_[line * nc];
      for (std::size_t i = 0; i < nc; ++i) acc[i] += weight * w[i];
      return;
    }
    int j0, j1;
    double t0, t1;
    locate(alpha0_rad, j0, t0);
    locate(alpha1_rad, j1, t1);
    const double* a0 = &table_[(line * static_cast<std::size_t>(cells_ + 1) + static_cast<std::size_t>(j0)) * nc];
    const double* b0 = a0 + nc;
    const double* a1 = &table_[(line * static_cast<std::size_t>(cells_ + 1) + static_cast<std::size_t>(j1)) * nc];
    const double* b1 = a1 + nc;
    for (std::size_t i = 0; i < nc; ++i) acc[i] += weight * ((a1[i] + t1 * (b1[i] - a1[i])) - (a0[i] + t0 * (b0[i] - a0[i])));
  }
  void locate(double alpha_rad, int& node, double& t) const {
    const double x = std::clamp(alpha_rad, 0.0, kPi) * inv_step_;  // a product: ~10⁸ per image
    node = std::min(static_cast<int>(x), cells_ - 1);
    t = std::min(x - node, 1.0);
  }
  void require_spectral() const;
  // whole_ = E_l(π) − E_l(0) per line and channel, by the same expression add_interval evaluates
  // (so a whole visible line, the commonest interval, costs no look-up and gives the same bits).
  void tabulate_whole();

  std::size_t lines_ = 0;
  int cells_ = 0;
  int channels_ = kSpectrumSamples;
  double step_rad_ = 0;
  double inv_step_ = 0;  // 1/step_rad_ (cells per radian)
  std::vector<double> deltas_;
  std::vector<double> table_;  // [line][node 0..cells][channel]
  std::vector<double> whole_;  // [line][channel]
};

// E(λ) of one cached point from a table built for its frame and bands (W·m⁻²·nm⁻¹).
Spectrum diffuse_sky_irradiance(const PointVisibilityView& v, const SkyLut& lut);
// The same through any table: out[k] = Σ_b w_b Σ_visible [E_b(α1) − E_b(α0)][k], k < channels().
void diffuse_sky_channels(const PointVisibilityView& v, const SkyLut& lut, double* out);

// Tables of one sky, built on first use per (quantised frame, band layout). Thread-safe.
class SkyLutCache {
 public:
  // `frame_quantum`: components of the frame's normal and axis are rounded to this before keying
  // (frames closer than this share a table; the error this adds is of the same order).
  // `projections`: weight sets; with each spectral table the cache also keeps its projection by
  // every set (SkyLut::project), served by projected_for.
  // `keep_spectral` false: only the projected tables are kept (a spectral table of N = 64 bands
  // is 3.8 MB, a projection by 3 weights 0.28 MB: on a real model with a thousand distinct face
  // orientations that is the difference between gigabytes and a few hundred MB); lut_for then
  // throws std::logic_error.
  explicit SkyLutCache(SkyRadianceFn sky, int alpha_cells = 360, double frame_quantum = 1e-9,
                       std::vector<std::vector<Spectrum>> projections = {}, bool keep_spectral = true);

  std::shared_ptr<const SkyLut> lut_for(const PointVisibilityView& v);
  // The table of v's frame and bands projected by weight set k.
  std::shared_ptr<const SkyLut> projected_for(const PointVisibilityView& v, std::size_t k);
  std::size_t size() const;
  // True when a and b are served the same table: bit-identical frames and band planes (a
  // sufficient condition, cheaper than a look-up). Lets a caller keep the last table for runs of
  // samples on one plane, sparing the hash over every band and the lock.
  static bool same_table(const PointVisibilityView& a, const PointVisibilityView& b);

 private:
  struct Entry {
    std::int64_t q[6];
    std::vector<float> deltas;
    std::shared_ptr<const SkyLut> lut;
    std::vector<std::shared_ptr<const SkyLut>> projected;
  };
  std::shared_ptr<const Entry> entry_for(const PointVisibilityView& v);

  SkyRadianceFn sky_;
  int alpha_cells_;
  double quantum_;
  std::vector<std::vector<Spectrum>> projections_;
  bool keep_spectral_ = true;
  mutable std::mutex mutex_;
  std::unordered_map<std::uint64_t, std::vector<std::shared_ptr<const Entry>>> map_;
  std::size_t count_ = 0;
};

Spectrum diffuse_sky_irradiance(const PointVisibilityView& v, SkyLutCache& cache);

}  // namespace skyband
