#pragma once
// Output files are written atomically: to a temporary file beside the target, then renamed over
// it, so that an error or a crash never leaves a half-written output.
#include <filesystem>
#include <functional>
#include <string>

namespace skyband {

// Calls write(temp_path) and renames temp_path to `path` if it returns without throwing; on an
// exception the temporary file is removed and the exception propagates. Throws InputError when
// the target's folder does not exist or the rename fails.
void write_atomically(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write);

}  // namespace skyband
