// Fuzz harness for read_epw (io/epw_reader.h): the input is a whole EPW weather file.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.h"
#include "io/epw_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path path = skyband::fuzz::temp_path("weather", ".epw");
  skyband::fuzz::write_input(path, data, size);
  skyband::fuzz::expect_input_errors_only("read_epw", [&] { (void)skyband::read_epw(path); });
  return 0;
}
