// `amha <command> [args]`: the project's command line; each command registers itself.
#include <algorithm>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>

#include "command_registry.h"
#include "exit_codes.h"

namespace amha {
namespace cli {
std::vector<Command>& commandRegistry() {
  static std::vector<Command> commands;
  return commands;
}
}  // namespace cli
}  // namespace amha

namespace {
void usage(std::ostream& out) {
  out << "usage: amha <command> [options]   (amha <command> --help for its options)\n\ncommands:\n";
  std::size_t width = 0;
  for (const auto& c : amha::cli::commandRegistry()) width = std::max(width, std::strlen(c.name));
  for (const auto& c : amha::cli::commandRegistry()) {
    out << "  " << c.name << std::string(width + 3 - std::strlen(c.name), ' ') << c.summary << "\n";
  }
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    usage(argc < 2 ? std::cerr : std::cout);
    return argc < 2 ? amha::cli::kExitUsage : amha::cli::kExitOk;
  }
  for (const auto& c : amha::cli::commandRegistry()) {
    if (argv[1] == std::string(c.name)) {
      std::string name = std::string("amha ") + c.name;
      argv[1] = name.data();
      try {
        return c.run(argc - 1, argv + 1);
      } catch (const std::exception& e) {
        std::cerr << "amha " << c.name << ": internal error: " << e.what() << "\n";
        return amha::cli::kExitInternal;
      }
    }
  }
  std::cerr << "amha: unknown command '" << argv[1] << "'\n";
  usage(std::cerr);
  return amha::cli::kExitUsage;
}
