// skyband — exact band-source sky visibility and spectral sun + sky shading of outdoor scenes.
// Coordinates: metres, z up (x east, y north). Azimuths: degrees clockwise from north.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <iostream>
#include <new>

#include "examples/command_registry.h"
#include "geometry/input_error.h"
#include "io/utf8_text.h"

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
    // One line whatever the message quotes: control characters (a line break inside a quoted
    // CSV cell, a terminal escape) are printed escaped (io/utf8_text.h).
    std::fprintf(stderr, "skyband: error: %s\n", printable_text(e.what()).c_str());
    return 2;
  } catch (const std::bad_alloc&) {
    // Never a silent success, never "internal error": the readers bound every count by the
    // file's size, so what is left is an input (or a job) too large for this machine's memory.
    std::fprintf(stderr, "skyband: error: out of memory (std::bad_alloc): the input is too large for this machine\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "skyband: internal error: %s\n", printable_text(e.what()).c_str());
    return 3;
  }
  return 0;
}
