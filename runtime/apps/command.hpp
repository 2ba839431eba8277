// Subcommand registry of the `sgnlf` app. Each cmd_<name>.cpp defines a static Registrar that
// adds its subcommand to the CLI11 app; the callback returns the process exit code.
#pragma once
#include <CLI/CLI.hpp>

#include <functional>
#include <vector>

namespace sgnlf::app {

// Sets up options on `sub` and returns the function run when the subcommand is chosen.
using CommandSetup = std::function<std::function<int()>(CLI::App& sub)>;

struct CommandDef {
  const char* name;
  const char* help;
  CommandSetup setup;
};

std::vector<CommandDef>& registry();

struct Registrar {
  Registrar(const char* name, const char* help, CommandSetup setup) {
    registry().push_back({name, help, std::move(setup)});
  }
};

}  // namespace sgnlf::app
