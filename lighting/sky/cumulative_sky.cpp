#include "lighting/sky/cumulative_sky.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "geometry/core/input_error.h"
#include "geometry/core/thread_arena.h"
#include "lighting/integrals/fast_exp.h"
#include "lighting/sky/perez_sky.h"

namespace skyband {

namespace {

constexpr int kNodes = kCumulativeSkyCells + 1;

// e^x, by the table of fast_exp.h where x ≤ 0 (b ≤ 0 always; d < 0 in all but odd overcast skies).
double exp_of(double x) {
  return x <= 0 ? exp_neg(-x) : std::exp(x);
}

struct HourSky {
  PerezSkyCoefficients k;
  Vec3 sun;
  double w_W, w_lx;  // Δt·scale per channel
};

void check(double v, std::size_t i, const char* what) {
  if (!(v >= 0) || !std::isfinite(v))
    throw InputError("weather interval " + std::to_string(i + 1) + ": " + what + " " + std::to_string(v) +
                     " must be finite and >= 0");
}

}  // namespace

CumulativeSky cumulative_perez_sky(std::span<const WeatherHour> hours, int threads) {
  CumulativeSky out;
  std::vector<HourSky> skies;
  for (std::size_t i = 0; i < hours.size(); ++i) {
    const WeatherHour& h = hours[i];
    check(h.hours, i, "length (h)");
    check(h.dhi_W_m2, i, "diffuse horizontal irradiance (W/m2)");
    check(h.dni_W_m2, i, "direct normal irradiance (W/m2)");
    check(h.dhi_lx, i, "diffuse horizontal illuminance (lx)");
    if (!(h.dhi_W_m2 > 0) || !(h.hours > 0)) continue;
    const double zenith = std::acos(std::clamp(h.sun_dir.z(), -1.0, 1.0));
    const PerezSkyCondition c = perez_sky_condition(h.dhi_W_m2, h.dni_W_m2, zenith, h.day_of_year);
    const PerezSky sky = make_perez_sky(c, h.sun_dir, h.dhi_W_m2);
    if (!(sky.scale > 0)) continue;
    skies.push_back({sky.coefficients, h.sun_dir, h.hours * sky.scale, h.hours * sky.scale * h.dhi_lx / h.dhi_W_m2});
    out.horizontal_Wh_m2 += h.hours * h.dhi_W_m2;
    out.horizontal_lxh += h.hours * h.dhi_lx;
    ++out.sky_hours;
  }
  // Σ over the hours at each coarse node; outside the disk the linear extension across the rim.
  std::vector<double> coarse(static_cast<std::size_t>(kNodes) * kNodes * 2, 0.0);
  const auto sum_at = [&](const Vec3& d, double& w, double& lx) {
    w = lx = 0;
    if (!(d.z() > 0)) return;
    // l = G(θ)·F(γ) as perez_relative_luminance, with cos γ used as it comes (no cos(acos)).
    const double inv_cos_theta = 1.0 / d.z();
    for (const HourSky& s : skies) {
      const double cg = std::clamp(d.dot(s.sun), -1.0, 1.0);
      const double g = std::max(0.0, 1.0 + s.k.a * exp_of(s.k.b * inv_cos_theta));
      const double f = std::max(0.0, 1.0 + s.k.c * exp_of(s.k.d * std::acos(cg)) + s.k.e * cg * cg);
      const double l = g * f;
      w += s.w_W * l;
      lx += s.w_lx * l;
    }
  };
  run_with_threads(threads, [&] {
    tbb::parallel_for(0, kNodes, [&](int iy) {
      const double step = 2.0 / kCumulativeSkyCells;
      for (int ix = 0; ix < kNodes; ++ix) {
        const double px = -1.0 + ix * step, py = -1.0 + iy * step;
        const double r = std::hypot(px, py);
        double w, lx;
        sum_at(sky_grid_disk_direction(px, py), w, lx);
        if (r > 1.0) {
          const double k = (2.0 - r) / r;
          double wi, lxi;
          sum_at(sky_grid_disk_direction(px * k, py * k), wi, lxi);
          w = std::max(0.0, 2 * w - wi);
          lx = std::max(0.0, 2 * lx - lxi);
        }
        double* c = &coarse[(static_cast<std::size_t>(iy) * kNodes + static_cast<std::size_t>(ix)) * 2];
        c[0] = w;
        c[1] = lx;
      }
    });
  });
  // Bilinear interpolation of the coarse sums at a direction above the horizon.
  out.grid = ProjectedSkyGrid::sample(
      2,
      [&](const Vec3& d, double* v) {
        const double k = 1.0 / (1.0 + d.z());
        const double u = (d.x() * k + 1.0) * 0.5 * kCumulativeSkyCells, t = (d.y() * k + 1.0) * 0.5 * kCumulativeSkyCells;
        const int ix = std::clamp(static_cast<int>(u), 0, kCumulativeSkyCells - 1);
        const int iy = std::clamp(static_cast<int>(t), 0, kCumulativeSkyCells - 1);
        const double fx = std::clamp(u - ix, 0.0, 1.0), fy = std::clamp(t - iy, 0.0, 1.0);
        const auto at = [&](int x, int y, int c) {
          return coarse[(static_cast<std::size_t>(y) * kNodes + static_cast<std::size_t>(x)) * 2 + c];
        };
        for (int c = 0; c < 2; ++c)
          v[c] = (1 - fy) * ((1 - fx) * at(ix, iy, c) + fx * at(ix + 1, iy, c)) +
                 fy * ((1 - fx) * at(ix, iy + 1, c) + fx * at(ix + 1, iy + 1, c));
      },
      threads);
  return out;
}

}  // namespace skyband
