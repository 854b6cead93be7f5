// Fuzz harness for read_mesh (io/mesh_reader.h): the input is a whole mesh file. Built once per
// format (fuzz/CMakeLists.txt: fuzz_mesh_obj, _off, _ply, _stl, _cityjson, _cityjsonseq);
// SKYBAND_FUZZ_MESH_EXT is the extension the temporary file gets, which is how read_mesh picks
// the format. Every pass runs: the validating reader (and OpenMesh for OBJ, PLY and STL), then
// triangulation and the defect report.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.h"
#include "io/mesh_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path path = skyband::fuzz::temp_path("mesh", SKYBAND_FUZZ_MESH_EXT);
  skyband::fuzz::write_input(path, data, size);
  skyband::fuzz::expect_input_errors_only("read_mesh", [&] {
    skyband::MeshReadReport report;
    const skyband::TriangleSoup soup = skyband::read_mesh(path, &report);
    (void)report.summary();
  });
  return 0;
}
