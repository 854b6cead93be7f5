#pragma once
// User-input errors are values, not crashes: library code throws InputError with a message that
// names the file, line/element/field and the offending value; the CLI prints it on one line and
// exits non-zero. Library code never calls exit() or abort().
#include <stdexcept>
#include <string>

namespace skyband {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace skyband
