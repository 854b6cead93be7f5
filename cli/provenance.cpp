#include "cli/provenance.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "cli/command_registry.h"
#include "geometry/core/input_error.h"
#include "io/atomic_file.h"

namespace skyband::cli {

namespace {

// "2026-12-02T01:23:45Z" for a system-clock time.
std::string iso_utc(std::chrono::system_clock::time_point t) {
  const std::time_t s = std::chrono::system_clock::to_time_t(t);
  std::tm tm{};
  gmtime_r(&s, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace

void write_provenance(const std::string& output, const std::vector<std::pair<std::string, std::string>>& inputs) {
  namespace fs = std::filesystem;
  nlohmann::json j;
  j["output"] = output;
  j["skyband_version"] = SKYBAND_VERSION;
  j["command_line"] = invocation();
  std::error_code ec;
  j["working_folder"] = fs::current_path(ec).string();
  j["written_utc"] = iso_utc(std::chrono::system_clock::now());
  nlohmann::json files = nlohmann::json::array();
  for (const auto& [flag, path] : inputs) {
    if (path.empty()) continue;
    nlohmann::json f{{"flag", flag}, {"path", path}};
    std::error_code e1, e2;
    const auto size = fs::file_size(path, e1);
    const auto mtime = fs::last_write_time(path, e2);
    if (!e1) f["bytes"] = size;
    if (!e2)
      f["modified_utc"] =
          iso_utc(std::chrono::time_point_cast<std::chrono::system_clock::duration>(std::chrono::file_clock::to_sys(mtime)));
    files.push_back(std::move(f));
  }
  j["inputs"] = std::move(files);
  const std::string file = output + ".provenance.json";
  write_atomically(file, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
    if (!out.flush()) throw InputError("cannot write '" + file + "'");
  });
}

}  // namespace skyband::cli
