// `amha tiles`: runs A-MHA*, MHA*, ARA*, ANA* (and weighted A*, A*) on sliding-tile instances
// (generated from a seed or read from a file), shows progress, prints the paper's table and
// writes every run as JSON. See docs/tiles.md.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>

#include <time.h>

#include <CLI/CLI.hpp>

#include "amha_planner/search/planner.h"
#include "amha_planner/tiles/instances.h"
#include "amha_planner/tiles/tiles_problem.h"
#include "command_registry.h"
#include "exit_codes.h"
#include "keep_freed_memory.h"
#include "line_plot.h"
#include "run_json.h"
#include "schedule_option.h"
#include "tiles_report.h"
#include "weight_options.h"

namespace amha {
namespace cli {
namespace {

struct Options {
  int size = 0;
  int random = 0;
  std::uint64_t seed = 1;
  int walk = 0;
  std::string instances_file;
  std::string algorithms = "amha,mha,ara,ana";
  double time_limit = 10.0;
  std::string clock = "wall";
  std::uint64_t max_expansions = 0;
  double w1 = 5.0, w2 = 5.0, dw1 = 0.5, dw2 = 0.5;
  double eps = 25.0, deps = 3.0;
  double weight = 5.0;
  int heuristics = 4;
  std::uint32_t heuristic_seed = 1;
  QueueSchedule schedule = QueueSchedule::kRoundRobin;
  double memory_limit_gb = 8.0;
  int jobs = 1;
  std::string json, write_instances, plot, markdown;
  bool quiet = false;
  bool fresh_memory = false;
};

PlannerConfig configFor(Algorithm a, const Options& o) {
  PlannerConfig c = defaultConfig(a);
  // Each algorithm has its own options: --eps/--deps for ARA*, --weight for weighted A*.
  if (a == Algorithm::kAraStar) {
    applyWeights({o.eps, {}, o.deps, {}}, &c);
  } else if (a == Algorithm::kWeightedAStar) {
    applyWeights({o.weight, {}, {}, {}}, &c);
  } else {
    applyWeights({o.w1, o.w2, o.dw1, o.dw2}, &c);
  }
  if (algorithmSpecs(a).queue_schedule) c.schedule = o.schedule;
  return c;
}

std::string fmtBound(double b) {
  if (!std::isfinite(b)) return "inf";
  std::ostringstream s;
  s.precision(b >= 1e5 ? 3 : 4);
  s << b;
  return s.str();
}

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string fmtSeconds(double t) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3f", t);
  return buf;
}

// Checks a solution move by move on the boards; the command refuses to report a wrong path.
std::string verify(const tiles::TilesProblem& p, const tiles::Board& start, const Solution& s) {
  if (s.path.empty() || p.board(s.path.front()) != start) return "path does not begin at the start";
  if (p.board(s.path.back()) != tiles::goalBoard(start.size))
    return "path does not end at the goal";
  for (std::size_t k = 1; k < s.path.size(); ++k) {
    if (!tiles::isOneMoveApart(p.board(s.path[k - 1]), p.board(s.path[k]))) {
      return "step " + std::to_string(k) + " is not a legal move";
    }
  }
  if (s.cost != static_cast<Cost>(s.path.size() - 1)) return "cost is not the path length";
  return "";
}

int runTiles(int argc, char** argv) {
  Options o;
  CLI::App app{
      "Sliding-tile experiments (the paper's Tables 1 and 2): runs the chosen "
      "algorithms on N x N puzzles and prints success rate, T_initial, T_final, "
      "eps_initial, eps_final, certified bound, cost, expansions/s."};
  app.name(argv[0]);
  auto* size_opt =
      app.add_option("--size", o.size, "board size N (3..9): 7 = 48-puzzle, 8 = 63-puzzle")
          ->check(CLI::Range(tiles::kMinSize, tiles::kMaxSize));
  auto* random_opt =
      app.add_option("--random", o.random, "generate this many uniformly random solvable instances")
          ->check(CLI::Range(1, 1000000));
  app.add_option("--seed", o.seed, "seed of the generated instances (default 1)");
  auto* walk_opt =
      app.add_option("--walk", o.walk,
                     "with --random: random walks of this many moves from the goal instead")
          ->check(CLI::Range(1, 100000000));
  auto* file_opt = app.add_option("--instances", o.instances_file,
                                  "read instances from FILE (Korf format: id optimal md tiles...)");
  app.add_option("--algorithms", o.algorithms,
                 "comma-separated: amha,mha,ara,ana,wastar,astar (default amha,mha,ara,ana)");
  app.add_option("--time-limit", o.time_limit, "seconds per run (default 10)")
      ->check(CLI::PositiveNumber);
  app.add_option("--clock", o.clock,
                 "wall (default) or cpu: measure the time limit and the reported times on the "
                 "CPU clock of the searching thread, for fair numbers on a shared machine")
      ->check(CLI::IsMember({"wall", "cpu"}));
  app.add_option("--max-expansions", o.max_expansions, "expansions per run (default: no cap)");
  app.add_option("--w1", o.w1, "A-MHA*/MHA* initial w1 in [1, 1e6] (default 5)")
      ->check(weightRange());
  app.add_option("--w2", o.w2, "A-MHA*/MHA* initial w2 in [1, 1e6] (default 5)")
      ->check(weightRange());
  app.add_option("--dw1", o.dw1, "A-MHA* decrement of w1 per iteration in [0, 1e6] (default 0.5)")
      ->check(decrementRange());
  app.add_option("--dw2", o.dw2, "A-MHA* decrement of w2 per iteration in [0, 1e6] (default 0.5)")
      ->check(decrementRange());
  app.add_option("--eps", o.eps, "ARA* initial epsilon in [1, 1e6] (default 25)")
      ->check(weightRange());
  app.add_option("--deps", o.deps,
                 "ARA* decrement of epsilon per iteration in [0, 1e6] (default 3)")
      ->check(decrementRange());
  app.add_option("--weight", o.weight, "weighted A* weight in [1, 1e6] (default 5)")
      ->check(weightRange());
  app.add_option("--heuristics", o.heuristics,
                 "inadmissible heuristics for A-MHA*/MHA* (default 4)")
      ->check(CLI::Range(0, 64));
  app.add_option("--heuristic-seed", o.heuristic_seed, "seed of their random weights (default 1)");
  cli::addScheduleOption(app, &o.schedule);
  app.add_option("--memory-limit-gb", o.memory_limit_gb,
                 "memory for all parallel runs together, split evenly between jobs (default 8)")
      ->check(CLI::PositiveNumber);
  app.add_option("--jobs", o.jobs, "runs in parallel (default 1)")->check(CLI::Range(1, 64));
  app.add_option("--json", o.json, "write every run (and the settings) to FILE");
  app.add_option("--write-instances", o.write_instances,
                 "write the instances to FILE (Korf format)");
  app.add_option("--plot", o.plot,
                 "write a PNG of the median certified bound vs time per algorithm");
  app.add_option("--markdown", o.markdown, "write the summary table as Markdown to FILE");
  app.add_flag("--quiet,-q", o.quiet, "no progress lines");
  app.add_flag("--fresh-memory", o.fresh_memory,
               "let every run fault in fresh pages (default: reuse the memory of earlier runs, "
               "as a long-lived planner does)");
  try {
    app.parse(argc, argv);
    if (random_opt->count() == 0 && file_opt->count() == 0) {
      throw CLI::ValidationError("give --random COUNT (with --size) or --instances FILE");
    }
    if (random_opt->count() > 0 && file_opt->count() > 0) {
      throw CLI::ValidationError("--random and --instances exclude each other");
    }
    if (random_opt->count() > 0 && size_opt->count() == 0) {
      throw CLI::ValidationError("--random needs --size");
    }
    if (walk_opt->count() > 0 && random_opt->count() == 0) {
      throw CLI::ValidationError("--walk needs --random COUNT (and --size)");
    }
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }

  std::vector<Algorithm> algorithms;
  {
    std::stringstream list(o.algorithms);
    for (std::string name; std::getline(list, name, ',');) {
      Algorithm a;
      if (!parseAlgorithm(name, &a)) {
        std::cerr << "amha tiles: unknown algorithm '" << name
                  << "' (known: amha, mha, ara, ana, wastar, astar)\n";
        return kExitUsage;
      }
      if (std::find(algorithms.begin(), algorithms.end(), a) == algorithms.end())
        algorithms.push_back(a);
    }
    if (algorithms.empty()) {
      std::cerr << "amha tiles: --algorithms is empty\n";
      return kExitUsage;
    }
  }
  for (Algorithm a : algorithms) {
    try {
      makePlanner(configFor(a, o));
    } catch (const std::invalid_argument& e) {
      std::cerr << "amha tiles: " << algorithmName(a) << ": " << e.what() << "\n";
      return kExitUsage;
    }
  }

  std::vector<tiles::Instance> instances;
  try {
    instances = o.instances_file.empty()
                    ? tiles::generateInstances(o.size, o.random, o.seed, o.walk)
                    : tiles::readInstances(o.instances_file, o.size);
  } catch (const tiles::InstanceError& e) {
    std::cerr << "amha tiles: " << e.what() << "\n";
    return kExitBadInstances;
  }
  if (!o.write_instances.empty()) {
    std::ostringstream comment;
    comment << "written by: amha tiles";
    for (int i = 1; i < argc; ++i) comment << " " << argv[i];
    try {
      tiles::writeInstances(o.write_instances, instances, comment.str());
    } catch (const std::exception& e) {
      std::cerr << "amha tiles: " << e.what() << "\n";
      return kExitOutput;
    }
  }

  const bool cpu_clock = o.clock == "cpu";
  const auto weights =
      tiles::randomTermWeights(static_cast<std::size_t>(o.heuristics), o.heuristic_seed);
  const std::size_t per_run_bytes =
      static_cast<std::size_t>(o.memory_limit_gb * double(1ull << 30) / o.jobs);
  // Between runs the pool keeps at most one run's cap: resident memory stays below
  // --memory-limit-gb plus that.
  if (!o.fresh_memory) keepFreedMemoryMapped(per_run_bytes);

  // Tasks in instance-major order: instance i runs all algorithms before instance i + 1.
  const std::size_t n_tasks = instances.size() * algorithms.size();
  std::vector<TilesRun> runs(n_tasks);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex io;
  std::string failure;
  const int n_inst = static_cast<int>(instances.size());
  auto worker = [&] {
    for (;;) {
      const std::size_t task = next.fetch_add(1);
      if (task >= n_tasks || failed) return;
      const std::size_t ii = task / algorithms.size();
      const Algorithm alg = algorithms[task % algorithms.size()];
      const tiles::Instance& inst = instances[ii];
      char tag[96];
      std::snprintf(tag, sizeof(tag), "[%*zu/%d] %s %-4s",
                    static_cast<int>(std::to_string(n_inst).size()), ii + 1, n_inst,
                    inst.id.c_str(), algorithmName(alg));
      auto problem = tiles::TilesProblem::create(inst.start, weights);
      auto planner = makePlanner(configFor(alg, o));
      TilesRun& run = runs[task];
      run.instance = inst.id;
      run.algorithm = alg;
      run.optimal = inst.optimal;
      SearchLimits limits;
      limits.time_limit_s = o.time_limit;
      if (o.max_expansions > 0) limits.max_expansions = o.max_expansions;
      limits.max_memory_bytes = per_run_bytes;
      const double cpu0 = threadCpuSeconds();
      SolutionCallback cb = [&](const Solution& s) {
        run.solution_cpu_s.push_back(threadCpuSeconds() - cpu0);
        if (o.quiet) return;
        std::lock_guard<std::mutex> lock(io);
        std::cerr << tag << "  solution " << s.iteration + 1 << ": cost " << s.cost << "  bound "
                  << fmtBound(s.nominal_bound) << " (certified " << fmtBound(s.certified_bound)
                  << ")  at " << fmtSeconds(cpu_clock ? run.solution_cpu_s.back() : s.elapsed_s)
                  << " s\n";
      };
      // On the CPU clock the search measures its budget on this thread's CPU time.
      if (cpu_clock) limits.clock = StopClock::kThreadCpu;
      run.result = planner->search(*problem, limits, cb);
      run.cpu_s = threadCpuSeconds() - cpu0;
      for (Solution& s : run.result.solutions) {
        const std::string err = verify(*problem, inst.start, s);
        if (!err.empty()) {
          std::lock_guard<std::mutex> lock(io);
          failure = std::string(algorithmName(alg)) + " on " + inst.id + ": " + err;
          failed = true;
        }
        s.path.clear();
        s.path.shrink_to_fit();
      }
      dropLateSolutions(run, o.time_limit, cpu_clock);
      if (!o.quiet) {
        const SearchResult& r = run.result;
        std::lock_guard<std::mutex> lock(io);
        std::cerr << tag << "  " << statusName(r.status) << ": ";
        if (r.hasSolution()) {
          std::cerr << r.solutions.size() << " solution(s), best cost " << r.best().cost
                    << " bound " << fmtBound(r.best().nominal_bound) << " (certified "
                    << fmtBound(r.best().certified_bound) << ")";
        } else {
          std::cerr << "no solution";
        }
        std::cerr << ", " << r.expansions << " expansions in " << fmtSeconds(r.elapsed_s)
                  << " s (CPU " << fmtSeconds(run.cpu_s) << " s), " << r.peak_states << " states, "
                  << (r.peak_memory_bytes >> 20) << " MiB\n";
      }
    }
  };
  std::vector<std::thread> pool;
  for (int j = 1; j < o.jobs; ++j) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (failed) {
    std::cerr << "amha tiles: internal error: a reported solution failed verification: " << failure
              << "\n";
    return kExitInternal;
  }

  const auto summary = summarize(runs, algorithms, cpu_clock);
  std::cout << instances.size() << " instance(s), board " << instances.front().start.size << "x"
            << instances.front().start.size << ", time limit " << o.time_limit << " s ("
            << (cpu_clock ? "CPU" : "wall") << " clock), " << o.heuristics
            << " inadmissible heuristic(s) (seed " << o.heuristic_seed << "), "
            << (o.schedule == QueueSchedule::kDts ? "DTS" : "round-robin") << " queue schedule\n"
            << reportText(runs, algorithms, cpu_clock);

  try {
    if (!o.json.empty()) {
      nlohmann::json jruns = nlohmann::json::array();
      for (const TilesRun& r : runs) {
        nlohmann::json j = runToJson(r.instance, r.algorithm, r.result,
                                     r.optimal ? std::optional<Cost>(*r.optimal) : std::nullopt);
        j["cpu_s"] = r.cpu_s;  // beyond the shared schema: CPU time of the searching thread
        j["solutions_after_limit"] = r.late_solutions;  // dropped: see dropLateSolutions
        for (std::size_t k = 0; k < r.solution_cpu_s.size() && k < j["solutions"].size(); ++k) {
          j["solutions"][k]["cpu_s"] = r.solution_cpu_s[k];
        }
        jruns.push_back(std::move(j));
      }
      nlohmann::json extra;
      std::ostringstream cmd;
      cmd << "amha tiles";
      for (int i = 1; i < argc; ++i) cmd << " " << argv[i];
      extra["command"] = cmd.str();
      nlohmann::json jw = nlohmann::json::array();
      for (const auto& w : weights) jw.push_back({{"md", w.md}, {"lc", w.lc}, {"mt", w.mt}});
      extra["settings"] = {
          {"size", instances.front().start.size},
          {"instances_file",
           o.instances_file.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.instances_file)},
          {"random", o.random},
          {"seed", o.seed},
          {"walk", o.walk},
          {"algorithms", o.algorithms},
          {"time_limit_s", o.time_limit},
          {"clock", o.clock},
          {"max_expansions",
           o.max_expansions > 0 ? nlohmann::json(o.max_expansions) : nlohmann::json(nullptr)},
          {"w1", o.w1},
          {"w2", o.w2},
          {"dw1", o.dw1},
          {"dw2", o.dw2},
          {"schedule", scheduleName(o.schedule)},
          {"ara_eps", o.eps},
          {"ara_deps", o.deps},
          {"wastar_weight", o.weight},
          {"memory_limit_gb", o.memory_limit_gb},
          {"jobs", o.jobs},
          {"fresh_memory", o.fresh_memory},
          {"hardware_threads", std::thread::hardware_concurrency()}};
      extra["heuristics"] = {{"anchor", "MD + LC"},
                             {"inadmissible", "round(md*MD + lc*LC + mt*MT)"},
                             {"count", o.heuristics},
                             {"seed", o.heuristic_seed},
                             {"weights", jw}};
      nlohmann::json jinst = nlohmann::json::array();
      for (const auto& inst : instances) {
        jinst.push_back(
            {{"id", inst.id},
             {"tiles", inst.start.tiles},
             {"optimal", inst.optimal ? nlohmann::json(*inst.optimal) : nlohmann::json(nullptr)}});
      }
      extra["instances"] = jinst;
      nlohmann::json jsum = nlohmann::json::array();
      for (const auto& s : summary) {
        jsum.push_back({{"algorithm", algorithmName(s.algorithm)},
                        {"runs", s.runs},
                        {"solved", s.solved},
                        {"success_rate", s.success_rate()},
                        {"t_initial_s", s.t_initial},
                        {"t_final_s", s.t_final},
                        {"eps_initial", s.eps_initial},
                        {"eps_final", s.eps_final},
                        {"certified_final", s.certified_final},
                        {"cost_final", s.cost_final},
                        {"expansions_per_s", s.expansions_per_s},
                        {"expansions_per_cpu_s", s.expansions_per_cpu_s},
                        {"bytes_per_state", s.bytes_per_state},
                        {"proven_optimal", s.proven_optimal},
                        {"with_known_optimal", s.with_known_optimal},
                        {"at_known_optimal", s.at_known_optimal},
                        {"below_known_optimal", s.below_known_optimal}});
      }
      for (auto& j : jsum) {
        for (auto it = j.begin(); it != j.end(); ++it) {
          if (it->is_number_float() && !std::isfinite(it->get<double>())) *it = nullptr;
        }
      }
      extra["summary"] = jsum;
      writeRunsJson(o.json, jruns, extra);
    }
    if (!o.markdown.empty()) {
      std::ofstream md(o.markdown);
      md << reportMarkdown(runs, algorithms, cpu_clock);
      if (!md) throw std::runtime_error("cannot write " + o.markdown);
    }
    if (!o.plot.empty() && !writeBoundPlot(o.plot, runs, algorithms, o.time_limit, cpu_clock,
                                           instances.front().start.size, instances.size())) {
      std::cerr << "amha tiles: no plot written: no algorithm solved half of the instances\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "amha tiles: " << e.what() << "\n";
    return kExitOutput;
  }
  const bool any = std::any_of(runs.begin(), runs.end(),
                               [](const TilesRun& r) { return r.result.hasSolution(); });
  return any ? kExitOk : kExitNoSolution;
}

}  // namespace

AMHA_REGISTER_COMMAND("tiles", "sliding-tile experiments (A-MHA*, MHA*, ARA*, ANA*)", runTiles);

}  // namespace cli
}  // namespace amha
