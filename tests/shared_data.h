// The shared test data (real city models, weather files, spectra, reference tables, the
// degeneracy and fuzz-found corpora) lives outside the repository, in SKYBAND_SHARED_DATA
// (the CMake cache variable SKYBAND_SHARED_DIR, default ../shared beside the checkout, plus /data).
// A test case that reads it carries the decorator
//
//   BOOST_AUTO_TEST_CASE(name, *skyband::test::needs_shared_data())
//
// so that a clone without the data skips it with a message naming the missing folder and runs
// everything else. Only a missing *folder* skips: where the folder exists (as in CI) every such
// test runs, and a file missing from it fails the test that needs it.
#pragma once

#include <filesystem>
#include <iostream>
#include <string>

#include <boost/test/unit_test.hpp>

namespace skyband::test {

// GCC 12 reports boost::function's copy of the lambda's buffer (function_template.hpp:910) as
// -Wuninitialized once inlined here; the bytes it copies past the empty lambda are never read.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"  // a GCC-only group
#endif
inline boost::unit_test::precondition needs_shared_data() {
  return boost::unit_test::precondition([](boost::unit_test::test_unit_id id) {
    const std::filesystem::path dir(SKYBAND_SHARED_DATA);
    std::error_code ec;
    boost::test_tools::assertion_result present(std::filesystem::is_directory(dir, ec));
    if (!present) {
      const std::string why = "the shared test data folder " + dir.string() +
                              " is missing (the CMake variable SKYBAND_SHARED_DIR names the folder "
                              "holding data/)";
      present.message() << why;
      // Boost.Test logs skips only at --log_level=test_suite; say it on stderr as well.
      std::cerr << boost::unit_test::framework::get(id, boost::unit_test::TUT_ANY).p_name.get() << ": skipped: " << why << '\n';
    }
    return present;
  });
}
#pragma GCC diagnostic pop

}  // namespace skyband::test
