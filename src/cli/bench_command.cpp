// `amha bench <what> [options]`: dispatches to the registered benchmarks.
#include "bench_command.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>

#include "command_registry.h"
#include "exit_codes.h"

namespace amha {
namespace cli {

std::vector<Benchmark>& benchmarkRegistry() {
  static std::vector<Benchmark> benchmarks;
  return benchmarks;
}

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::infinity();
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);  // inf if either middle value is
}

std::string benchCommandLine(int argc, char** argv) {
  std::string s = argv[0];
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a.find_first_of(" ;\"'") != std::string::npos) a = "\"" + a + "\"";
    s += " " + a;
  }
  return s;
}

std::string machineDescription() {
  std::ifstream in("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  int cores = 0;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0 && model == "unknown CPU")
      model = line.substr(line.find(':') + 2);
    if (line.rfind("processor", 0) == 0) ++cores;
  }
  return model + ", " + std::to_string(cores) + " logical cores";
}

namespace {

// The first line a shell command prints, or "" (popen: git is an optional tool here).
std::string firstLineOf(const std::string& command, bool* succeeded = nullptr) {
  FILE* p = popen(command.c_str(), "r");
  if (p == nullptr) return "";
  char buf[128] = {0};
  const bool read = std::fgets(buf, sizeof buf, p) != nullptr;
  const int status = pclose(p);
  if (succeeded != nullptr) *succeeded = status == 0;
  std::string s = read ? buf : "";
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

}  // namespace

std::string sourceCommit() {
  const std::string git = std::string("git -C '") + AMHA_SOURCE_DIR + "' ";
  const std::string commit = firstLineOf(git + "rev-parse --short HEAD 2>/dev/null");
  if (commit.empty()) return "unknown";
  bool clean = false;
  firstLineOf(git + "diff --quiet HEAD -- src include 2>/dev/null", &clean);
  return clean ? commit : commit + " (+ uncommitted changes)";
}

namespace {

void usage(std::ostream& out) {
  out << "usage: amha bench <benchmark> [options]   (amha bench <benchmark> "
         "--help)\n\nbenchmarks:\n";
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

AMHA_REGISTER_COMMAND("bench", "run a benchmark and write its figures (amha bench --help)",
                      benchMain);

}  // namespace cli
}  // namespace amha
