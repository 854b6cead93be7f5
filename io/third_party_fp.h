#pragma once
// Calls into third-party numeric libraries (PROJ, GDAL) may raise floating-point exception flags
// inside their own code (a NaN compared on purpose, a division they check afterwards). skyband's
// test runner traps FE_INVALID and FE_DIVBYZERO (tests/fp_traps.cpp) to catch such operations in
// skyband's code; this guard runs a library call with the traps off and, on leaving, restores the
// caller's floating-point environment as it was (its traps and its flags), so that the library's
// flags neither trap nor leak into skyband's.
#include <cfenv>

namespace skyband {

class ThirdPartyFpGuard {
 public:
  ThirdPartyFpGuard() { std::feholdexcept(&saved_); }  // saves, clears the flags, traps off
  ~ThirdPartyFpGuard() { std::fesetenv(&saved_); }
  ThirdPartyFpGuard(const ThirdPartyFpGuard&) = delete;
  ThirdPartyFpGuard& operator=(const ThirdPartyFpGuard&) = delete;

 private:
  std::fenv_t saved_;
};

}  // namespace skyband
