// Summaries of `amha tiles` runs: the paper's table (success rate, T_initial, T_final,
// eps_initial, eps_final) plus certified bound, final cost, speed and memory per algorithm,
// and the median certified bound vs time curves for the plot.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "amha_planner/search/planner.h"
#include "line_plot.h"

namespace amha {
namespace cli {

struct TilesRun {
  std::string instance;
  Algorithm algorithm = Algorithm::kAmhaStar;
  std::optional<int> optimal;
  SearchResult result;  // solution paths may have been dropped after verification
  double cpu_s = 0;     // CPU time of the searching thread (wall time is result.elapsed_s)
  std::vector<double> solution_cpu_s;  // the same clock at each solution
  int late_solutions = 0;  // solutions reported after the time limit, dropped (see below)

  /// Time of solution k on the chosen clock.
  double solutionTime(std::size_t k, bool cpu_clock) const {
    return cpu_clock ? solution_cpu_s.at(k) : result.solutions.at(k).elapsed_s;
  }
};

/// Drops the solutions reported after `time_limit` (on the chosen clock) and counts them in
/// `late_solutions`. A search checks the clock between expansions but not inside a step such
/// as growing a table of millions of states, so under load it can finish a solution after its
/// limit; such a run did not solve the instance within the limit.
void dropLateSolutions(TilesRun& run, double time_limit, bool cpu_clock);

/// Means are over the runs that found a solution ("solved"); speed and memory over all runs.
/// Times (T_initial, T_final, the plot's axis) are on the CPU clock of the searching thread if
/// `cpu_clock`, else wall-clock.
struct AlgorithmSummary {
  Algorithm algorithm = Algorithm::kAmhaStar;
  int runs = 0, solved = 0;
  double t_initial = 0, t_final = 0;      ///< mean seconds to the first / last solution
  double eps_initial = 0, eps_final = 0;  ///< mean nominal bound of the first / last solution
  int eps_initial_finite = 0;             ///< solved runs whose first nominal bound is finite
  int eps_final_finite = 0;               ///< ... whose last nominal bound is finite
                                          ///< (eps means are over the finite ones; ANA*'s E
                                          ///< is infinite until its second solution)
  double certified_final = 0;             ///< mean certified bound of the last solution
  double cost_final = 0;                  ///< mean cost of the last solution
  double median_t_initial = 0, median_certified_final = 0;
  double expansions_per_s = 0;      ///< total expansions / total search (wall) time
  double expansions_per_cpu_s = 0;  ///< total expansions / total CPU time: the speed
                                    ///< on an idle core, when the machine is shared
  double bytes_per_state = 0;       ///< mean of peak_memory_bytes / peak_states
  double peak_states = 0;           ///< mean states stored at the end of a run
  int proven_optimal = 0;           ///< runs that ended proving optimality
  int with_known_optimal = 0;       ///< solved runs whose instance has a known optimum
  int at_known_optimal = 0;         ///< ... whose final cost equals it
  int below_known_optimal = 0;      ///< ... whose final cost is below it (a wrong file)
  double success_rate() const { return runs > 0 ? 100.0 * solved / runs : 0.0; }
};

std::vector<AlgorithmSummary> summarize(const std::vector<TilesRun>& runs,
                                        const std::vector<Algorithm>& algorithms, bool cpu_clock);

/// Aligned plain-text table (for the terminal).
std::string formatTable(const std::vector<AlgorithmSummary>& s);
/// Lines comparing final costs with the instances' known optimal lengths ("" if none known).
std::string formatOptimalityCheck(const std::vector<AlgorithmSummary>& s);
/// The same as a Markdown table.
std::string formatMarkdownTable(const std::vector<AlgorithmSummary>& s);

/// Means over the instances that every algorithm solved, so that costs and bounds compare
/// like with like.
struct CommonSummary {
  Algorithm algorithm = Algorithm::kAmhaStar;
  double t_initial = 0, median_t_initial = 0, t_final = 0;
  double cost_final = 0, certified_final = 0, eps_final = 0;
  int n = 0, eps_final_finite = 0;
};
std::vector<CommonSummary> summarizeCommon(const std::vector<TilesRun>& runs,
                                           const std::vector<Algorithm>& algorithms, bool cpu_clock,
                                           std::size_t* n_common, std::size_t* n_instances);

/// The whole report, as the terminal text or as Markdown: the main table, the legend, the
/// like-with-like table and the checks against known optimal lengths.
std::string reportText(const std::vector<TilesRun>& runs, const std::vector<Algorithm>& algorithms,
                       bool cpu_clock);
std::string reportMarkdown(const std::vector<TilesRun>& runs,
                           const std::vector<Algorithm>& algorithms, bool cpu_clock);

/// Writes the median-bound plot; false (and nothing written) if no curve has a finite point.
/// Throws std::runtime_error if the file cannot be written.
bool writeBoundPlot(const std::string& path, const std::vector<TilesRun>& runs,
                    const std::vector<Algorithm>& algorithms, double time_limit, bool cpu_clock,
                    int board_size, std::size_t n_instances);

/// Per algorithm: at each time t (log grid up to time_limit), the median over instances of the
/// best certified bound found by t (infinite until half of the instances have a solution).
/// Points are emitted where the median changes, plus one at the time limit.
std::vector<PlotSeries> medianBoundCurves(const std::vector<TilesRun>& runs,
                                          const std::vector<Algorithm>& algorithms,
                                          double time_limit, bool cpu_clock);

}  // namespace cli
}  // namespace amha
