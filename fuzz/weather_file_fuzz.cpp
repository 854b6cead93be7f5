// Fuzz harness for read_weather_file (io/tmy3_reader.h): the input is a whole weather file, EPW
// or TMY3 CSV (told by content).
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.h"
#include "io/tmy3_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path path = skyband::fuzz::temp_path("weather", ".csv");
  skyband::fuzz::write_input(path, data, size);
  skyband::fuzz::expect_input_errors_only("read_weather_file", [&] { (void)skyband::read_weather_file(path); });
  return 0;
}
