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
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <unordered_map>
#include <vector>

#include "geometry/band_frame.h"
#include "geometry/visibility_cache.h"
#include "lighting/spectrum.h"

namespace skyband {

// Sky radiance in a world direction (unit, z up): out = L(λ, ω) in W·m⁻²·sr⁻¹·nm⁻¹.
using SkyRadianceFn = std::function<void(const Vec3& world_dir, Spectrum& radiance_W_m2_sr_nm)>;

class SkyLut {
 public:
  // Tables for the sample planes `line_deltas_rad` of `frame`, `alpha_cells` equal α cells.
  SkyLut(const BandFrame& frame, std::span<const double> line_deltas_rad, const SkyRadianceFn& sky,
         int alpha_cells = 360);

  std::size_t line_count() const { return lines_; }
  int alpha_cells() const { return cells_; }
  double line_delta_rad(std::size_t line) const { return deltas_[line]; }

  // out = E_l(α) (α clamped to [0, π]).
  void primitive(std::size_t line, double alpha_rad, Spectrum& out) const;
  // acc += weight·(E_l(α1) − E_l(α0)).
  void add_interval(std::size_t line, double alpha0_rad, double alpha1_rad, double weight, Spectrum& acc) const;

 private:
  const double* row(std::size_t line, int node) const {
    return &table_[(line * static_cast<std::size_t>(cells_ + 1) + static_cast<std::size_t>(node)) * kSpectrumSamples];
  }
  void locate(double alpha_rad, int& node, double& t) const;

  std::size_t lines_ = 0;
  int cells_ = 0;
  double step_rad_ = 0;
  std::vector<double> deltas_;
  std::vector<double> table_;  // [line][node 0..cells][wavelength]
};

// E(λ) of one cached point from a table built for its frame and bands (W·m⁻²·nm⁻¹).
Spectrum diffuse_sky_irradiance(const PointVisibilityView& v, const SkyLut& lut);

// Tables of one sky, built on first use per (quantised frame, band layout). Thread-safe.
class SkyLutCache {
 public:
  // `frame_quantum`: components of the frame's normal and axis are rounded to this before keying
  // (frames closer than this share a table; the error this adds is of the same order).
  explicit SkyLutCache(SkyRadianceFn sky, int alpha_cells = 360, double frame_quantum = 1e-9);

  std::shared_ptr<const SkyLut> lut_for(const PointVisibilityView& v);
  std::size_t size() const;

 private:
  struct Entry {
    std::int64_t q[6];
    std::vector<float> deltas;
    std::shared_ptr<const SkyLut> lut;
  };
  SkyRadianceFn sky_;
  int alpha_cells_;
  double quantum_;
  mutable std::mutex mutex_;
  std::unordered_map<std::uint64_t, std::vector<Entry>> map_;
  std::size_t count_ = 0;
};

Spectrum diffuse_sky_irradiance(const PointVisibilityView& v, SkyLutCache& cache);

}  // namespace skyband
