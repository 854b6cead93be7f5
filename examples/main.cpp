// skyband — exact band-source sky visibility and spectral sun + sky shading of outdoor scenes.
// Coordinates: metres, z up (x east, y north). Azimuths: degrees clockwise from north.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <iostream>

#include "examples/command_registry.h"
#include "geometry/input_error.h"

namespace skyband::cli {

std::vector<CommandEntry>& command_registry() {
  static std::vector<CommandEntry> entries;
  return entries;
}

static std::string g_invocation;
const std::string& invocation() { return g_invocation; }

}  // namespace skyband::cli

int main(int argc, char** argv) {
  using namespace skyband;
  for (int i = 0; i < argc; ++i) {
    if (i) cli::g_invocation += ' ';
    cli::g_invocation += argv[i];
  }
  CLI::App app{
      "skyband " SKYBAND_VERSION " — exact sky visibility and spectral sun + sky shading of outdoor scenes.\n"
      "Units: metres, z up (x east, y north); azimuths clockwise from north; radiance W·m⁻²·sr⁻¹."};
  app.set_version_flag("--version", std::string("skyband ") + SKYBAND_VERSION);
  app.require_subcommand(1);
  auto& entries = cli::command_registry();
  std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  for (auto& e : entries) e.setup(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help/--version exit 0; every malformed command line is an input error: exit code 2.
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const InputError& e) {
    std::fprintf(stderr, "skyband: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "skyband: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
