#pragma once
// The message of the InputError that f() throws, "" when it throws none: for tests of what bad
// input says.
#include <string>

#include "geometry/core/input_error.h"

namespace skyband::test {

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace skyband::test
