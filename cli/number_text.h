#pragma once
// A double as the shortest text that reads back to the same value (std::to_chars): 0.1, 1e+300,
// -0.05. For CSV cells and for echoing a flag's value in a message (std::to_string would print
// 1e300 with 300 digits and 1e-7 as 0.000000).
#include <charconv>
#include <string>

namespace skyband::cli {

inline std::string shortest_text(double v) {
  char b[32];
  const auto [end, ec] = std::to_chars(b, b + sizeof b, v);
  return ec == std::errc() ? std::string(b, end) : std::string("?");
}

}  // namespace skyband::cli
