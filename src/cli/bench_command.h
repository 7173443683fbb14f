// `amha bench <what>`: benchmarks register themselves here, one file each (bench_*.cpp).
#pragma once

#include <string>
#include <vector>

namespace amha {
namespace cli {

struct Benchmark {
  const char* name;
  const char* summary;
  int (*run)(int argc, char** argv);  // argv[0] is "amha bench <name>"
};

std::vector<Benchmark>& benchmarkRegistry();

// Shared by the benchmarks' reports.
/// The median; infinity for none (or if either middle value is).
double median(std::vector<double> v);
/// The command as typed: argv[0] ("amha bench <name>") and the arguments, quoted where needed.
std::string benchCommandLine(int argc, char** argv);
/// The CPU model and the number of logical cores, from /proc/cpuinfo.
std::string machineDescription();
/// The source tree's commit, "+ uncommitted changes" if src/ or include/ differ from it (as
/// scripts/bench-tiles stamps its tables); "unknown" without git. The tree is the one this
/// binary was configured from; scripts/amha builds it before running it.
std::string sourceCommit();

struct BenchmarkRegistrar {
  BenchmarkRegistrar(const char* name, const char* summary, int (*run)(int, char**)) {
    benchmarkRegistry().push_back(Benchmark{name, summary, run});
  }
};

}  // namespace cli
}  // namespace amha

#define AMHA_REGISTER_BENCHMARK(name, summary, fn) \
  static const ::amha::cli::BenchmarkRegistrar amha_benchmark_registrar_##fn(name, summary, fn)
