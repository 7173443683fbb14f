// What every algorithm takes (limits, parameters) and gives back (solutions, a final status).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "amha_planner/search/problem.h"
#include "amha_planner/search/stop_condition.h"
#include "amha_planner/search/types.h"

namespace amha {

enum class Algorithm { kAmhaStar, kMhaStar, kAraStar, kAnaStar, kWeightedAStar, kAStar };

/// "amha", "mha", "ara", "ana", "wastar", "astar".
const char* algorithmName(Algorithm a);
/// Parses the names above; returns false for anything else.
bool parseAlgorithm(const std::string& name, Algorithm* out);

/// Which inadmissible queue A-MHA*/MHA* tries next.
///  - kRoundRobin: 1, 2, ..., N, 1, ... (the paper's Algorithm 1);
///  - kDts: Dynamic Thompson Sampling (Phillips et al., IJCAI 2015): each queue is an arm of a
///    bandit whose reward is "this expansion lowered the smallest h_i ever queued in OPEN_i";
///    the next queue is the one with the largest draw from its Beta posterior. Queues that
///    make progress get more expansions. The bound w1*w2 does not depend on the order (the
///    anchor test of line 19 is unchanged), only how soon solutions come.
enum class QueueSchedule { kRoundRobin, kDts };
/// "rr", "dts".
const char* scheduleName(QueueSchedule s);
bool parseSchedule(const std::string& name, QueueSchedule* out);

/// How the anytime algorithms (A-MHA*, ARA*) choose the next iteration's weights.
///  - kDecrement: the paper's Algorithm 1 (line 35): w1 -= dw1, w2 -= dw2, down to 1. Iterations
///    whose bound w1 * w2 is not below the last solution's certified bound cannot improve on the
///    guarantee already proven; they are skipped (the weights jump over them), which changes
///    no path, only how many identical solutions are reported.
///  - kCertified: from the certified bound c of the last solution, the next bound is
///    B = 1 + certified_ratio x (c - 1) (1 if that is within final_gap of 1; a ratio of 0 goes
///    straight to the proof), below c so that the iteration must expand, with
///    w1 = B^certified_split and w2 = B / w1 (never above their current values). With
///    publish_within_iterations, what an iteration finds is published as it comes.
enum class WeightSchedule { kDecrement, kCertified };
/// "decrement", "certified".
const char* weightScheduleName(WeightSchedule s);
bool parseWeightSchedule(const std::string& name, WeightSchedule* out);

enum class SearchStatus {
  kProvenOptimal,   ///< the last solution is optimal (bound 1 reached or certified)
  kBoundReached,    ///< a one-shot algorithm (MHA*, weighted A*) met its requested bound
  kTimeLimit,       ///< wall-clock budget used up (a solution may exist)
  kExpansionLimit,  ///< expansion cap hit
  kMemoryLimit,     ///< state or memory cap hit
  kCancelled,       ///< the cancel flag was set
  kNoSolution,      ///< the search space was exhausted: the goal is unreachable
};
const char* statusName(SearchStatus s);

/// Limits every search honours. The time budget is measured on `clock` (the wall by default) and,
/// with the cancel flag, checked often enough to be honoured within a few milliseconds.
struct SearchLimits {
  double time_limit_s = std::numeric_limits<double>::infinity();
  std::uint64_t max_expansions = std::numeric_limits<std::uint64_t>::max();
  std::size_t max_states = std::numeric_limits<std::size_t>::max();
  std::size_t max_memory_bytes = std::numeric_limits<std::size_t>::max();
  const std::atomic<bool>* cancel = nullptr;  ///< set to true from any thread to stop
  /// The clock of time_limit_s: the wall, or the CPU time of the thread that runs the search
  /// (fair timings on a shared machine; the search's reported times stay on the wall clock).
  StopClock clock = StopClock::kWall;
};

/// The largest weight (w1, w2, epsilon) and weight decrement a planner accepts. Heuristic values
/// are below 2^32, so w x h stays below 4.3e15: under 2^53 (keys, which are doubles, hold such
/// integers exactly) and 500 times below the infinite-cost sentinel kInfiniteCost (2.3e18).
/// Weights far below it already make the search greedy (docs/search.md, "Weights").
constexpr double kMaxWeight = 1e6;

/// Parameters. A-MHA* uses all of them; the others read what applies:
///  - MHA*: w1, w2 (one ImprovePath, no schedule);
///  - ARA*: w1 is epsilon, dw1 its decrement (w2 = 1, no inadmissible heuristics);
///  - weighted A*: w1 is the weight; A*: none.
struct PlannerConfig {
  Algorithm algorithm = Algorithm::kAmhaStar;
  double w1 = 5.0;   ///< anchor inflation (initial)
  double w2 = 5.0;   ///< inadmissible-vs-anchor factor (initial); bound is w1 * w2 = 25
  double dw1 = 0.5;  ///< decrement of w1 per iteration
  double dw2 = 0.5;  ///< decrement of w2 per iteration
  /// How the weights fall between iterations (kDecrement uses dw1, dw2; kCertified the three
  /// parameters below).
  WeightSchedule weight_schedule = WeightSchedule::kDecrement;
  double certified_ratio = 0.5;  ///< in [0, 1): the share of c - 1 the next bound keeps
  double certified_split = 1.0;  ///< in [0, 1]: the exponent of the bound given to w1
  double final_gap = 0.002;      ///< >= 0: below 1 + this, the next iteration is the proof
  /// Publish a cheaper path as soon as an iteration finds it, not only when the iteration ends
  /// (A-MHA*, ARA*). Its bounds are those proven so far: the last finished iteration's w1 w2
  /// (infinite before the first) and cost / the best lower bound proven so far. Off: the
  /// paper's Algorithm 1 exactly, one solution per ImprovePath.
  bool publish_within_iterations = false;
  /// A-MHA*, ARA*: if the first iteration has expanded this many states without reaching the
  /// goal (0: never), it gives way to an iteration with w1 = stall_w1 (if larger), which finds a
  /// first path sooner on the queries where a small w1 crawls; the schedule then goes on from
  /// there (the weights may rise once: each iteration's bound is proven for its own weights).
  std::uint64_t stall_expansions = 0;
  double stall_w1 = 5.0;
  /// A rung between the two (0: none): the stalled first iteration goes on at stall_mid_w1 (if
  /// above its w1 and below stall_w1) for stall_mid_expansions more expansions, and only then,
  /// still without a path, at stall_w1. A small step up often suffices where the first w1
  /// crawls, and its path is closer to the optimum than stall_w1's.
  double stall_mid_w1 = 0.0;
  std::uint64_t stall_mid_expansions = 0;
  /// A-MHA*: the last iteration (w1 = w2 = 1, the proof) keeps and computes the anchor alone, as
  /// A* on h0. At w2 = 1 an inadmissible queue may expand only states whose key is at most
  /// OPEN_0's minimum, so the proof expands nearly the same states either way; without the other
  /// queues it computes, queues and tests none of their heuristics. Off: Algorithm 1 as written.
  bool proof_anchor_only = false;
  /// Use at most this many inadmissible heuristics of the problem (all by default).
  std::size_t max_inadmissible = std::numeric_limits<std::size_t>::max();
  /// Order in which the inadmissible queues are tried (A-MHA*, MHA*).
  QueueSchedule schedule = QueueSchedule::kRoundRobin;
  /// Seed of the DTS draws: a search is reproducible from its inputs and this seed.
  std::uint64_t schedule_seed = 1;
  /// Stop as soon as the certified bound proves the current solution optimal, instead of
  /// running the remaining iterations down to w = 1.
  bool stop_when_certified_optimal = true;
  /// Check the algorithm's queue invariants at every iteration (slow; for tests).
  bool check_invariants = false;
};

/// One improved solution, reported as soon as it is found.
struct Solution {
  std::vector<StateId> path;  ///< start ... goal
  /// Edge::label of each edge of path (path.size() - 1 of them; kNoLabel for unlabelled ones).
  std::vector<std::uint32_t> edge_labels;
  Cost cost = kInfiniteCost;  ///< the sum of the path's edge costs
  /// The bound the algorithm guarantees by construction: w1*w2 (A-MHA*, MHA*), epsilon (ARA*,
  /// weighted A*), ANA*'s E (infinite before its first bound), 1 for A*.
  double nominal_bound = std::numeric_limits<double>::infinity();
  /// cost / (a proven lower bound on the optimal cost), clamped to [1, nominal_bound].
  double certified_bound = std::numeric_limits<double>::infinity();
  double elapsed_s = 0.0;
  std::uint64_t expansions = 0;
  int iteration = 0;  ///< 0-based ImprovePath iteration that produced it
  double w1 = 1.0;    ///< weights in force (epsilon in w1 for ARA*/weighted A*; 1 for A*/ANA*)
  double w2 = 1.0;
};

using SolutionCallback = std::function<void(const Solution&)>;

/// How a search ended and what it cost.
struct SearchSummary {
  SearchStatus status = SearchStatus::kNoSolution;
  std::uint64_t expansions = 0;
  std::size_t peak_states = 0;        ///< states generated (with search data) at the end
  std::size_t peak_memory_bytes = 0;  ///< search arrays + domain, as counted for the cap
  double elapsed_s = 0.0;
  /// With kNoSolution: true when the domain proved it from the goal's side
  /// (SearchProblem::goalUnreachable: the states that reach the goal ran out, the start none of
  /// them), false when the search ran out of states from the start.
  bool goal_side_proof = false;
};

struct SearchResult : SearchSummary {
  std::vector<Solution> solutions;  ///< every reported solution, in order; back() is the best

  bool hasSolution() const { return !solutions.empty(); }
  const Solution& best() const { return solutions.back(); }
};

/// An algorithm instance. A planner may be reused for several searches (its buffers are kept).
class Planner {
 public:
  virtual ~Planner() = default;
  virtual SearchResult search(SearchProblem& problem, const SearchLimits& limits,
                              const SolutionCallback& on_solution = {}) = 0;
};

/// Makes the planner for config.algorithm. Throws std::invalid_argument for weights outside
/// [1, kMaxWeight] (NaN included), decrements outside [0, kMaxWeight], or certified-schedule
/// parameters outside their ranges.
std::unique_ptr<Planner> makePlanner(const PlannerConfig& config);

/// Presets that reproduce the paper's settings for `algorithm` (documented in the README).
PlannerConfig defaultConfig(Algorithm algorithm);

/// What an algorithm reads of a PlannerConfig (in the spirit of OMPL's PlannerSpecs), so that
/// domains and front ends ask instead of listing algorithms.
struct AlgorithmSpecs {
  bool inadmissible_heuristics = false;  ///< uses h_1..h_N (A-MHA*, MHA*)
  bool w1 = false;              ///< w1: A-MHA*'s and MHA*'s, ARA*'s epsilon, weighted A*'s weight
  bool w2 = false;              ///< A-MHA*, MHA*
  bool dw1 = false;             ///< A-MHA*, ARA*
  bool dw2 = false;             ///< A-MHA*
  bool queue_schedule = false;  ///< the order of the inadmissible queues (A-MHA*, MHA*)
};
AlgorithmSpecs algorithmSpecs(Algorithm algorithm);

/// Weights a user chose (from options, parameters or a request); an empty one keeps the
/// configuration's.
struct WeightChoice {
  std::optional<double> w1, w2, dw1, dw2;
};
/// Sets in `config` those chosen weights that config->algorithm reads (algorithmSpecs); the
/// others are ignored. Checked later by makePlanner.
void applyWeights(const WeightChoice& choice, PlannerConfig* config);

}  // namespace amha
