#include "lighting/sky/perez_sky.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "geometry/core/input_error.h"
#include "lighting/integrals/fast_exp.h"

namespace skyband {

namespace {

constexpr double kHalfPi = 0.5 * kPi;
constexpr double kDeg = kPi / 180.0;

// Perez93 Table 1: per bin, the four coefficients x1..x4 of a, b, c, d, e in that order
// (x = x1 + x2 Z + Δ (x3 + x4 Z); bin 1's c and d use eqs. 7–8 instead). The values are those of
// Radiance's gendaymtx.c (PerezCoeff, which cites the paper together with its erratum, Solar
// Energy 51(5) 423) and gendaylit.c (coeff_perez); the two agree digit for digit.
constexpr double kPerezTable[kPerezBinCount][5][4] = {{{1.3525, -0.2576, -0.2690, -1.4366},
                                                       {-0.7670, 0.0007, 1.2734, -0.1233},
                                                       {2.8000, 0.6004, 1.2375, 1.0000},
                                                       {1.8734, 0.6297, 0.9738, 0.2809},
                                                       {0.0356, -0.1246, -0.5718, 0.9938}},
                                                      {{-1.2219, -0.7730, 1.4148, 1.1016},
                                                       {-0.2054, 0.0367, -3.9128, 0.9156},
                                                       {6.9750, 0.1774, 6.4477, -0.1239},
                                                       {-1.5798, -0.5081, -1.7812, 0.1080},
                                                       {0.2624, 0.0672, -0.2190, -0.4285}},
                                                      {{-1.1000, -0.2515, 0.8952, 0.0156},
                                                       {0.2782, -0.1812, -4.5000, 1.1766},
                                                       {24.7219, -13.0812, -37.7000, 34.8438},
                                                       {-5.0000, 1.5218, 3.9229, -2.6204},
                                                       {-0.0156, 0.1597, 0.4199, -0.5562}},
                                                      {{-0.5484, -0.6654, -0.2672, 0.7117},
                                                       {0.7234, -0.6219, -5.6812, 2.6297},
                                                       {33.3389, -18.3000, -62.2500, 52.0781},
                                                       {-3.5000, 0.0016, 1.1477, 0.1062},
                                                       {0.4659, -0.3296, -0.0876, -0.0329}},
                                                      {{-0.6000, -0.3566, -2.5000, 2.3250},
                                                       {0.2937, 0.0496, -5.6812, 1.8415},
                                                       {21.0000, -4.7656, -21.5906, 7.2492},
                                                       {-3.5000, -0.1554, 1.4062, 0.3988},
                                                       {0.0032, 0.0766, -0.0656, -0.1294}},
                                                      {{-1.0156, -0.3670, 1.0078, 1.4051},
                                                       {0.2875, -0.5328, -3.8500, 3.3750},
                                                       {14.0000, -0.9999, -7.1406, 7.5469},
                                                       {-3.4000, -0.1078, -1.0750, 1.5702},
                                                       {-0.0672, 0.4016, 0.3017, -0.4844}},
                                                      {{-1.0000, 0.0211, 0.5025, -0.5119},
                                                       {-0.3000, 0.1922, 0.7023, -1.6317},
                                                       {19.0000, -5.0000, 1.2438, -1.9094},
                                                       {-4.0000, 0.0250, 0.3844, 0.2656},
                                                       {1.0468, -0.3788, -2.4517, 1.4656}},
                                                      {{-1.0500, 0.0289, 0.4260, 0.3590},
                                                       {-0.3250, 0.1156, 0.7781, 0.0025},
                                                       {31.0625, -14.5000, -46.1148, 55.3750},
                                                       {-7.2312, 0.4050, 13.3500, 0.6234},
                                                       {1.5000, -0.6426, 1.8564, 0.5636}}};

std::string fmt(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

void require_finite_nonnegative(double v, const char* what) {
  if (!std::isfinite(v) || v < 0) throw InputError(std::string("Perez sky: ") + what + " " + fmt(v) + " must be finite and >= 0");
}

// Gauss–Legendre rules on [0, 1] for n = 1..kMaxNodes, built once by Newton iteration on the
// three-term recurrence of P_n (nodes and weights to ~1 ulp).
constexpr int kMaxNodes = 128;
struct GaussRule {
  std::array<double, kMaxNodes> x{}, w{};
};

std::vector<GaussRule> build_gauss_rules() {
  std::vector<GaussRule> rules(kMaxNodes + 1);
  for (int n = 1; n <= kMaxNodes; ++n) {
    for (int i = 0; i < (n + 1) / 2; ++i) {
      double z = std::cos(kPi * (i + 0.75) / (n + 0.5));  // Tricomi's initial guess
      double dp = 1;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1, p1 = z;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (z * p1 - p0) / (z * z - 1);
        const double dz = p1 / dp;
        z -= dz;
        if (std::abs(dz) < 1e-16) break;
      }
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double w = 2.0 / ((1 - z * z) * dp * dp);
      // z is the i-th largest node on [−1, 1]; store in increasing order on [0, 1].
      rules[n].x[n - 1 - i] = 0.5 * (1 + z);
      rules[n].w[n - 1 - i] = 0.5 * w;
      rules[n].x[i] = 0.5 * (1 - z);
      rules[n].w[i] = 0.5 * w;
    }
    if (n % 2 == 1) rules[n].x[n / 2] = 0.5;
  }
  return rules;
}

const GaussRule& gauss_rule(int n) {
  static const std::vector<GaussRule> rules = build_gauss_rules();
  return rules[n];
}

// ∫_{ψa}^{ψb} μ exp(−s/μ) dψ, μ = A + B cos ψ decreasing on [ψa, ψb] ⊂ [0, π], s > 0, B > 0.
// exp(−s/μ) is C∞ but not analytic at μ = 0: it switches from 0 to 1 over μ ~ s, so one
// Gauss–Legendre rule over an arc that reaches the horizon converges slowly. Where the arc
// reaches below 16 s, that part is cut into pieces with μ ratio 4 (each is analytic in a
// Bernstein ellipse of fixed shape, so the rule converges geometrically whatever s); below s/20
// the integrand is < 2.1e-9 μ and is dropped (at most 2.1e-9 (s/20) π of the result). Node
// counts per piece: `top` for the piece that carries most of the integral, `mid` above μ = s,
// `low` below it.
struct ArcRule {
  const GaussRule* top;
  const GaussRule* mid;
  const GaussRule* low;
  int n_top, n_mid, n_low;
};

ArcRule arc_rule(int top, int mid, int low) {
  return {&gauss_rule(top), &gauss_rule(mid), &gauss_rule(low), top, mid, low};
}

// exp(−x) by lighting/integrals/fast_exp.h (relative error < 3e-11, far below the quadrature's).
double exp_term_arc(double A, double B, double s, double psi_a, double psi_b, const ArcRule& rule) {
  const auto mu_of = [&](double psi) { return A + B * std::cos(psi); };
  const auto psi_of = [&](double mu) { return std::acos(std::clamp((mu - A) / B, -1.0, 1.0)); };
  const auto gl = [&](double p0, double p1, const GaussRule& r, int n) {
    const double h = p1 - p0;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      const double mu = mu_of(p0 + h * r.x[i]);
      if (mu > 0) sum += r.w[i] * mu * exp_neg(s / mu);
    }
    return sum * h;
  };
  constexpr double kSmoothAbove = 16.0, kRatio = 4.0, kDropBelow = 1.0 / 20.0;
  const double mu_hi = mu_of(psi_a);
  const double mu_lo = std::max(mu_of(psi_b), 0.0);
  if (mu_lo >= kSmoothAbove * s || mu_hi <= kRatio * mu_lo) return gl(psi_a, psi_b, *rule.top, rule.n_top);
  const double floor_mu = std::max(mu_lo, kDropBelow * s);
  if (mu_hi <= floor_mu) return 0.0;
  double total = 0, psi = psi_a, mu = mu_hi;
  bool first = true;
  if (mu_hi > kSmoothAbove * s) {
    const double p = psi_of(kSmoothAbove * s);
    total += gl(psi_a, p, *rule.top, rule.n_top);
    psi = p;
    mu = kSmoothAbove * s;
    first = false;
  }
  while (mu > floor_mu) {
    double next_mu = mu / kRatio;
    if (next_mu < 1.5 * floor_mu) next_mu = floor_mu;
    const double p = next_mu <= mu_lo ? psi_b : psi_of(next_mu);
    if (first)
      total += gl(psi, p, *rule.top, rule.n_top);
    else if (mu <= s)
      total += gl(psi, p, *rule.low, rule.n_low);
    else
      total += gl(psi, p, *rule.mid, rule.n_mid);
    first = false;
    psi = p;
    mu = next_mu;
  }
  return total;
}

// J(γ) = ∫ G(μ) μ dψ over the whole circle of radius γ about the sun, restricted to
// 0 < μ ≤ mu_cap (mu_cap ≥ 1: no restriction). cos/sin of the sun zenith: cz, sz.
double circle_integral(const PerezSkyCoefficients& k, double cz, double sz, double mu_cap, double gamma, const ArcRule& rule) {
  const double A = std::cos(gamma) * cz;
  const double B = std::sin(gamma) * sz;
  const double s = -k.b;
  if (!(B > 1e-15)) {  // the circle is a point (γ = 0 or π) or the sun is at the zenith/nadir
    if (A <= 0 || A > mu_cap) return 0.0;
    return 2 * kPi * A * (1 + k.a * exp_neg(s / A));
  }
  // μ(ψ) = A + B cos ψ decreases on [0, π]; keep 0 < μ ≤ mu_cap.
  const double psi0 = A >= B ? kPi : (A <= -B ? 0.0 : std::acos(std::clamp(-A / B, -1.0, 1.0)));
  double psic = 0;
  if (mu_cap < 1) psic = A + B <= mu_cap ? 0.0 : (A - B >= mu_cap ? kPi : std::acos(std::clamp((mu_cap - A) / B, -1.0, 1.0)));
  if (psic >= psi0) return 0.0;
  const double j1 = A * (psi0 - psic) + B * (std::sin(psi0) - std::sin(psic));
  double je = 0;
  if (k.a != 0) je = s > 0 ? exp_term_arc(A, B, s, psic, psi0, rule) : j1;
  return 2 * (j1 + k.a * je);
}

// Parameters γ at which a circle of radius γ about the sun (zenith angle zs) touches the circle of
// zenith angle theta_c.
void tangencies(double zs, double theta_c, std::vector<double>& out) {
  out.push_back(std::abs(zs - theta_c));
  const double t = zs + theta_c;
  out.push_back(t <= kPi ? t : 2 * kPi - t);
}

double indicatrix_raw(double gamma, const PerezSkyCoefficients& k) {
  const double cg = std::cos(gamma);
  return 1 + k.c * std::exp(k.d * gamma) + k.e * cg * cg;
}

// Zeros of F(γ) on (0, π), only searched when a lower bound of F can be negative: sign changes on
// a uniform grid of 512 cells, each refined by bisection to the last bit. A pair of zeros within
// one cell (0.35°) is missed; with |F''| ≲ 2e3 on the table's range that needs min F within
// ~1e-2 of 0, and the negative sliver then missed is narrower than the cell.
void indicatrix_zeros(const PerezSkyCoefficients& k, std::vector<double>& out) {
  const double c_low = k.c >= 0 ? 0.0 : k.c * std::max(1.0, std::exp(k.d * kPi));
  const double bound = 1 + c_low + std::min(0.0, k.e);
  if (bound >= 0) return;
  constexpr int kCells = 512;
  double g0 = 0, f0 = indicatrix_raw(0, k);
  for (int i = 1; i <= kCells; ++i) {
    const double g1 = kPi * i / kCells;
    const double f1 = indicatrix_raw(g1, k);
    if ((f0 < 0) != (f1 < 0)) {
      double lo = g0, hi = g1;
      const bool lo_neg = f0 < 0;
      for (int it = 0; it < 200 && hi - lo > 0; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        if ((indicatrix_raw(mid, k) < 0) == lo_neg)
          lo = mid;
        else
          hi = mid;
      }
      out.push_back(0.5 * (lo + hi));
    }
    g0 = g1;
    f0 = f1;
  }
}

}  // namespace

double relative_air_mass_kasten_young(double zenith_rad) {
  if (!std::isfinite(zenith_rad)) throw InputError("Perez sky: sun zenith " + fmt(zenith_rad) + " is not finite");
  const double z = std::clamp(zenith_rad, 0.0, kHalfPi);
  return 1.0 / (std::cos(z) + 0.50572 * std::pow(96.07995 - z / kDeg, -1.6364));
}

double extraterrestrial_normal_irradiance_W_m2(int day_of_year, double solar_constant_W_m2) {
  if (day_of_year < 1 || day_of_year > 366)
    throw InputError("Perez sky: day of year " + std::to_string(day_of_year) + " is not in 1..366");
  if (!(solar_constant_W_m2 > 0) || !std::isfinite(solar_constant_W_m2))
    throw InputError("Perez sky: solar constant " + fmt(solar_constant_W_m2) + " W/m2 must be positive");
  const double g = 2 * kPi * (day_of_year - 1) / 365.0;
  const double e0 =
      1.000110 + 0.034221 * std::cos(g) + 0.001280 * std::sin(g) + 0.000719 * std::cos(2 * g) + 0.000077 * std::sin(2 * g);
  return solar_constant_W_m2 * e0;
}

double perez_sky_clearness(double dhi_W_m2, double dni_W_m2, double zenith_rad) {
  if (dhi_W_m2 == 0) return std::numeric_limits<double>::infinity();
  const double kz3 = kPerezKappa * zenith_rad * zenith_rad * zenith_rad;
  return ((dhi_W_m2 + dni_W_m2) / dhi_W_m2 + kz3) / (1 + kz3);
}

double perez_sky_brightness(double dhi_W_m2, double air_mass, double extraterrestrial_W_m2) {
  return dhi_W_m2 * air_mass / extraterrestrial_W_m2;
}

int perez_clearness_bin(double clearness) {
  if (std::isnan(clearness)) throw InputError("Perez sky: clearness is NaN");
  int bin = 0;
  for (int i = 1; i < kPerezBinCount; ++i)
    if (clearness >= kPerezClearnessLowerEdges[i]) bin = i;
  return bin;
}

PerezSkyCondition perez_sky_condition(double dhi_W_m2, double dni_W_m2, double sun_zenith_rad, double air_mass,
                                      double extraterrestrial_W_m2) {
  require_finite_nonnegative(dhi_W_m2, "diffuse horizontal irradiance (W/m2)");
  require_finite_nonnegative(dni_W_m2, "direct normal irradiance (W/m2)");
  if (!std::isfinite(sun_zenith_rad) || sun_zenith_rad < 0 || sun_zenith_rad > kPi)
    throw InputError("Perez sky: sun zenith " + fmt(sun_zenith_rad) + " rad is not in [0, pi]");
  if (!std::isfinite(air_mass) || !(air_mass > 0)) throw InputError("Perez sky: air mass " + fmt(air_mass) + " must be positive");
  if (!std::isfinite(extraterrestrial_W_m2) || !(extraterrestrial_W_m2 > 0))
    throw InputError("Perez sky: extraterrestrial irradiance " + fmt(extraterrestrial_W_m2) + " W/m2 must be positive");
  PerezSkyCondition c;
  c.dhi_W_m2 = dhi_W_m2;
  c.dni_W_m2 = dni_W_m2;
  c.sun_zenith_rad = sun_zenith_rad;
  c.model_zenith_rad = std::min(sun_zenith_rad, kHalfPi);
  c.clearness = perez_sky_clearness(dhi_W_m2, dni_W_m2, c.model_zenith_rad);
  c.brightness_unclamped = perez_sky_brightness(dhi_W_m2, air_mass, extraterrestrial_W_m2);
  c.brightness = std::clamp(c.brightness_unclamped, kPerezMinBrightness, kPerezMaxBrightness);
  c.bin = perez_clearness_bin(c.clearness);
  return c;
}

PerezSkyCondition perez_sky_condition(double dhi_W_m2, double dni_W_m2, double sun_zenith_rad, int day_of_year) {
  return perez_sky_condition(dhi_W_m2, dni_W_m2, sun_zenith_rad, relative_air_mass_kasten_young(sun_zenith_rad),
                             extraterrestrial_normal_irradiance_W_m2(day_of_year));
}

PerezSkyCoefficients perez_sky_coefficients_raw(int bin, double brightness, double zenith_rad) {
  if (bin < 0 || bin >= kPerezBinCount) throw InputError("Perez sky: clearness bin " + std::to_string(bin) + " is not in 0..7");
  const auto& t = kPerezTable[bin];
  const double D = brightness, Z = zenith_rad;
  const auto lin = [&](int i) { return t[i][0] + t[i][1] * Z + D * (t[i][2] + t[i][3] * Z); };
  PerezSkyCoefficients k;
  k.a = lin(0);
  k.b = lin(1);
  k.e = lin(4);
  if (bin == 0) {
    k.c = std::exp(std::pow(D * (t[2][0] + t[2][1] * Z), t[2][2])) - t[2][3];  // eq. 7
    k.d = -std::exp(D * (t[3][0] + t[3][1] * Z)) + t[3][2] + D * t[3][3];      // eq. 8
  } else {
    k.c = lin(2);
    k.d = lin(3);
  }
  return k;
}

PerezSkyCoefficients perez_sky_coefficients(const PerezSkyCondition& condition) {
  double D = condition.brightness;
  if (condition.bin >= 1 && condition.bin <= 4) D = std::max(D, kPerezMinBrightnessBins2to5);
  PerezSkyCoefficients k = perez_sky_coefficients_raw(condition.bin, D, condition.model_zenith_rad);
  k.b = std::min(k.b, 0.0);
  return k;
}

double perez_gradation(double cos_theta, double a, double b) {
  if (!(cos_theta > 0)) return b < 0 ? 1.0 : std::max(0.0, 1.0 + a);  // limits as cos θ → 0⁺
  return std::max(0.0, 1.0 + a * std::exp(b / cos_theta));
}

double perez_indicatrix(double gamma_rad, double c, double d, double e) {
  const double cg = std::cos(gamma_rad);
  return std::max(0.0, 1.0 + c * std::exp(d * gamma_rad) + e * cg * cg);
}

double perez_relative_luminance(const PerezSkyCoefficients& k, double cos_theta, double gamma_rad) {
  if (!(cos_theta > 0)) return 0.0;
  return perez_gradation(cos_theta, k.a, k.b) * perez_indicatrix(gamma_rad, k.c, k.d, k.e);
}

double perez_horizontal_integral(const PerezSkyCoefficients& k, const Vec3& sun_dir, int nodes) {
  if (nodes < 4 || nodes > kMaxNodes) throw InputError("Perez sky: quadrature nodes " + std::to_string(nodes) + " not in 4..128");
  if (!(k.b <= 0)) throw InputError("Perez sky: coefficient b " + fmt(k.b) + " must be <= 0 for a finite sky integral");
  if (!sun_dir.allFinite()) throw InputError("Perez sky: sun direction is not finite");
  const double cz = std::clamp(sun_dir.z(), -1.0, 1.0);
  const double sz = std::min(1.0, std::hypot(sun_dir.x(), sun_dir.y()));
  const double zs = std::atan2(sz, cz);

  // Region where G ≥ 0: all μ unless a < −1, then μ ≤ mu_cap (G decreases with μ for a < 0).
  double mu_cap = 2.0;
  if (k.a < -1) {
    if (!(k.b < 0)) return 0.0;  // G = 1 + a < 0 everywhere
    mu_cap = -k.b / std::log(-k.a);
  }

  std::vector<double> breaks = {0.0, kPi};
  breaks.reserve(32);
  tangencies(zs, kHalfPi, breaks);
  const double t_lo = breaks[2], t_hi = breaks[3];
  // exp(b/μ) switches on within μ ~ |b| of the horizon, so near a horizon tangency J(γ) varies
  // on the scale |b| (C∞ but not analytic where the circles cross the horizon): pieces at
  // distances |b|, |b|/4, |b|/16 on both sides of each tangency, as for the arcs.
  const double s_layer = (k.a != 0 && k.b < 0) ? -k.b : 0.0;
  if (s_layer > 0)
    for (double t : {t_lo, t_hi})
      for (double f : {1.0, 0.25, 0.0625})
        for (double g : {t - f * s_layer, t + f * s_layer})
          if (g > 0 && g < kPi) breaks.push_back(g);
  if (mu_cap < 1) tangencies(zs, std::acos(mu_cap), breaks);
  indicatrix_zeros(k, breaks);
  std::sort(breaks.begin(), breaks.end());

  const int n_graded = std::max(4, nodes / 2);
  const ArcRule arc = arc_rule(std::max(4, nodes / 2), std::max(4, (5 * nodes) / 12), std::max(4, nodes / 3));
  const ArcRule probe = arc_rule(4, 4, 4);
  double total = 0;
  for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
    const double g0 = breaks[p], g1 = breaks[p + 1];
    if (!(g1 > g0)) continue;
    const double gm = 0.5 * (g0 + g1);
    if (indicatrix_raw(gm, k) <= 0) continue;                            // F clamped to 0 here
    if (circle_integral(k, cz, sz, mu_cap, gm, probe) == 0.0) continue;  // circles wholly outside the sky
    const bool graded = s_layer > 0 && (std::abs(gm - t_lo) < s_layer || std::abs(gm - t_hi) < s_layer);
    const int n = graded ? n_graded : nodes;
    const GaussRule& outer = gauss_rule(n);
    // γ = g0 + (g1 − g0)(1 − cos t)/2, t ∈ [0, π]: removes the square-root behaviour of J at
    // a tangency at either end.
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      const double t = kPi * outer.x[i];
      const double gamma = g0 + (g1 - g0) * 0.5 * (1 - std::cos(t));
      const double jac = (g1 - g0) * 0.5 * std::sin(t) * kPi;
      const double f = std::max(0.0, indicatrix_raw(gamma, k));
      sum += outer.w[i] * jac * f * std::sin(gamma) * circle_integral(k, cz, sz, mu_cap, gamma, arc);
    }
    total += sum;
  }
  return total;
}

double PerezSky::radiance(const Vec3& dir) const {
  const double cz = dir.z();
  if (!(cz > 0) || scale == 0) return 0.0;
  const double gamma = std::atan2(dir.cross(sun_dir).norm(), dir.dot(sun_dir));
  return scale * perez_relative_luminance(coefficients, cz, gamma);
}

PerezSky make_perez_sky(const PerezSkyCondition& condition, const Vec3& sun_dir, double horizontal_diffuse, int nodes) {
  if (!sun_dir.allFinite() || std::abs(sun_dir.norm() - 1.0) > 1e-9)
    throw InputError("Perez sky: sun direction is not a unit vector");
  require_finite_nonnegative(horizontal_diffuse, "horizontal diffuse quantity");
  PerezSky sky;
  sky.sun_dir = sun_dir;
  sky.condition = condition;
  if (!condition.has_sky() || horizontal_diffuse == 0) return sky;
  sky.coefficients = perez_sky_coefficients(condition);
  double integral = perez_horizontal_integral(sky.coefficients, sun_dir, nodes);
  if (!(integral > 0)) {  // the clamped sky vanished everywhere: uniform sky (gendaymtx)
    sky.coefficients = PerezSkyCoefficients{};
    integral = kPi;
  }
  sky.scale = horizontal_diffuse / integral;
  return sky;
}

}  // namespace skyband
