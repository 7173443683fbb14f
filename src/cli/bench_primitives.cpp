// `amha bench primitives`: the same queries planned to the optimum (A*) with several primitive
// sets on one map and robot: optimal costs relative to a reference set, queries one set solves
// and another cannot, primitives per heading, planning times, and a picture of the paths.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/motion_primitives.h"
#include "bench_command.h"
#include "exit_codes.h"
#include "lattice_image.h"
#include "lattice_options.h"
#include "random_queries.h"

namespace amha {
namespace cli {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct PrimitiveSetUnderTest {
  std::string name, spec;  // spec: near-minimal | legacy | a primitive file
  lattice::LatticeConfig config;
  std::size_t primitives = 0, min_per_heading = 0, max_per_heading = 0;
  std::unique_ptr<lattice::LatticePlanner> planner;
};

struct Outcome {
  SearchStatus status = SearchStatus::kNoSolution;
  double cost = kInf;    // metres-equivalent: cost units / kCostUnitsPerMetre
  double seconds = 0.0;  // heuristics included
  std::uint64_t expansions = 0;
  std::vector<lattice::Pose2D> path;
  bool optimal() const { return status == SearchStatus::kProvenOptimal; }
  bool proven_unsolvable() const { return status == SearchStatus::kNoSolution; }
};

std::vector<Query> readQueries(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("cannot open --queries-json " + path);
  std::vector<Query> out;
  try {
    const nlohmann::json doc = nlohmann::json::parse(in);
    for (const auto& q : doc.at("queries")) {
      const auto& s = q.at("start");
      const auto& g = q.at("goal");
      out.push_back({{s.at(0).get<double>(), s.at(1).get<double>(), s.at(2).get<double>()},
                     {g.at(0).get<double>(), g.at(1).get<double>(), g.at(2).get<double>()}});
    }
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(path + ": not an `amha bench queries --json` file: " + e.what());
  }
  return out;
}

std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

int benchPrimitivesMain(int argc, char** argv) {
  CLI::App app(
      "Plans the same queries to the optimum (A*) with several primitive sets and compares the "
      "optima, "
      "the queries each set solves, primitives per heading and planning times.",
      argv[0]);
  LatticeOptions lo;
  lo.addTo(app);
  std::vector<std::string> set_texts;
  std::string queries_json, out_base, reference;
  int count = 20, image_query = 0;
  unsigned seed = 1;
  double min_distance = 0.0, time_limit = 300.0;
  app.add_option("--set", set_texts,
                 "NAME=SPEC, repeatable: SPEC is near-minimal or legacy (generated with the "
                 "generator options "
                 "given) or a primitive file (.json Nav2, else .mprim)")
      ->required();
  app.add_option("--reference", reference,
                 "the set the others' optima are divided by (default: the last --set)");
  app.add_option("--queries", count,
                 "seeded random queries, as `amha bench queries` draws them (default 20)");
  app.add_option("--seed", seed, "their seed (default 1)");
  app.add_option("--min-distance", min_distance,
                 "their minimum start-goal distance, m (default 0)");
  app.add_option("--queries-json", queries_json,
                 "read the queries from an `amha bench queries --json` file instead");
  app.add_option("--time-limit", time_limit,
                 "seconds per A* run, heuristics included (default 300)");
  app.add_option("--out", out_base,
                 "write OUT.txt (summary), OUT.csv (per query and set) and OUT.png (the paths)");
  app.add_option(
      "--image-query", image_query,
      "query (1-based) to draw (default: the one whose optima differ most between the sets)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  if (!(time_limit > 0.0) || !std::isfinite(time_limit) || count < 1 || !(min_distance >= 0.0)) {
    std::cerr
        << "amha bench primitives: --time-limit must be > 0, --queries >= 1, --min-distance >= 0\n";
    return kExitUsage;
  }

  LoadedLattice loaded;
  std::vector<PrimitiveSetUnderTest> sets;
  std::vector<Query> queries;
  try {
    loaded = loadLattice(lo);
    for (const std::string& t : set_texts) {
      const std::size_t eq = t.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == t.size()) {
        throw std::invalid_argument("--set '" + t + "' is not NAME=SPEC");
      }
      PrimitiveSetUnderTest s;
      s.name = t.substr(0, eq);
      s.spec = t.substr(eq + 1);
      s.config = loaded.config;
      s.config.motion.mprim_file.clear();
      // A generator's name, else a primitive file.
      if (!lattice::parsePrimitiveGenerator(s.spec, &s.config.motion.generator)) {
        s.config.motion.mprim_file = s.spec;
      }
      s.planner.reset(new lattice::LatticePlanner(loaded.map, s.config));
      const lattice::PrimitiveSet& p = s.planner->graph().primitives();  // the set the planner uses
      s.primitives = p.primitives.size();
      s.min_per_heading = p.primitives.size();
      for (int h = 0; h < p.num_headings; ++h) {
        const auto r = p.range(h);
        s.min_per_heading = std::min(s.min_per_heading, r.second - r.first);
        s.max_per_heading = std::max(s.max_per_heading, r.second - r.first);
      }
      sets.push_back(std::move(s));
    }
    if (!queries_json.empty()) {
      queries = readQueries(queries_json);
    } else {
      queries = randomQueries(sets.front().planner->graph(), count, seed, min_distance);
    }
  } catch (const lattice::LatticeError& e) {
    std::cerr << "amha bench primitives: " << e.what() << "\n";
    return exitCodeFor(e);
  } catch (const std::invalid_argument& e) {
    std::cerr << "amha bench primitives: " << e.what() << "\n";
    return kExitUsage;
  }
  std::size_t ref = sets.size() - 1;
  if (!reference.empty()) {
    const auto it = std::find_if(sets.begin(), sets.end(), [&](const PrimitiveSetUnderTest& s) {
      return s.name == reference;
    });
    if (it == sets.end()) {
      std::cerr << "amha bench primitives: --reference " << reference
                << " is none of the --set names\n";
      return kExitUsage;
    }
    ref = static_cast<std::size_t>(it - sets.begin());
  }
  if (queries.empty() || image_query < 0 || image_query > static_cast<int>(queries.size())) {
    std::cerr << "amha bench primitives: no queries (or --image-query out of range)\n";
    return kExitBadInstances;
  }

  const std::string command = benchCommandLine(argc, argv);
  std::printf("%s\n%zu queries, %zu primitive sets, A* with a %.0f s limit per run\n",
              command.c_str(), queries.size(), sets.size(), time_limit);
  std::vector<std::vector<Outcome>> results(queries.size(), std::vector<Outcome>(sets.size()));
  std::ostringstream csv;
  csv << "query,set,status,cost_m,seconds,expansions\n";
  SearchLimits limits;
  limits.time_limit_s = time_limit;
  for (std::size_t q = 0; q < queries.size(); ++q) {
    for (std::size_t s = 0; s < sets.size(); ++s) {
      const lattice::PlanResult r = sets[s].planner->plan(queries[q].start, queries[q].goal,
                                                          defaultConfig(Algorithm::kAStar), limits);
      if (r.error != lattice::QueryError::kNone) {
        std::cerr << "amha bench primitives: query " << q + 1 << " (" << sets[s].name
                  << "): " << r.message << "\n";
        return kExitBadInstances;
      }
      Outcome& o = results[q][s];
      o.status = r.search.status;
      o.expansions = r.search.expansions;
      o.seconds = r.totalSeconds();
      if (!r.solutions.empty()) {
        o.cost = r.solutions.back().search.cost / lattice::kCostUnitsPerMetre;
        o.path = r.solutions.back().poses;
      }
      std::printf("query %2zu %-14s %-15s cost %10s  %8.3f s  %10llu expansions\n", q + 1,
                  sets[s].name.c_str(), statusName(o.status), fixed(o.cost, 3).c_str(), o.seconds,
                  static_cast<unsigned long long>(o.expansions));
      std::fflush(stdout);
      csv << q + 1 << "," << sets[s].name << "," << statusName(o.status) << "," << fixed(o.cost, 4)
          << "," << fixed(o.seconds, 4) << "," << o.expansions << "\n";
    }
  }

  std::ostringstream sum;
  sum << "command: " << command << "\nmachine: " << machineDescription()
      << " (shared: wall times vary)\ncommit: " << sourceCommit() << "\nmap: " << lo.map_file
      << " (" << loaded.map->width << " x " << loaded.map->height << " cells of "
      << loaded.map->resolution << " m); " << queries.size() << " queries"
      << (queries_json.empty() ? " (seed " + std::to_string(seed) + ", min distance " +
                                     fixed(min_distance, 1) + " m)"
                               : " from " + queries_json)
      << "; A*, " << time_limit << " s limit per run; costs in metres of free straight driving\n\n";
  char row[320];
  std::snprintf(row, sizeof row, "%-14s %10s %9s %7s %9s %14s %14s %14s %12s %12s\n", "set",
                "primitives", "/heading", "optimal", "unsolved", "median ratio", "min ratio",
                "max ratio", "median s", "median exp.");
  sum << "optimum ratio: this set's optimum / " << sets[ref].name
      << "'s, over the queries both solve to proven optimality; unsolved: proven to have no path\n"
      << row;
  for (std::size_t s = 0; s < sets.size(); ++s) {
    std::vector<double> ratios, seconds, expansions;
    int optimal = 0, unsolved = 0;
    for (std::size_t q = 0; q < queries.size(); ++q) {
      const Outcome& o = results[q][s];
      optimal += o.optimal();
      unsolved += o.proven_unsolvable();
      seconds.push_back(o.optimal() || o.proven_unsolvable() ? o.seconds : kInf);
      expansions.push_back(static_cast<double>(o.expansions));
      if (o.optimal() && results[q][ref].optimal()) ratios.push_back(o.cost / results[q][ref].cost);
    }
    const std::string per = sets[s].min_per_heading == sets[s].max_per_heading
                                ? std::to_string(sets[s].min_per_heading)
                                : std::to_string(sets[s].min_per_heading) + "-" +
                                      std::to_string(sets[s].max_per_heading);
    std::snprintf(
        row, sizeof row, "%-14s %10zu %9s %3d/%-3zu %9d %14s %14s %14s %12s %12.0f\n",
        sets[s].name.c_str(), sets[s].primitives, per.c_str(), optimal, queries.size(), unsolved,
        fixed(median(ratios), 4).c_str(),
        ratios.empty() ? "-" : fixed(*std::min_element(ratios.begin(), ratios.end()), 4).c_str(),
        ratios.empty() ? "-" : fixed(*std::max_element(ratios.begin(), ratios.end()), 4).c_str(),
        fixed(median(seconds), 3).c_str(), median(expansions));
    sum << row;
  }
  // Queries one set proves unsolvable that another solves.
  sum << "\n";
  int disagreements = 0;
  for (std::size_t q = 0; q < queries.size(); ++q) {
    for (std::size_t a = 0; a < sets.size(); ++a) {
      for (std::size_t b = 0; b < sets.size(); ++b) {
        if (results[q][a].proven_unsolvable() && std::isfinite(results[q][b].cost)) {
          sum << "query " << q + 1 << ": no path with " << sets[a].name << ", a path with "
              << sets[b].name << "\n";
          ++disagreements;
        }
      }
    }
  }
  if (disagreements == 0) sum << "no query is unsolvable with one set and solved with another\n";
  // The picture: the query whose optima differ most (or the one asked for).
  std::size_t pick = image_query > 0 ? static_cast<std::size_t>(image_query - 1) : 0;
  if (image_query == 0) {
    double spread = -1.0;
    for (std::size_t q = 0; q < queries.size(); ++q) {
      double lo_c = kInf, hi_c = 0.0;
      for (const Outcome& o : results[q]) {
        if (!std::isfinite(o.cost)) continue;
        lo_c = std::min(lo_c, o.cost);
        hi_c = std::max(hi_c, o.cost);
      }
      if (std::isfinite(lo_c) && hi_c / lo_c > spread) {
        spread = hi_c / lo_c;
        pick = q;
      }
    }
  }
  const Query& shown = queries[pick];
  sum << "\npicture: query " << pick + 1 << " (" << fixed(shown.start.x, 2) << ", "
      << fixed(shown.start.y, 2) << ", " << fixed(shown.start.theta, 3) << ") -> ("
      << fixed(shown.goal.x, 2) << ", " << fixed(shown.goal.y, 2) << ", "
      << fixed(shown.goal.theta, 3) << "):";
  for (std::size_t s = 0; s < sets.size(); ++s)
    sum << " " << sets[s].name << " " << fixed(results[pick][s].cost, 3) << " m";
  sum << "\n";
  std::cout << "\n" << sum.str();

  if (!out_base.empty()) {
    try {
      std::ofstream txt(out_base + ".txt"), table(out_base + ".csv");
      txt << sum.str();
      table << csv.str();
      if (!txt || !table) throw std::runtime_error("cannot write " + out_base + ".txt / .csv");
      static const std::array<int, 3> colours[] = {
          {40, 40, 230}, {200, 120, 0}, {0, 160, 0}, {160, 0, 160}, {0, 140, 220}};
      std::vector<LabelledPath> paths;
      for (std::size_t s = 0; s < sets.size(); ++s) {
        paths.push_back({sets[s].name + " " + fixed(results[pick][s].cost, 2) + " m",
                         colours[s % 5], results[pick][s].path});
      }
      writePathsImage(out_base + ".png", *loaded.map, paths, shown.start, shown.goal);
      std::printf("wrote %s.txt, %s.csv, %s.png\n", out_base.c_str(), out_base.c_str(),
                  out_base.c_str());
    } catch (const std::exception& e) {
      std::cerr << "amha bench primitives: " << e.what() << "\n";
      return kExitOutput;
    }
  }
  return kExitOk;
}

}  // namespace

AMHA_REGISTER_BENCHMARK("primitives",
                        "optimal paths with several primitive sets on the same queries (A*)",
                        benchPrimitivesMain);

}  // namespace cli
}  // namespace amha
