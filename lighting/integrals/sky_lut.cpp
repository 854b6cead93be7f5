#include "lighting/integrals/sky_lut.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#include "geometry/bands/sky_integral.h"
#include "geometry/core/gauss_legendre.h"
#include "geometry/core/input_error.h"

namespace skyband {

SkyLut::SkyLut(const BandFrame& frame, std::span<const double> line_deltas_rad, const SkyRadianceFn& sky, int alpha_cells)
    : lines_(line_deltas_rad.size()), cells_(alpha_cells), deltas_(line_deltas_rad.begin(), line_deltas_rad.end()) {
  if (alpha_cells < 1) throw InputError("sky look-up table: alpha cell count must be ≥ 1, got " + std::to_string(alpha_cells));
  step_rad_ = kPi / cells_;
  inv_step_ = cells_ / kPi;
  table_.assign(lines_ * static_cast<std::size_t>(cells_ + 1) * kSpectrumSamples, 0.0);
  Spectrum radiance;
  for (std::size_t l = 0; l < lines_; ++l) {
    const double delta = deltas_[l];
    Spectrum acc;  // E_l at the current node
    double* out = &table_[l * static_cast<std::size_t>(cells_ + 1) * kSpectrumSamples];
    std::copy(acc.v.begin(), acc.v.end(), out);
    for (int j = 0; j < cells_; ++j) {
      const double mid = (j + 0.5) * step_rad_;
      for (int g = 0; g < 4; ++g) {
        const double a = mid + 0.5 * step_rad_ * kGauss4Nodes[g];
        const double s = std::sin(a);
        sky(frame.direction(a, delta), radiance);
        const double k = 0.5 * step_rad_ * kGauss4Weights[g] * s * s;
        for (int i = 0; i < kSpectrumSamples; ++i) acc[i] += k * radiance[i];
      }
      std::copy(acc.v.begin(), acc.v.end(), out + static_cast<std::size_t>(j + 1) * kSpectrumSamples);
    }
  }
  tabulate_whole();
}

void SkyLut::tabulate_whole() {
  const std::size_t c = static_cast<std::size_t>(channels_);
  whole_.assign(lines_ * c, 0.0);
  int j0, j1;
  double t0, t1;
  locate(0.0, j0, t0);
  locate(kPi, j1, t1);
  for (std::size_t l = 0; l < lines_; ++l) {
    const double* a0 = row(l, j0);
    const double* b0 = a0 + c;
    const double* a1 = row(l, j1);
    const double* b1 = a1 + c;
    for (std::size_t i = 0; i < c; ++i) whole_[l * c + i] = (a1[i] + t1 * (b1[i] - a1[i])) - (a0[i] + t0 * (b0[i] - a0[i]));
  }
}

void SkyLut::require_spectral() const {
  if (channels_ != kSpectrumSamples) throw std::logic_error("SkyLut: spectral access to a projected table");
}

SkyLut SkyLut::project(std::span<const Spectrum> weights) const {
  require_spectral();
  SkyLut p;
  p.lines_ = lines_;
  p.cells_ = cells_;
  p.channels_ = static_cast<int>(weights.size());
  p.step_rad_ = step_rad_;
  p.inv_step_ = inv_step_;
  p.deltas_ = deltas_;
  const std::size_t nodes = lines_ * static_cast<std::size_t>(cells_ + 1);
  p.table_.assign(nodes * weights.size(), 0.0);
  for (std::size_t n = 0; n < nodes; ++n) {
    const double* e = &table_[n * kSpectrumSamples];
    for (std::size_t k = 0; k < weights.size(); ++k) {
      double sum = 0;
      for (int i = 0; i < kSpectrumSamples; ++i) sum += weights[k][i] * e[i];
      p.table_[n * weights.size() + k] = sum;
    }
  }
  p.tabulate_whole();
  return p;
}

void SkyLut::add_interval(std::size_t line, double alpha0_rad, double alpha1_rad, double weight, double* acc) const {
  accumulate(line, alpha0_rad, alpha1_rad, weight, acc, static_cast<std::size_t>(channels_));
}

void diffuse_sky_channels(const PointVisibilityView& v, const SkyLut& lut, double* out) {
  for (int k = 0; k < lut.channels(); ++k) out[k] = 0.0;
  const std::size_t n = std::min(v.band_count(), lut.line_count());
  auto sum = [&](auto&& add) {
    for (std::size_t b = 0; b < n; ++b) {
      const double w = v.band_weight(b);
      for (const VisibleInterval& iv : v.visible(b)) add(b, clamp_alpha(iv.alpha0_rad), clamp_alpha(iv.alpha1_rad), w);
    }
  };
  if (lut.channels() == 3) {  // XYZ, the renderer's tables: the channel loop unrolled
    sum([&](std::size_t b, double a0, double a1, double w) { lut.add_interval_n<3>(b, a0, a1, w, out); });
  } else {
    sum([&](std::size_t b, double a0, double a1, double w) { lut.add_interval(b, a0, a1, w, out); });
  }
}

void SkyLut::primitive(std::size_t line, double alpha_rad, Spectrum& out) const {
  require_spectral();
  int j;
  double t;
  locate(alpha_rad, j, t);
  const double* a = row(line, j);
  const double* b = a + kSpectrumSamples;
  for (int i = 0; i < kSpectrumSamples; ++i) out[i] = a[i] + t * (b[i] - a[i]);
}

void SkyLut::add_interval(std::size_t line, double alpha0_rad, double alpha1_rad, double weight, Spectrum& acc) const {
  require_spectral();
  add_interval(line, alpha0_rad, alpha1_rad, weight, acc.v.data());
}

Spectrum diffuse_sky_irradiance(const PointVisibilityView& v, const SkyLut& lut) {
  if (lut.channels() != kSpectrumSamples) throw std::logic_error("diffuse_sky_irradiance: a projected table");
  Spectrum e;
  diffuse_sky_channels(v, lut, e.v.data());
  return e;
}

SkyLutCache::SkyLutCache(SkyRadianceFn sky, int alpha_cells, double frame_quantum, std::vector<std::vector<Spectrum>> projections,
                         bool keep_spectral)
    : sky_(std::move(sky)),
      alpha_cells_(alpha_cells),
      quantum_(frame_quantum),
      projections_(std::move(projections)),
      keep_spectral_(keep_spectral) {
  if (!(frame_quantum > 0))
    throw InputError("sky look-up table cache: frame quantum must be > 0, got " + std::to_string(frame_quantum));
  if (alpha_cells < 1)
    throw InputError("sky look-up table cache: alpha cell count must be ≥ 1, got " + std::to_string(alpha_cells));
}

std::shared_ptr<const SkyLut> SkyLutCache::lut_for(const PointVisibilityView& v) {
  if (!keep_spectral_) throw std::logic_error("SkyLutCache::lut_for: the cache keeps projected tables only");
  return entry_for(v)->lut;
}

std::shared_ptr<const SkyLut> SkyLutCache::projected_for(const PointVisibilityView& v, std::size_t k) {
  return entry_for(v)->projected.at(k);
}

std::shared_ptr<const SkyLutCache::Entry> SkyLutCache::entry_for(const PointVisibilityView& v) {
  const BandFrame& f = v.frame();
  std::int64_t q[6];
  for (int i = 0; i < 3; ++i) {
    q[i] = std::llround(f.normal[i] / quantum_);
    q[3 + i] = std::llround(f.x[i] / quantum_);
  }
  // FNV-1a over the quantised frame and the bands' δ bits (no allocation on the hit path).
  std::uint64_t hash = 1469598103934665603ull;
  auto mix = [&hash](std::uint64_t x) {
    for (int k = 0; k < 8; ++k) {
      hash ^= (x >> (8 * k)) & 0xffu;
      hash *= 1099511628211ull;
    }
  };
  for (std::int64_t x : q) mix(static_cast<std::uint64_t>(x));
  mix(v.band_count());
  for (std::size_t b = 0; b < v.band_count(); ++b) mix(std::bit_cast<std::uint32_t>(v.band(b).delta_rad));

  auto matches = [&](const Entry& e) {
    if (!std::equal(q, q + 6, e.q) || e.deltas.size() != v.band_count()) return false;
    for (std::size_t b = 0; b < v.band_count(); ++b)
      if (std::bit_cast<std::uint32_t>(e.deltas[b]) != std::bit_cast<std::uint32_t>(v.band(b).delta_rad)) return false;
    return true;
  };
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = map_.find(hash);
    if (it != map_.end())
      for (const auto& e : it->second)
        if (matches(*e)) return e;
  }
  // Build outside the lock (other threads keep shading); the first insert wins.
  Entry e;
  std::copy(q, q + 6, e.q);
  std::vector<double> deltas(v.band_count());
  e.deltas.resize(v.band_count());
  for (std::size_t b = 0; b < v.band_count(); ++b) {
    e.deltas[b] = v.band(b).delta_rad;
    deltas[b] = v.band(b).delta_rad;
  }
  auto spectral = std::make_shared<const SkyLut>(f, deltas, sky_, alpha_cells_);
  for (const std::vector<Spectrum>& w : projections_) e.projected.push_back(std::make_shared<const SkyLut>(spectral->project(w)));
  if (keep_spectral_) e.lut = std::move(spectral);
  std::lock_guard<std::mutex> lock(mutex_);
  auto& bucket = map_[hash];
  for (const auto& other : bucket)
    if (matches(*other)) return other;
  bucket.push_back(std::make_shared<const Entry>(std::move(e)));
  ++count_;
  return bucket.back();
}

bool SkyLutCache::same_table(const PointVisibilityView& a, const PointVisibilityView& b) {
  if (a.frame().normal != b.frame().normal || a.frame().x != b.frame().x || a.band_count() != b.band_count()) return false;
  for (std::size_t i = 0; i < a.band_count(); ++i)
    if (std::bit_cast<std::uint32_t>(a.band(i).delta_rad) != std::bit_cast<std::uint32_t>(b.band(i).delta_rad)) return false;
  return true;
}

std::size_t SkyLutCache::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return count_;
}

Spectrum diffuse_sky_irradiance(const PointVisibilityView& v, SkyLutCache& cache) {
  return diffuse_sky_irradiance(v, *cache.lut_for(v));
}

}  // namespace skyband
