// Fuzz harness for parse_scene (io/scene_file.h): the input is the text of a scene file. It is
// parsed as if it were examples/scenes/fuzz.toml, so that `meshes = ["default_scene.obj"]`
// names a file that exists (mesh paths are checked, not read).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz/fuzz_support.h"
#include "io/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path name = std::filesystem::path(SKYBAND_FUZZ_SCENE_DIR) / "fuzz.toml";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  skyband::fuzz::expect_input_errors_only("parse_scene", [&] { (void)skyband::parse_scene(text, name); });
  return 0;
}
