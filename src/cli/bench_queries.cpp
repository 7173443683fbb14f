// `amha bench queries`: the seeded start/goal pairs a benchmark runs, printed (and written as
// JSON) so that other planners can be run on exactly the same ones.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bench_command.h"
#include "exit_codes.h"
#include "lattice_options.h"
#include "random_queries.h"

namespace amha {
namespace cli {

namespace {

int benchQueriesMain(int argc, char** argv) {
  CLI::App app(
      "Prints seeded random start/goal pairs, one per line as \"sx,sy,st gx,gy,gt\" (map frame: m, "
      "m, "
      "rad): collision-free for the robot, in one connected region of the cells its centre may "
      "occupy, "
      "at least --min-distance apart.",
      argv[0]);
  LatticeOptions lo;
  lo.addTo(app);
  int count = 20;
  unsigned seed = 1;
  double min_distance = 0.0;
  std::string json_path;
  app.add_option("--count", count, "number of pairs (default 20)");
  app.add_option("--seed", seed, "random seed (default 1)");
  app.add_option("--min-distance", min_distance,
                 "minimum straight-line start-goal distance, m (default 0)");
  app.add_option("--json", json_path,
                 "also write {\"queries\": [{\"start\": [x, y, theta], \"goal\": [...]}, ...]}");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  if (count < 1 || !(min_distance >= 0.0) || !std::isfinite(min_distance)) {
    std::cerr << "amha bench queries: --count must be >= 1 and --min-distance finite and >= 0\n";
    return kExitUsage;
  }
  std::vector<Query> queries;
  try {
    const LoadedLattice loaded = loadLattice(lo);
    const lattice::LatticeGraph graph(loaded.map, loaded.config);
    queries = randomQueries(graph, count, seed, min_distance);
  } catch (const lattice::LatticeError& e) {
    std::cerr << "amha bench queries: " << e.what() << "\n";
    return exitCodeFor(e);
  } catch (const std::invalid_argument& e) {
    std::cerr << "amha bench queries: " << e.what() << "\n";
    return kExitUsage;
  }
  if (static_cast<int>(queries.size()) < count) {
    std::cerr << "amha bench queries: found only " << queries.size() << " of " << count
              << " pairs in a million draws (lower --min-distance?)\n";
    return kExitBadInstances;
  }
  nlohmann::json list = nlohmann::json::array();
  for (const Query& q : queries) {
    std::printf("%.4f,%.4f,%.6f %.4f,%.4f,%.6f\n", q.start.x, q.start.y, q.start.theta, q.goal.x,
                q.goal.y, q.goal.theta);
    list.push_back({{"start", {q.start.x, q.start.y, q.start.theta}},
                    {"goal", {q.goal.x, q.goal.y, q.goal.theta}}});
  }
  if (!json_path.empty()) {
    std::ofstream out(json_path);
    out << nlohmann::json{{"command", benchCommandLine(argc, argv)},
                          {"seed", seed},
                          {"min_distance", min_distance},
                          {"queries", list}}
               .dump(1)
        << "\n";
    out.flush();
    if (!out) {
      std::cerr << "amha bench queries: cannot write " << json_path << "\n";
      return kExitOutput;
    }
  }
  return kExitOk;
}

}  // namespace

AMHA_REGISTER_BENCHMARK(
    "queries", "seeded random start/goal pairs for a map and robot (to run other planners on)",
    benchQueriesMain);

}  // namespace cli
}  // namespace amha
