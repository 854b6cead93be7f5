#include "io/atomic_file.h"

#include <unistd.h>
#include <atomic>
#include <system_error>

#include "geometry/core/input_error.h"
#include "io/interrupted_output.h"

namespace skyband {

void write_atomically(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write) {
  namespace fs = std::filesystem;
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError("cannot write '" + path.string() + "': folder '" + dir.string() + "' does not exist");
  static std::atomic<unsigned> counter{0};
  // Built with += : GCC 12 warns falsely (-Wrestrict) on "." + std::string&& here.
  std::string name = ".";
  name += path.filename().string();
  name += ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const fs::path temp = dir / name;
  const TemporaryOutput removed_on_interrupt(temp);
  try {
    write(temp);
  } catch (...) {
    fs::remove(temp, ec);
    throw;
  }
  fs::rename(temp, path, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw InputError("cannot write '" + path.string() + "': " + ec.message());
  }
}

}  // namespace skyband
