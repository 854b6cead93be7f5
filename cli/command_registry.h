#pragma once
// Each subcommand lives in its own examples/cmd_<name>.cpp and registers itself here with a
// static CommandRegistration, so adding a command touches no other file.
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace skyband::cli {

// setup(app) adds the subcommand to `app` and returns it; the subcommand's callback does the
// work. Errors: throw skyband::InputError (printed as one line, exit code 2).
using CommandSetup = std::function<CLI::App*(CLI::App& app)>;

struct CommandEntry {
  std::string name;
  CommandSetup setup;
};

std::vector<CommandEntry>& command_registry();

struct CommandRegistration {
  CommandRegistration(std::string name, CommandSetup setup) { command_registry().push_back({std::move(name), std::move(setup)}); }
};

// The command line as typed (for provenance in output headers).
const std::string& invocation();

// After a command-line parse error: " (did you mean --points?)" for a flag or command within a
// few edits of a known one, else "; see skyband <command> --help".
std::string did_you_mean(CLI::App& app, int argc, char** argv);

}  // namespace skyband::cli
