// `amha bench lattice`: the paper's anytime comparison on a map. Runs A-MHA*, ARA*, ANA* and
// MHA* (or a chosen list) on given or seeded random start/goal pairs and writes the median
// solution cost and median certified bound against time as PNG charts, the CSV behind them
// and a summary with the command that made them.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>

#include <time.h>

#include <CLI/CLI.hpp>
#include <opencv2/imgproc.hpp>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "bench_command.h"
#include "exit_codes.h"
#include "lattice_options.h"
#include "line_plot.h"
#include "random_queries.h"
#include "run_json.h"
#include "schedule_option.h"

namespace amha {
namespace cli {

namespace {

using lattice::Pose2D;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Run {
  std::size_t query;
  Algorithm algorithm;
  lattice::PlanResult result;
};

// CPU time of the whole process (all threads), seconds.
double processCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Times the per-goal heuristic tables alone: all of them (in parallel) and each one alone.
// The CPU time of "all" (both threads) tells what the wall time would be on idle cores: on a
// shared machine the wall time also counts the time other jobs hold the cores.
std::string gridTimingReport(const lattice::LatticeGraph& graph, int goals, unsigned seed) {
  lattice::HeuristicGridBuilder builder(graph);
  const std::vector<Query> qs = randomQueries(graph, goals, seed + 1, 0.0);
  std::vector<double> all, all_cpu, single[lattice::kNumGridKinds];
  for (const Query& q : qs) {
    int x, y, h;
    graph.poseToState(q.goal, &x, &y, &h);
    const double c0 = processCpuSeconds();
    all.push_back(builder.compute(x, y, h, true)->seconds);
    all_cpu.push_back(processCpuSeconds() - c0);
    for (int k = 0; k < lattice::kNumGridKinds; ++k) {
      if (!builder.needed(static_cast<lattice::GridKind>(k))) continue;
      const auto t0 = std::chrono::steady_clock::now();
      builder.computeOne(static_cast<lattice::GridKind>(k), x, y);
      single[k].push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
  }
  std::ostringstream out;
  char line[200];
  std::snprintf(line, sizeof line,
                "heuristic tables for one goal, median of %zu goals: all (parallel) %.4f s wall, "
                "%.4f s CPU; alone:",
                qs.size(), median(all), median(all_cpu));
  out << line;
  const char* names[lattice::kNumGridKinds] = {"anchor grid", "point robot", "inscribed opening",
                                               "circumscribed opening"};
  for (int k = 0; k < lattice::kNumGridKinds; ++k) {
    if (single[k].empty()) continue;
    std::snprintf(line, sizeof line, " %s %.4f s;", names[k], median(single[k]));
    out << line;
  }
  out << " (grids shared between identical kinds are computed once in 'all')\n";
  return out.str();
}

int gridTiming(const lattice::LatticeGraph& graph, int goals, unsigned seed,
               const std::string& command) {
  std::printf("%s\nmachine: %s\ncommit: %s\nmap: %d x %d cells\n%s", command.c_str(),
              machineDescription().c_str(), sourceCommit().c_str(), graph.width(), graph.height(),
              gridTimingReport(graph, goals, seed).c_str());
  return kExitOk;
}

int benchLatticeMain(int argc, char** argv) {
  CLI::App app(
      "Runs anytime algorithms on start/goal pairs on a map and writes the median cost and "
      "certified bound vs time (PNG + CSV) and a summary into --out-dir.",
      argv[0]);
  LatticeOptions lo;
  lo.addTo(app);
  int num_queries = 20;
  unsigned seed = 1;
  double min_distance = 0.0, time_limit = 5.0;
  std::vector<std::string> query_texts;
  std::string algorithms_text = "amha,ara,ana,mha", out_dir = "docs/results", name = "lattice",
              json_path;
  int grid_timing = 0;
  app.add_option("--queries", num_queries, "number of seeded random start/goal pairs (default 20)");
  app.add_option("--seed", seed, "seed of the random pairs (default 1)");
  app.add_option("--min-distance", min_distance,
                 "minimum start-goal distance of random pairs, m (default 0)");
  app.add_option("--query", query_texts,
                 "a given pair \"sx,sy,st;gx,gy,gt\" (repeatable; replaces random pairs)");
  app.add_option("--algorithms", algorithms_text,
                 "comma-separated algorithms (default amha,ara,ana,mha)");
  app.add_option("--time-limit", time_limit, "seconds per run, heuristics included (default 5)");
  QueueSchedule schedule = QueueSchedule::kRoundRobin;
  cli::addScheduleOption(app, &schedule);
  std::string preset = "paper";
  app.add_option("--preset", preset,
                 "weights: paper (each algorithm's paper preset, the paper's figures; default) or "
                 "lattice (the "
                 "lattice planner's defaults, as amha plan and the server use them)")
      ->check(CLI::IsMember({"paper", "lattice"}));
  app.add_option("--out-dir", out_dir, "directory for the outputs (default docs/results)");
  app.add_option("--name", name, "file name prefix (default lattice)");
  app.add_option("--json", json_path, "also write every run (runs/solutions schema) to this file");
  app.add_option("--grid-timing", grid_timing,
                 "also time the heuristic grids for this many random goals");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  std::vector<Algorithm> algorithms;
  {
    std::stringstream ss(algorithms_text);
    std::string a;
    while (std::getline(ss, a, ',')) {
      Algorithm alg;
      if (!parseAlgorithm(a, &alg)) {
        std::cerr << "amha bench lattice: unknown algorithm '" << a << "'\n";
        return kExitUsage;
      }
      algorithms.push_back(alg);
    }
  }
  if (algorithms.empty() || !(time_limit > 0.0) || num_queries < 0 ||
      (num_queries == 0 && grid_timing <= 0)) {
    std::cerr << "amha bench lattice: need algorithms, a positive time limit and queries (or "
                 "--queries 0 --grid-timing N)\n";
    return kExitUsage;
  }
  const bool grids_only = num_queries == 0 && query_texts.empty();

  LoadedLattice loaded;
  std::unique_ptr<lattice::LatticeGraph> graph;
  std::vector<Query> queries;
  std::vector<std::unique_ptr<lattice::LatticePlanner>> planners;
  try {
    loaded = loadLattice(lo);
    graph.reset(new lattice::LatticeGraph(loaded.map, loaded.config));
    for (const std::string& q : query_texts) {
      const std::size_t semi = q.find(';');
      if (semi == std::string::npos)
        throw std::invalid_argument("--query '" + q + "' is not \"sx,sy,st;gx,gy,gt\"");
      queries.push_back({parsePose(q.substr(0, semi), "--query start"),
                         parsePose(q.substr(semi + 1), "--query goal")});
    }
    if (queries.empty() && !grids_only)
      queries = randomQueries(*graph, num_queries, seed, min_distance, true);
    // One planner per algorithm: every query has a new goal, so no run reuses cached grids.
    for (std::size_t a = 0; a < algorithms.size(); ++a)
      planners.emplace_back(new lattice::LatticePlanner(loaded.map, loaded.config));
  } catch (const lattice::LatticeError& e) {
    std::cerr << "amha bench lattice: " << e.what() << "\n";
    return exitCodeFor(e);
  } catch (const std::invalid_argument& e) {
    std::cerr << "amha bench lattice: " << e.what() << "\n";
    return kExitUsage;
  }
  if (queries.empty() && !grids_only) {
    std::cerr << "amha bench lattice: found no valid start/goal pair on this map\n";
    return kExitBadInstances;
  }
  if (grids_only) return gridTiming(*graph, grid_timing, seed, benchCommandLine(argc, argv));
  const std::string command = benchCommandLine(argc, argv);
  std::printf("%s\n%zu queries, %zu algorithms, %.1f s each\n", command.c_str(), queries.size(),
              algorithms.size(), time_limit);

  std::vector<Run> runs;
  SearchLimits limits;
  limits.time_limit_s = time_limit;
  for (std::size_t q = 0; q < queries.size(); ++q) {
    for (std::size_t a = 0; a < algorithms.size(); ++a) {
      PlannerConfig pc = preset == "lattice" ? lattice::defaultPlannerConfig(algorithms[a])
                                             : defaultConfig(algorithms[a]);
      pc.schedule = schedule;
      Run r{q, algorithms[a], planners[a]->plan(queries[q].start, queries[q].goal, pc, limits)};
      if (r.result.error != lattice::QueryError::kNone) {
        std::cerr << "amha bench lattice: query " << q + 1 << ": " << r.result.message << "\n";
        return r.result.error == lattice::QueryError::kStartInCollision ||
                       r.result.error == lattice::QueryError::kStartOutOfMap ||
                       r.result.error == lattice::QueryError::kStartNotFinite
                   ? kExitBadStart
                   : kExitBadGoal;
      }
      const auto& sols = r.result.solutions;
      std::printf(
          "query %zu/%zu %-6s %-15s solutions %2zu  first %8.4f s  last %8.4f s  bound %7.3f  "
          "expansions %llu\n",
          q + 1, queries.size(), algorithmName(algorithms[a]), statusName(r.result.search.status),
          sols.size(), sols.empty() ? kInf : sols.front().elapsed_total_s,
          sols.empty() ? kInf : sols.back().elapsed_total_s,
          sols.empty() ? kInf : sols.back().search.certified_bound,
          static_cast<unsigned long long>(r.result.search.expansions));
      std::fflush(stdout);
      runs.push_back(std::move(r));
    }
  }

  // Best known cost per query (over every algorithm), for normalising costs across queries.
  std::vector<double> best(queries.size(), kInf);
  for (const Run& r : runs)
    for (const auto& s : r.result.solutions)
      best[r.query] = std::min(best[r.query], static_cast<double>(s.search.cost));

  const int points = 200;
  std::vector<double> times;
  for (int i = 0; i < points; ++i)
    times.push_back(1e-3 * std::pow(time_limit / 1e-3, i / (points - 1.0)));
  std::vector<PlotSeries> cost_series, bound_series;
  std::ostringstream csv;
  csv << "algorithm,time_s,median_cost_over_best,median_certified_bound,solved_fraction\n";
  for (Algorithm alg : algorithms) {
    PlotSeries cs{algorithmName(alg), {}, {}, true}, bs{algorithmName(alg), {}, {}, true};
    for (double t : times) {
      std::vector<double> costs, bounds;
      int solved = 0;
      for (const Run& r : runs) {
        if (r.algorithm != alg) continue;
        const lattice::LatticeSolution* cur = nullptr;
        for (const auto& s : r.result.solutions) {
          if (s.elapsed_total_s <= t) cur = &s;
        }
        solved += cur != nullptr;
        costs.push_back(cur ? cur->search.cost / best[r.query] : kInf);
        bounds.push_back(cur ? cur->search.certified_bound : kInf);
      }
      const double mc = median(costs), mb = median(bounds);
      cs.x.push_back(t);
      cs.y.push_back(mc);
      bs.x.push_back(t);
      bs.y.push_back(mb);
      char line[160];
      std::snprintf(line, sizeof line, "%s,%.6g,%.6g,%.6g,%.4f\n", algorithmName(alg), t, mc, mb,
                    static_cast<double>(solved) / queries.size());
      csv << line;
    }
    cost_series.push_back(cs);
    bound_series.push_back(bs);
  }

  // Summary per algorithm.
  std::ostringstream sum;
  sum << "command: " << command << "\nmachine: " << machineDescription()
      << "\ncommit: " << sourceCommit() << "\nmap: " << lo.map_file << " (" << loaded.map->width
      << " x " << loaded.map->height << " cells of " << loaded.map->resolution << " m), "
      << graph->primitives().num_headings << " headings, " << graph->primitives().primitives.size()
      << " primitives\n"
      << "queries: " << queries.size()
      << (query_texts.empty() ? " seeded random (seed " + std::to_string(seed) +
                                    ", kept if weighted A* finds a path in 2 s)"
                              : " given")
      << ", time limit " << time_limit << " s per run, heuristics included\n\n";
  char row[256];
  std::snprintf(row, sizeof row, "%-7s %7s %11s %11s %11s %11s %9s %13s\n", "algo", "solved",
                "t_first(s)", "cost_first", "cost_final", "bound_final", "optimal", "t_optimal(s)");
  sum << "medians over queries (cost relative to the best known for the query; inf = none)\n"
      << row;
  for (Algorithm alg : algorithms) {
    std::vector<double> t_first, c_first, c_final, b_final, t_opt;
    int solved = 0, optimal = 0;
    for (const Run& r : runs) {
      if (r.algorithm != alg) continue;
      const auto& s = r.result.solutions;
      solved += !s.empty();
      t_first.push_back(s.empty() ? kInf : s.front().elapsed_total_s);
      c_first.push_back(s.empty() ? kInf : s.front().search.cost / best[r.query]);
      c_final.push_back(s.empty() ? kInf : s.back().search.cost / best[r.query]);
      b_final.push_back(s.empty() ? kInf : s.back().search.certified_bound);
      const bool opt = r.result.search.status == SearchStatus::kProvenOptimal;
      optimal += opt;
      t_opt.push_back(opt ? s.back().elapsed_total_s : kInf);
    }
    std::snprintf(row, sizeof row, "%-7s %3d/%-3zu %11.4f %11.4f %11.4f %11.4f %5d/%-3zu %13.4f\n",
                  algorithmName(alg), solved, queries.size(), median(t_first), median(c_first),
                  median(c_final), median(b_final), optimal, queries.size(), median(t_opt));
    sum << row;
  }

  if (grid_timing > 0) sum << "\n" << gridTimingReport(*graph, grid_timing, seed);
  std::cout << "\n" << sum.str();

  try {
    const std::string base = out_dir + "/" + name;
    PlotOptions po;
    po.log_x = true;
    po.x_label = "time (s), heuristics included";
    po.title =
        "median solution cost / best known cost (" + std::to_string(queries.size()) + " queries)";
    po.y_label = "cost / best known";
    writeLinePlot(base + "_cost.png", cost_series, po);
    po.title =
        "median certified suboptimality bound (" + std::to_string(queries.size()) + " queries)";
    po.y_label = "certified bound";
    writeLinePlot(base + "_bound.png", bound_series, po);
    std::ofstream out_csv(base + ".csv");
    out_csv << csv.str();
    std::ofstream out_sum(base + "_summary.txt");
    out_sum << sum.str();
    if (!out_csv || !out_sum)
      throw std::runtime_error("cannot write " + base + ".csv / _summary.txt");
    if (!json_path.empty()) {
      nlohmann::json all = nlohmann::json::array();
      for (const Run& r : runs) {
        nlohmann::json j = runToJson("query " + std::to_string(r.query + 1), r.algorithm,
                                     r.result.search, r.result.searchSolutions(), std::nullopt);
        j["heuristic_seconds"] = r.result.heuristic_seconds;
        all.push_back(j);
      }
      writeRunsJson(json_path, all, {{"command", command}});
    }
    std::printf("wrote %s_cost.png, %s_bound.png, %s.csv, %s_summary.txt\n", base.c_str(),
                base.c_str(), base.c_str(), base.c_str());
  } catch (const std::exception& e) {
    std::cerr << "amha bench lattice: " << e.what() << "\n";
    return kExitOutput;
  }
  return kExitOk;
}

}  // namespace

AMHA_REGISTER_BENCHMARK("lattice", "anytime algorithms on a map: cost and bound vs time",
                        benchLatticeMain);

}  // namespace cli
}  // namespace amha
