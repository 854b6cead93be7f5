// Floating-point traps for test runs (style.md, libigl): with SKYBAND_FP_TRAPS=1 in the
// environment every test executable enables the FE_INVALID and FE_DIVBYZERO traps before its
// first test case (SKYBAND_FP_TRAPS=invalid or =divbyzero: that one alone, to look past a known
// trap of the other kind), so a NaN or an infinity born of 0/0, ∞−∞, sqrt(−1) or x/0 raises SIGFPE where
// it is born instead of surfacing as a wrong number far away. Overflow, underflow and inexact
// stay untrapped: they are normal in the exact-arithmetic filters (CGAL's interval arithmetic
// overflows to ∞ on purpose) and in exp() of large negative arguments.
//
// Why not Boost.Test's own --detect_fp_exceptions: in Boost 1.74 it passes a bool as the trap
// mask (so only FE_INVALID, bit 0, is trapped, never FE_DIVBYZERO) and installs its own SIGFPE
// handler, which reports "floating point error" without a stack. And Boost.Test clears every
// trap around each test unit (execution_monitor.ipp, fpe_except_guard: fedisableexcept(FE_ALL)
// before, restore after), so traps set in a global fixture would be off inside the tests. Hence
// the fedisableexcept below: while traps are requested it passes every call on to the C
// library's function except for the two trapped exceptions, which stay enabled. (The executable's
// definition takes precedence over libm's for Boost's shared library too: ELF interposition.)
//
// Caveat: an ordered comparison (<, <=, >, >=) with a quiet NaN also raises FE_INVALID on
// x86-64 (comisd), so with traps on, code that tests a value that may be NaN must use
// std::isnan/std::isfinite (which do not raise) before comparing it.
//
// Worker threads inherit the trap mask of the thread that creates them (Linux copies the FP
// control state on clone; oneTBB's workers are created from inside a test body, and its arenas
// propagate the creating thread's FP settings to their tasks). Child processes (the CLI tests
// run the skyband executable) are not covered: the CLI does not read SKYBAND_FP_TRAPS.
//
// Linked into every test executable (tests/CMakeLists.txt); without the variable it does
// nothing. scripts/test-sanitized.sh sets it, together with Boost.Test's
// --catch_system_errors=no so that AddressSanitizer's SIGFPE handler prints the stack of the trap.
#include <boost/test/unit_test.hpp>

#include <atomic>
#include <cfenv>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <dlfcn.h>

namespace {

// The exceptions whose traps fedisableexcept must leave on (0 until the fixture has run).
std::atomic<int> g_kept_traps{0};

struct FpTraps {
  FpTraps() {
    const char* v = std::getenv("SKYBAND_FP_TRAPS");
    if (v == nullptr || *v == '\0' || std::strcmp(v, "0") == 0) return;
    int traps = 0;
    const char* names = "";
    if (std::strcmp(v, "1") == 0)
      traps = FE_INVALID | FE_DIVBYZERO, names = "FE_INVALID and FE_DIVBYZERO";
    else if (std::strcmp(v, "invalid") == 0)
      traps = FE_INVALID, names = "FE_INVALID";
    else if (std::strcmp(v, "divbyzero") == 0)
      traps = FE_DIVBYZERO, names = "FE_DIVBYZERO";
    if (traps == 0) {
      std::fprintf(stderr, "SKYBAND_FP_TRAPS=%s: unknown value (1, invalid, divbyzero or 0); traps are off\n", v);
      std::abort();
    }
    std::feclearexcept(FE_ALL_EXCEPT);
    if (feenableexcept(traps) == -1) {
      std::fprintf(stderr, "SKYBAND_FP_TRAPS=%s: feenableexcept failed; floating-point traps are off\n", v);
      std::abort();
    }
    g_kept_traps = traps;
    std::fprintf(stderr, "SKYBAND_FP_TRAPS=%s: trapping %s\n", v, names);
  }
};

}  // namespace

BOOST_TEST_GLOBAL_FIXTURE(FpTraps);

// glibc's fedisableexcept (<fenv.h>, a GNU extension) with the kept traps masked out of
// `excepts`; returns the previously enabled exceptions as the original does.
extern "C" int fedisableexcept(int excepts) {
  using Fn = int (*)(int);
  static const Fn libc_fedisableexcept = reinterpret_cast<Fn>(dlsym(RTLD_NEXT, "fedisableexcept"));
  if (libc_fedisableexcept == nullptr) return -1;
  return libc_fedisableexcept(excepts & ~g_kept_traps.load());
}
