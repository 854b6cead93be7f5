// Fuzz harness for read_csv_table (io/csv_table.h): the input is a whole CSV file. Every cell is
// also read as a number and every header name looked up, as the points and times readers do.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.h"
#include "io/csv_table.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path path = skyband::fuzz::temp_path("table", ".csv");
  skyband::fuzz::write_input(path, data, size);
  skyband::fuzz::expect_input_errors_only("read_csv_table", [&] {
    const skyband::CsvTable t = skyband::read_csv_table(path, "fuzz table");
    for (const std::string& name : t.header)
      skyband::fuzz::expect_input_errors_only("CsvTable::column", [&] { (void)t.column(skyband::trim_csv_cell(name)); });
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      (void)t.where(r);
      for (std::size_t c = 0; c < t.rows[r].size(); ++c)
        skyband::fuzz::expect_input_errors_only("CsvTable::number", [&] { (void)t.number(r, static_cast<int>(c)); });
    }
  });
  return 0;
}
