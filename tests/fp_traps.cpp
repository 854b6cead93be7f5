// Floating-point traps for test runs (style.md, libigl): with SKYBAND_FP_TRAPS=1 in the
// environment every test executable enables the FE_INVALID and FE_DIVBYZERO traps before its
// first test case, so a NaN or an infinity born of 0/0, ∞−∞, sqrt(−1) or x/0 raises SIGFPE where
// it is born instead of surfacing as a wrong number far away. Overflow, underflow and inexact
// stay untrapped: they are normal in the exact-arithmetic filters (CGAL's interval arithmetic
// overflows to ∞ on purpose) and in exp() of large negative arguments.
//
// Caveat: an ordered comparison (<, <=, >, >=) with a quiet NaN also raises FE_INVALID on
// x86-64 (comisd), so with traps on, code that tests a value that may be NaN must use
// std::isnan/std::isfinite (which do not raise) before comparing it.
//
// Worker threads inherit the trap mask from the thread that creates them (Linux clones the FP
// environment; oneTBB also propagates the creating thread's FP settings to its tasks), so traps
// set here before the first parallel_for cover TBB workers too. Child processes (the CLI tests
// run the skyband executable) are not covered: the CLI does not read SKYBAND_FP_TRAPS.
//
// Compiled into every test executable (tests/CMakeLists.txt); without the variable it does
// nothing. scripts/test-sanitized.sh sets it, together with Boost.Test's
// --catch_system_errors=no so that AddressSanitizer's SIGFPE handler prints the stack of the trap.
#include <boost/test/unit_test.hpp>

#include <cfenv>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

struct FpTraps {
  FpTraps() {
    const char* v = std::getenv("SKYBAND_FP_TRAPS");
    if (v == nullptr || std::strcmp(v, "1") != 0) return;
    std::feclearexcept(FE_ALL_EXCEPT);
    if (feenableexcept(FE_INVALID | FE_DIVBYZERO) == -1) {
      std::fprintf(stderr, "SKYBAND_FP_TRAPS=1: feenableexcept failed; floating-point traps are off\n");
      return;
    }
    std::fprintf(stderr, "SKYBAND_FP_TRAPS=1: trapping FE_INVALID and FE_DIVBYZERO\n");
  }
};

}  // namespace

BOOST_TEST_GLOBAL_FIXTURE(FpTraps);
