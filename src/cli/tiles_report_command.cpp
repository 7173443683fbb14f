// `amha tiles-report FILE.json`: renders the table, Markdown and plot of a finished
// `amha tiles --json` run again, from the recorded runs (no searching).
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "command_registry.h"
#include "exit_codes.h"
#include "tiles_report.h"

namespace amha {
namespace cli {
namespace {

double numberOr(const nlohmann::json& j, const char* key, double fallback) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

bool parseStatus(const std::string& name, SearchStatus* out) {
  for (SearchStatus s :
       {SearchStatus::kProvenOptimal, SearchStatus::kBoundReached, SearchStatus::kTimeLimit,
        SearchStatus::kExpansionLimit, SearchStatus::kMemoryLimit, SearchStatus::kCancelled,
        SearchStatus::kNoSolution}) {
    if (name == statusName(s)) {
      *out = s;
      return true;
    }
  }
  return false;
}

TilesRun runFromJson(const nlohmann::json& j) {
  const double inf = std::numeric_limits<double>::infinity();
  TilesRun r;
  r.instance = j.at("instance").get<std::string>();
  if (!parseAlgorithm(j.at("algorithm").get<std::string>(), &r.algorithm)) {
    throw std::runtime_error("unknown algorithm " + j.at("algorithm").dump());
  }
  if (!parseStatus(j.at("status").get<std::string>(), &r.result.status)) {
    throw std::runtime_error("unknown status " + j.at("status").dump());
  }
  if (!j.at("optimal_cost").is_null()) r.optimal = j["optimal_cost"].get<int>();
  r.result.expansions = j.at("expansions").get<std::uint64_t>();
  r.result.peak_states = j.at("peak_states").get<std::size_t>();
  r.result.peak_memory_bytes = j.at("peak_memory_bytes").get<std::size_t>();
  r.result.elapsed_s = j.at("elapsed_s").get<double>();
  r.cpu_s = numberOr(j, "cpu_s", 0.0);
  r.late_solutions = j.value("solutions_after_limit", 0);
  for (const auto& js : j.at("solutions")) {
    Solution s;
    s.cost = js.at("cost").get<Cost>();
    s.nominal_bound = numberOr(js, "bound", inf);
    s.certified_bound = numberOr(js, "certified_bound", inf);
    s.elapsed_s = js.at("elapsed_s").get<double>();
    s.expansions = js.at("expansions").get<std::uint64_t>();
    s.iteration = js.value("iteration", 0);
    r.result.solutions.push_back(s);
    r.solution_cpu_s.push_back(numberOr(js, "cpu_s", s.elapsed_s));
  }
  return r;
}

int runTilesReport(int argc, char** argv) {
  std::string input, markdown, plot, clock;
  CLI::App app{"Renders the table, Markdown and plot of an `amha tiles --json` file again."};
  app.name(argv[0]);
  app.add_option("json", input, "the JSON written by amha tiles --json")->required();
  app.add_option("--markdown", markdown, "write the tables as Markdown to FILE");
  app.add_option("--plot", plot, "write the median certified bound vs time PNG to FILE");
  app.add_option("--clock", clock, "wall or cpu (default: the clock of the run)")
      ->check(CLI::IsMember({"wall", "cpu"}));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  std::vector<TilesRun> runs;
  std::vector<Algorithm> algorithms;
  double time_limit = 10;
  bool cpu_clock = false;
  int size = 0;
  std::size_t n_instances = 0;
  try {
    std::ifstream in(input);
    if (!in) throw std::runtime_error("cannot open " + input);
    const nlohmann::json doc = nlohmann::json::parse(in);
    const auto& settings = doc.at("settings");
    time_limit = settings.at("time_limit_s").get<double>();
    size = settings.at("size").get<int>();
    cpu_clock = (clock.empty() ? settings.value("clock", std::string("wall")) : clock) == "cpu";
    n_instances = doc.at("instances").size();
    for (const auto& j : doc.at("runs")) {
      runs.push_back(runFromJson(j));
      dropLateSolutions(runs.back(), time_limit, cpu_clock);  // files written before the rule
      if (std::find(algorithms.begin(), algorithms.end(), runs.back().algorithm) ==
          algorithms.end()) {
        algorithms.push_back(runs.back().algorithm);
      }
    }
    if (runs.empty()) throw std::runtime_error("no runs");
  } catch (const std::exception& e) {
    std::cerr << "amha tiles-report: " << input << ": " << e.what() << "\n";
    return kExitBadInstances;
  }
  std::cout << n_instances << " instance(s), board " << size << "x" << size << ", time limit "
            << time_limit << " s (" << (cpu_clock ? "CPU" : "wall") << " clock)\n"
            << reportText(runs, algorithms, cpu_clock);
  try {
    if (!markdown.empty()) {
      std::ofstream md(markdown);
      md << reportMarkdown(runs, algorithms, cpu_clock);
      if (!md) throw std::runtime_error("cannot write " + markdown);
    }
    if (!plot.empty() &&
        !writeBoundPlot(plot, runs, algorithms, time_limit, cpu_clock, size, n_instances)) {
      std::cerr
          << "amha tiles-report: no plot written: no algorithm solved half of the instances\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "amha tiles-report: " << e.what() << "\n";
    return kExitOutput;
  }
  return kExitOk;
}

}  // namespace

AMHA_REGISTER_COMMAND("tiles-report",
                      "re-render the tables and plot of an `amha tiles --json` file",
                      runTilesReport);

}  // namespace cli
}  // namespace amha
