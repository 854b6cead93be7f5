// HorizonEnvelope (geometry/horizon/horizon_envelope.h) against an independent brute force: the upper
// envelope of the inserted arcs evaluated directly (the largest tan(elevation) of the arcs whose
// azimuth range holds a direction, 0 for the horizon) at many azimuths. The exact-horizon tests
// (horizon_svf_test) check the whole method against the exact Lambert oracle; these pin the
// envelope itself: its runs are the brute-force maximum, they cover the turn, and range tests
// never call hidden what lies above the envelope.
#define BOOST_TEST_MODULE horizon_envelope
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "geometry/horizon/horizon_envelope.h"
#include "geometry/mesh/scene.h"

using namespace skyband;

namespace {

struct Arc {
  double a, b;    // tan e = a·w_x + b·w_y
  double t0, t1;  // diamond angles of its ends (the shorter way between them)
};

// Is t inside the shorter range between t0 and t1 (less than 2 apart, or through t = 0)?
bool covers(const Arc& arc, double t) {
  const double lo = std::min(arc.t0, arc.t1), hi = std::max(arc.t0, arc.t1);
  return hi - lo < 2 ? (lo <= t && t <= hi) : (t >= hi || t <= lo);
}

double brute_force(const std::vector<Arc>& arcs, double t) {
  double wx, wy;
  diamond_direction(t, wx, wy);
  double v = 0.0;  // the horizon
  for (const Arc& arc : arcs)
    if (covers(arc, t)) v = std::max(v, arc.a * wx + arc.b * wy);
  return v;
}

// Random edges above the point (at the origin) at 5–200 m, up to 60 m high, inserted as the
// envelope's caller does (geometry/horizon/horizon_svf.cpp): the great circle through the origin and the edge.
std::vector<Arc> insert_random_edges(HorizonEnvelope& env, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(0, 2 * kPi), dist(5, 200), height(0.5, 60), half_len(1, 40), turn(0, kPi);
  std::vector<Arc> arcs;
  for (int i = 0; i < n; ++i) {
    const double phi = angle(rng), d = dist(rng), h = height(rng), l = half_len(rng), dir = turn(rng);
    const Vec3 mid(d * std::cos(phi), d * std::sin(phi), h);
    const Vec3 along(l * std::cos(dir), l * std::sin(dir), 0.0);
    const Vec3 lo = mid - along, hi = mid + along;
    if (lo.head<2>().norm() < 1.0 || hi.head<2>().norm() < 1.0) continue;  // keep away from the point
    const Vec3 m = lo.cross(hi);
    if (!(std::abs(m.z()) > 1e-9)) continue;
    const Arc arc{-m.x() / m.z(), -m.y() / m.z(), diamond_angle(lo.x(), lo.y()), diamond_angle(hi.x(), hi.y())};
    if (std::abs(std::abs(arc.t1 - arc.t0) - 2) < 1e-9) continue;  // over the point
    const std::uint32_t c = env.add_circle(arc.a, arc.b);
    const double rl = 1 / lo.head<2>().norm(), rh = 1 / hi.head<2>().norm();
    env.insert_range(c, arc.t0, lo.x() * rl, lo.y() * rl, arc.t1, hi.x() * rh, hi.y() * rh);
    arcs.push_back(arc);
  }
  return arcs;
}

}  // namespace

BOOST_AUTO_TEST_CASE(runs_are_the_brute_force_maximum_and_cover_the_turn) {
  HorizonEnvelope env;
  for (unsigned seed : {1u, 2u, 3u}) {
    env.reset();
    const std::vector<Arc> arcs = insert_random_edges(env, 300, seed);
    BOOST_TEST(env.raised());
    // The runs tile [0, 4) in order.
    double expected_start = 0.0;
    std::vector<std::array<double, 3>> runs;  // t0, t1, circle
    env.for_each_run([&](double t0, double t1, std::uint32_t c) {
      BOOST_TEST(t0 == expected_start);
      BOOST_TEST(t1 > t0);
      expected_start = t1;
      runs.push_back({t0, t1, double(c)});
    });
    BOOST_TEST(expected_start == 4.0);
    BOOST_TEST(env.run_count() == runs.size());
    // At 20,000 azimuths the run's circle gives the brute-force maximum (to rounding).
    double worst = 0;
    std::size_t r = 0;
    for (int k = 0; k < 20000; ++k) {
      const double t = (k + 0.5) * 4.0 / 20000;
      while (runs[r][1] <= t) ++r;
      double wx, wy;
      diamond_direction(t, wx, wy);
      worst = std::max(worst, std::abs(env.value(std::uint32_t(runs[r][2]), wx, wy) - brute_force(arcs, t)));
    }
    BOOST_TEST(worst < 1e-12);
  }
}

BOOST_AUTO_TEST_CASE(hidden_below_is_conservative_and_decides_clear_cases) {
  HorizonEnvelope env;
  const std::vector<Arc> arcs = insert_random_edges(env, 200, 11);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 4), width(0, 0.3), scale(0.5, 1.5);
  int hidden = 0, not_hidden = 0;
  for (int k = 0; k < 5000; ++k) {
    const double lo = u(rng), hi = lo + width(rng);  // may pass t = 4: wraps
    // The brute-force minimum over the range, sampled finely (an upper estimate of the minimum).
    double sampled_min = 1e300;
    for (int s = 0; s <= 200; ++s) {
      const double t = lo + (hi - lo) * s / 200;
      sampled_min = std::min(sampled_min, brute_force(arcs, t >= 4 ? t - 4 : t));
    }
    const double bound = sampled_min * scale(rng);
    if (env.hidden_below(lo, hi, bound)) {
      ++hidden;
      BOOST_TEST(bound <= sampled_min * (1 + 1e-12) + 1e-15);  // never hides what rises above
    } else {
      ++not_hidden;
    }
    BOOST_TEST(env.hidden_below(lo, hi, 0.0));  // everything sinks below the horizon
    BOOST_TEST(!env.hidden_below(lo, hi, sampled_min * 1.001 + 1e-9));
  }
  BOOST_TEST(hidden > 1000);
  BOOST_TEST(not_hidden > 1000);
}

BOOST_AUTO_TEST_CASE(blocked_half_turn_and_reset) {
  HorizonEnvelope env;
  // A vertical face looking along +x: no sky behind it, from +y through −x to −y.
  env.insert_half_turn(HorizonEnvelope::kBlocked, 1.0, 2.0, 3.0);
  BOOST_TEST(env.raised());
  BOOST_TEST(env.hidden_below(1.0, 2.999, 1e300));  // behind the face: everything hidden (t = 3 is the
                                                    // horizon again: a piece holds its start, not its end)
  BOOST_TEST(!env.hidden_below(3.5, 4.5, 1e-6));    // in front: the open horizon
  std::vector<std::array<double, 3>> runs;
  env.for_each_run([&](double t0, double t1, std::uint32_t c) { runs.push_back({t0, t1, double(c)}); });
  BOOST_TEST(runs.size() == 3u);
  BOOST_TEST(runs[1][0] == 1.0);
  BOOST_TEST(runs[1][1] == 3.0);
  BOOST_TEST(runs[1][2] == double(HorizonEnvelope::kBlocked));
  env.reset();
  BOOST_TEST(!env.raised());
  BOOST_TEST(env.run_count() == 1u);
  BOOST_TEST(!env.hidden_below(1.0, 3.0, 1e-6));
}
