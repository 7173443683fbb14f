// Subcommands of `amha` register themselves here, so each lives in its own file.
#pragma once

#include <vector>

namespace amha {
namespace cli {

/// A subcommand's entry point. argv[0] is "amha <name>", the rest are its own arguments.
using CommandFn = int (*)(int argc, char** argv);

struct Command {
  const char* name;
  const char* summary;
  CommandFn run;
};

std::vector<Command>& commandRegistry();

struct CommandRegistrar {
  CommandRegistrar(const char* name, const char* summary, CommandFn run) {
    commandRegistry().push_back(Command{name, summary, run});
  }
};

}  // namespace cli
}  // namespace amha

/// Registers `fn` as `amha <name>`; use once at namespace scope in the command's source file.
#define AMHA_REGISTER_COMMAND(name, summary, fn) \
  static const ::amha::cli::CommandRegistrar amha_command_registrar_##fn(name, summary, fn)
