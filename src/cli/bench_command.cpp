// `amha bench <what> [options]`: dispatches to the registered benchmarks.
#include "bench_command.h"

#include <cstring>
#include <iostream>
#include <string>

#include "command_registry.h"
#include "exit_codes.h"

namespace amha {
namespace cli {

std::vector<Benchmark>& benchmarkRegistry() {
  static std::vector<Benchmark> benchmarks;
  return benchmarks;
}

namespace {

void usage(std::ostream& out) {
  out << "usage: amha bench <benchmark> [options]   (amha bench <benchmark> --help)\n\nbenchmarks:\n";
  for (const auto& b : benchmarkRegistry()) out << "  " << b.name << "  " << b.summary << "\n";
}

int benchMain(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    usage(argc < 2 ? std::cerr : std::cout);
    return argc < 2 ? kExitUsage : kExitOk;
  }
  for (const auto& b : benchmarkRegistry()) {
    if (argv[1] == std::string(b.name)) {
      std::string name = std::string("amha bench ") + b.name;
      argv[1] = name.data();
      return b.run(argc - 1, argv + 1);
    }
  }
  std::cerr << "amha bench: unknown benchmark '" << argv[1] << "'\n";
  usage(std::cerr);
  return kExitUsage;
}

}  // namespace

AMHA_REGISTER_COMMAND("bench", "run a benchmark and write its figures (amha bench --help)", benchMain);

}  // namespace cli
}  // namespace amha
