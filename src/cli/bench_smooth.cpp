// `amha bench smooth`: what PathSmoother does to lattice paths. Plans seeded random queries (or
// given ones) with an anytime algorithm, smooths every solution it streams (timed) and compares
// the last one before and after: length, mean and max |curvature|, heading change per metre,
// curvature sign changes and cost. Writes a summary, a CSV row per query and a picture of one
// query (lattice path red, smoothed path blue).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include <time.h>

#include <CLI/CLI.hpp>

#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/path_smoother.h"
#include "bench_command.h"
#include "exit_codes.h"
#include "lattice_image.h"
#include "lattice_options.h"
#include "path_metrics.h"
#include "random_queries.h"

namespace amha {
namespace cli {

namespace {

struct Row {
  std::size_t query = 0;
  PathMetrics before, after;
  Cost cost_before = 0, cost_after = 0;
  std::size_t shortcuts = 0;
  double ms = 0.0;  // smoothing the last solution (its first run)
  std::vector<lattice::Pose2D> raw, smoothed;
};

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Times `repeats` smoothings of one path (milliseconds, wall and this thread's CPU time, which
// a shared machine disturbs less): the first, as in use (once, right after the search that
// found it), and the median of all.
struct Timing {
  double first_ms = 0.0, median_ms = 0.0, first_cpu_ms = 0.0, median_cpu_ms = 0.0;
};
Timing timeSmoothing(const lattice::PathSmoother& smoother,
                     const std::vector<lattice::Pose2D>& poses, int repeats,
                     lattice::SmoothedPath* out) {
  std::vector<double> ms, cpu_ms;
  for (int r = 0; r < repeats; ++r) {
    const double c0 = threadCpuSeconds();
    *out = smoother.smooth(poses);
    cpu_ms.push_back(1e3 * (threadCpuSeconds() - c0));
    ms.push_back(1e3 * out->seconds);
  }
  return {ms.front(), median(ms), cpu_ms.front(), median(cpu_ms)};
}

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

int benchSmoothMain(int argc, char** argv) {
  CLI::App app(
      "Plans start/goal pairs, smooths every solution (timed) and compares the last one before and "
      "after "
      "smoothing; writes a summary, a CSV and a picture into --out-dir.",
      argv[0]);
  LatticeOptions lo;
  lo.addTo(app);
  int num_queries = 20, repeats = 5, image_query = 0;
  unsigned seed = 1;
  double min_distance = 10.0, time_limit = 5.0;
  std::vector<std::string> query_texts;
  std::string algorithm_name = "amha", out_dir = "docs/results", name = "smoothing";
  app.add_option("--queries", num_queries, "number of seeded random start/goal pairs (default 20)");
  app.add_option("--seed", seed, "seed of the random pairs (default 1)");
  app.add_option("--min-distance", min_distance,
                 "minimum start-goal distance of random pairs, m (default 10)");
  app.add_option("--query", query_texts,
                 "a given pair \"sx,sy,st;gx,gy,gt\" (repeatable; replaces random pairs)");
  app.add_option("--algorithm", algorithm_name,
                 "the planner: amha | mha | ara | ana | wastar | astar (default amha)");
  app.add_option("--time-limit", time_limit, "seconds per query, heuristics included (default 5)");
  app.add_option("--repeat", repeats,
                 "smoothings timed per path; the median is reported (default 5)");
  app.add_option("--image-query", image_query,
                 "the query drawn (1-based; default 0: the longest path)");
  app.add_option("--out-dir", out_dir, "directory for the outputs (default docs/results)");
  app.add_option("--name", name, "file name prefix (default smoothing)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  Algorithm algorithm;
  if (!parseAlgorithm(algorithm_name, &algorithm)) {
    std::cerr << "amha bench smooth: unknown algorithm '" << algorithm_name << "'\n";
    return kExitUsage;
  }
  if (!(time_limit > 0.0) || num_queries < 1 || repeats < 1 || image_query < 0) {
    std::cerr << "amha bench smooth: need a positive time limit, --queries and --repeat >= 1, "
                 "--image-query >= 0\n";
    return kExitUsage;
  }

  LoadedLattice loaded;
  std::unique_ptr<lattice::LatticePlanner> planner;
  std::vector<Query> queries;
  try {
    loaded = loadLattice(lo);
    planner.reset(new lattice::LatticePlanner(loaded.map, loaded.config));
    for (const std::string& q : query_texts) {
      const std::size_t semi = q.find(';');
      if (semi == std::string::npos)
        throw std::invalid_argument("--query '" + q + "' is not \"sx,sy,st;gx,gy,gt\"");
      queries.push_back({parsePose(q.substr(0, semi), "--query start"),
                         parsePose(q.substr(semi + 1), "--query goal")});
    }
    if (queries.empty())
      queries = randomQueries(planner->graph(), num_queries, seed, min_distance, true);
  } catch (const lattice::LatticeError& e) {
    std::cerr << "amha bench smooth: " << e.what() << "\n";
    return exitCodeFor(e);
  } catch (const std::invalid_argument& e) {
    std::cerr << "amha bench smooth: " << e.what() << "\n";
    return kExitUsage;
  }
  if (queries.empty()) {
    std::cerr << "amha bench smooth: found no valid start/goal pair on this map\n";
    return kExitBadInstances;
  }
  const lattice::PathSmoother smoother(planner->graph());
  const std::string command = benchCommandLine(argc, argv);
  std::printf("%s\n%zu queries, %s, %.1f s each; shortcut turning radius %.3f m\n", command.c_str(),
              queries.size(), algorithmName(algorithm), time_limit, smoother.turningRadius());

  std::vector<Row> rows;
  // Per distinct streamed path (A-MHA* and ARA* repeat a path when only its bound tightens):
  // the first smoothing (as in use) and the median of the repeats, per path and per 100 m.
  std::vector<double> first_ms, warm_ms, first_per_100m, warm_per_100m, cpu_ms, cpu_per_100m;
  for (std::size_t q = 0; q < queries.size(); ++q) {
    SearchLimits limits;
    limits.time_limit_s = time_limit;
    const lattice::PlanResult r =
        planner->plan(queries[q].start, queries[q].goal, defaultConfig(algorithm), limits);
    if (r.error != lattice::QueryError::kNone) {
      std::cerr << "amha bench smooth: query " << q + 1 << ": " << r.message << "\n";
      return kExitBadInstances;
    }
    if (r.solutions.empty()) {
      std::printf("query %zu: no solution in %.1f s (%s)\n", q + 1, time_limit,
                  statusName(r.search.status));
      continue;
    }
    Row row;
    row.query = q + 1;
    lattice::SmoothedPath s;
    const std::vector<StateId>* previous = nullptr;
    for (const lattice::LatticeSolution& sol : r.solutions) {
      if (previous != nullptr && *previous == sol.search.path) continue;
      previous = &sol.search.path;
      const Timing t = timeSmoothing(smoother, sol.poses, repeats, &s);
      const double length = pathMetrics(sol.poses).length;
      first_ms.push_back(t.first_ms);
      warm_ms.push_back(t.median_ms);
      cpu_ms.push_back(t.first_cpu_ms);
      if (length > 0.0) {
        first_per_100m.push_back(t.first_ms * 100.0 / length);
        warm_per_100m.push_back(t.median_ms * 100.0 / length);
        cpu_per_100m.push_back(t.first_cpu_ms * 100.0 / length);
      }
      row.ms = t.first_ms;
    }
    row.raw = r.solutions.back().poses;
    row.smoothed = s.poses;
    row.before = pathMetrics(row.raw);
    row.after = pathMetrics(row.smoothed);
    row.cost_before = r.solutions.back().search.cost;
    row.cost_after = s.cost;
    row.shortcuts = s.shortcuts;
    std::printf(
        "query %2zu: %2zu solutions; length %7.2f -> %7.2f m  mean|k| %.3f -> %.3f  max|k| %.2f -> "
        "%.2f  "
        "dtheta/m %.3f -> %.3f  sign changes %3d -> %3d  cost %lld -> %lld  %.3f ms\n",
        row.query, r.solutions.size(), row.before.length, row.after.length,
        row.before.mean_curvature, row.after.mean_curvature, row.before.max_curvature,
        row.after.max_curvature, row.before.heading_change_per_metre,
        row.after.heading_change_per_metre, row.before.curvature_sign_changes,
        row.after.curvature_sign_changes, static_cast<long long>(row.cost_before),
        static_cast<long long>(row.cost_after), row.ms);
    std::fflush(stdout);
    rows.push_back(std::move(row));
  }
  if (rows.empty()) {
    std::cerr << "amha bench smooth: no query was solved\n";
    return kExitNoSolution;
  }

  // Medians over the queries, and the ratio after / before of each.
  auto med = [&](auto get) {
    std::vector<double> v;
    for (const Row& r : rows) v.push_back(get(r));
    return median(v);
  };
  std::ostringstream sum, csv;
  const lattice::GridMap& map = *loaded.map;
  sum << "command: " << command << "\nmachine: " << machineDescription()
      << " (shared; wall times)\ncommit: " << sourceCommit() << "\nmap: " << lo.map_file << " ("
      << map.width << " x " << map.height << " cells of " << map.resolution
      << " m); shortcut turning radius " << smoother.turningRadius() << " m\n"
      << "queries: " << rows.size() << " solved of " << queries.size()
      << (query_texts.empty() ? " seeded random (seed " + std::to_string(seed) + ", at least " +
                                    fmt("%g", min_distance) + " m apart)"
                              : " given")
      << ", " << algorithmName(algorithm) << ", " << time_limit
      << " s each; the last solution of each compared\n\n";
  char line[256];
  std::snprintf(line, sizeof line, "%-28s %12s %12s %9s\n", "median over queries", "lattice",
                "smoothed", "ratio");
  sum << line;
  auto add = [&](const char* label, auto before, auto after) {
    const double b = med(before), a = med(after), ratio = med([&](const Row&r) {
                                                    const double x = before(r);
                                                    return x > 0.0 ? after(r) / x : 1.0;
                                                  });
    std::snprintf(line, sizeof line, "%-28s %12.4f %12.4f %9.3f\n", label, b, a, ratio);
    sum << line;
  };
  add(
      "length (m)", [](const Row& r) { return r.before.length; },
      [](const Row& r) { return r.after.length; });
  add(
      "mean |curvature| (1/m)", [](const Row& r) { return r.before.mean_curvature; },
      [](const Row& r) { return r.after.mean_curvature; });
  add(
      "max |curvature| (1/m)", [](const Row& r) { return r.before.max_curvature; },
      [](const Row& r) { return r.after.max_curvature; });
  add(
      "|dheading| per metre (rad)", [](const Row& r) { return r.before.heading_change_per_metre; },
      [](const Row& r) { return r.after.heading_change_per_metre; });
  add(
      "curvature sign changes",
      [](const Row& r) { return static_cast<double>(r.before.curvature_sign_changes); },
      [](const Row& r) { return static_cast<double>(r.after.curvature_sign_changes); });
  add(
      "cost (units)", [](const Row& r) { return static_cast<double>(r.cost_before); },
      [](const Row& r) { return static_cast<double>(r.cost_after); });
  int costlier = 0;
  for (const Row& r : rows) costlier += r.cost_after > r.cost_before;
  sum << "smoothed paths costlier than their lattice path: " << costlier << "\n";
  std::vector<double> longest;
  for (const Row& r : rows) longest.push_back(r.before.length);
  // Median, 90th percentile (nearest rank) and maximum.
  auto spread = [](std::vector<double> v) {
    if (v.empty()) return std::string("none");
    std::sort(v.begin(), v.end());
    const std::size_t p90 = static_cast<std::size_t>(std::ceil(0.9 * v.size())) - 1;
    return "median " + fmt("%.3f", median(v)) + ", 90th percentile " + fmt("%.3f", v[p90]) +
           ", max " + fmt("%.3f", v.back()) + " ms";
  };
  auto stats = [&](const char* what, const std::vector<double>& ms,
                   const std::vector<double>& per_100m) {
    return std::string(what) + ": " + spread(ms) + "; per 100 m of path: " + spread(per_100m) +
           "\n";
  };
  sum << "smoothing time of each distinct streamed path (" << first_ms.size() << " paths, longest "
      << fmt("%.1f", *std::max_element(longest.begin(), longest.end())) << " m):\n"
      << stats("  first run, as in use (right after the search), wall", first_ms, first_per_100m)
      << stats("  first run, this thread's CPU time", cpu_ms, cpu_per_100m)
      << stats(("  warm (median of " + std::to_string(repeats) + " runs), wall").c_str(), warm_ms,
               warm_per_100m);
  csv << "query,length_before,length_after,mean_curvature_before,mean_curvature_after,max_"
         "curvature_before,"
         "max_curvature_after,dheading_per_m_before,dheading_per_m_after,sign_changes_before,sign_"
         "changes_after,"
         "cost_before,cost_after,shortcuts,smoothing_ms\n";
  for (const Row& r : rows) {
    std::snprintf(line, sizeof line,
                  "%zu,%.4f,%.4f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%d,%d,%lld,%lld,%zu,%.4f\n", r.query,
                  r.before.length, r.after.length, r.before.mean_curvature, r.after.mean_curvature,
                  r.before.max_curvature, r.after.max_curvature, r.before.heading_change_per_metre,
                  r.after.heading_change_per_metre, r.before.curvature_sign_changes,
                  r.after.curvature_sign_changes, static_cast<long long>(r.cost_before),
                  static_cast<long long>(r.cost_after), r.shortcuts, r.ms);
    csv << line;
  }
  std::cout << "\n" << sum.str();
  try {
    const std::string base = out_dir + "/" + name;
    std::size_t drawn = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (image_query > 0 ? rows[i].query == static_cast<std::size_t>(image_query)
                          : rows[i].before.length > rows[drawn].before.length) {
        drawn = i;
      }
    }
    writePathsImage(base + ".png", map,
                    {{"lattice path", {40, 40, 220}, rows[drawn].raw},
                     {"smoothed", {200, 90, 20}, rows[drawn].smoothed}},
                    rows[drawn].raw.front(), rows[drawn].raw.back(), 1.0);
    std::ofstream out_csv(base + ".csv");
    out_csv << csv.str();
    std::ofstream out_sum(base + "_summary.txt");
    out_sum << sum.str() << "picture: query " << rows[drawn].query
            << " (lattice path red, smoothed blue)\n";
    if (!out_csv || !out_sum)
      throw std::runtime_error("cannot write " + base + ".csv / _summary.txt");
    std::printf("picture: query %zu\nwrote %s.png, %s.csv, %s_summary.txt\n", rows[drawn].query,
                base.c_str(), base.c_str(), base.c_str());
  } catch (const std::exception& e) {
    std::cerr << "amha bench smooth: " << e.what() << "\n";
    return kExitOutput;
  }
  return kExitOk;
}

}  // namespace

AMHA_REGISTER_BENCHMARK(
    "smooth", "smoothing lattice paths: curvature, length, cost and time before and after",
    benchSmoothMain);

}  // namespace cli
}  // namespace amha
