// Fuzz harness for the `--set key=value` overrides of parse_scene (io/scene_file.h): the whole
// input is one override string (no trailing newline is stripped), applied to the valid scene
// examples/scenes/default.toml.
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>

#include "fuzz/fuzz_support.h"
#include "io/scene_file.h"

namespace {

const std::filesystem::path kScene = std::filesystem::path(SKYBAND_FUZZ_SCENE_DIR) / "default.toml";

std::string base_text() {
  std::ifstream in(kScene, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) skyband::fuzz::finding("cannot read " + kScene.string());
  return text;
}

}  // namespace

// The base scene must itself parse, else every override would only meet its InputError.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  try {
    (void)skyband::parse_scene(base_text(), kScene);
  } catch (const std::exception& e) {
    skyband::fuzz::finding("the base scene " + kScene.string() + " does not parse: " + e.what());
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string base = base_text();
  const std::string overrides[] = {std::string(reinterpret_cast<const char*>(data), size)};
  skyband::fuzz::expect_input_errors_only("parse_scene --set", [&] { (void)skyband::parse_scene(base, kScene, overrides); });
  return 0;
}
