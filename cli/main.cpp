// skyband — exact band-source sky visibility and spectral sun + sky shading of outdoor scenes.
// Coordinates: metres, z up (x east, y north). Azimuths: degrees clockwise from north.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "cli/command_registry.h"
#include "geometry/core/input_error.h"
#include "io/interrupted_output.h"
#include "io/utf8_text.h"

namespace skyband::cli {

std::vector<CommandEntry>& command_registry() {
  static std::vector<CommandEntry> entries;
  return entries;
}

static std::string g_invocation;
const std::string& invocation() {
  return g_invocation;
}

namespace {

// Levenshtein distance (insertions, deletions, substitutions), for suggestions.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// The closest of `names` to `word` within a third of its length (at least 2, at most 3 edits).
std::string closest(const std::string& word, const std::vector<std::string>& names) {
  std::string best;
  std::size_t best_d = std::min<std::size_t>(3, std::max<std::size_t>(2, word.size() / 3)) + 1;
  for (const std::string& n : names) {
    const std::size_t d = edit_distance(word, n);
    if (d < best_d) best_d = d, best = n;
  }
  return best;
}

}  // namespace

std::string did_you_mean(CLI::App& app, int argc, char** argv) {
  // The deepest subcommand named on the command line, and its flags.
  CLI::App* cmd = &app;
  std::vector<std::string> words;
  for (int i = 1; i < argc; ++i) words.emplace_back(argv[i]);
  for (const std::string& w : words) {
    if (w.starts_with("-")) continue;
    CLI::App* sub = nullptr;
    for (CLI::App* s : cmd->get_subcommands([](CLI::App*) { return true; }))
      if (s->get_name() == w) sub = s;
    if (sub) cmd = sub;
  }
  std::vector<std::string> flags, commands;
  for (const CLI::Option* o : cmd->get_options())
    for (const std::string& n : o->get_lnames()) flags.push_back("--" + n);
  for (CLI::App* s : cmd->get_subcommands([](CLI::App*) { return true; })) commands.push_back(s->get_name());
  for (const std::string& w : words) {
    if (w.starts_with("--")) {
      const std::string flag = w.substr(0, w.find('='));
      if (std::find(flags.begin(), flags.end(), flag) != flags.end()) continue;
      const std::string c = closest(flag, flags);
      if (!c.empty()) return " (did you mean " + c + "?)";
    } else if (!w.starts_with("-") && !commands.empty() && cmd->get_subcommands().empty()) {
      const std::string c = closest(w, commands);
      if (!c.empty() && c != w) return " (did you mean '" + c + "'?)";
    }
  }
  const std::string path = cmd == &app ? "" : " " + cmd->get_name();
  return "; see skyband" + path + " --help";
}

}  // namespace skyband::cli

int main(int argc, char** argv) {
  using namespace skyband;
  remove_temporary_outputs_on_interrupt();
  for (int i = 0; i < argc; ++i) {
    if (i) cli::g_invocation += ' ';
    cli::g_invocation += argv[i];
  }
  CLI::App app{"skyband " SKYBAND_VERSION
               " — exact sky visibility and spectral sun + sky shading of outdoor scenes.\n"
               "Units: metres, z up (x east, y north); azimuths clockwise from north; radiance W·m⁻²·sr⁻¹."};
  app.set_version_flag("--version", std::string("skyband ") + SKYBAND_VERSION);
  app.require_subcommand(1);
  auto& entries = cli::command_registry();
  std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  for (auto& e : entries) e.setup(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help/--version exit 0; every malformed command line is an input error: one line in the
    // form of every other error, with a "did you mean" for a mistyped flag or command, exit 2.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    std::fprintf(stderr, "skyband: error: %s%s\n", printable_text(e.what()).c_str(),
                 printable_text(cli::did_you_mean(app, argc, argv)).c_str());
    return 2;
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
