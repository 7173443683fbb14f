#include "tiles_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>

namespace amha {
namespace cli {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  if (v.size() % 2 == 1) return v[m];
  if (!std::isfinite(v[m - 1]) || !std::isfinite(v[m])) return v[m];
  return 0.5 * (v[m - 1] + v[m]);
}

std::string num(double v, int precision = 3) {
  if (std::isnan(v)) return "-";
  if (std::isinf(v)) return "inf";
  char buf[32];
  if (std::fabs(v) >= 1e5) {
    std::snprintf(buf, sizeof(buf), "%.3g", v);
  } else {
    std::snprintf(buf, sizeof(buf), "%.*f", precision, v);
  }
  return buf;
}

std::string rate(double v) {
  char buf[32];
  if (v >= 1e6) {
    std::snprintf(buf, sizeof(buf), "%.2fM", v / 1e6);
  } else {
    std::snprintf(buf, sizeof(buf), "%.0fk", v / 1e3);
  }
  return buf;
}

// A mean of nominal bounds over the finite ones, noting how many were infinite.
std::string epsCell(double mean, int finite, int total) {
  if (total == 0) return "-";
  if (finite == 0) return "inf";
  std::string cell = num(mean, 2);
  if (finite < total) cell += " (" + std::to_string(total - finite) + " inf)";
  return cell;
}

const char* kHeader[] = {"algorithm",   "success %", "T_initial s", "T_final s",
                         "eps_initial", "eps_final", "cert_final",  "cost_final",
                         "exp/s",       "exp/cpu-s", "bytes/state", "states"};

std::vector<std::vector<std::string>> rows(const std::vector<AlgorithmSummary>& s) {
  std::vector<std::vector<std::string>> out;
  for (const AlgorithmSummary& a : s) {
    const bool any = a.solved > 0;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::string eps_init = epsCell(a.eps_initial, a.eps_initial_finite, a.solved);
    char success[48];
    std::snprintf(success, sizeof(success), "%.1f (%d/%d)", a.success_rate(), a.solved, a.runs);
    out.push_back({algorithmName(a.algorithm), success, num(any ? a.t_initial : nan),
                   num(any ? a.t_final : nan), eps_init,
                   epsCell(a.eps_final, a.eps_final_finite, a.solved),
                   num(any ? a.certified_final : nan, 2), num(any ? a.cost_final : nan, 1),
                   rate(a.expansions_per_s), rate(a.expansions_per_cpu_s),
                   num(a.bytes_per_state, 1), num(a.peak_states, 0)});
  }
  return out;
}

std::string textTable(const std::vector<std::string>& header,
                      const std::vector<std::vector<std::string>>& body) {
  std::vector<std::size_t> width;
  for (const auto& h : header) width.push_back(h.size());
  for (const auto& r : body) {
    for (std::size_t i = 0; i < r.size(); ++i) width[i] = std::max(width[i], r[i].size());
  }
  std::ostringstream out;
  auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (i > 0) out << "  ";
      const std::string pad(width[i] - cells[i].size(), ' ');
      out << (i == 0 ? cells[i] + pad : pad + cells[i]);
    }
    out << "\n";
  };
  line(header);
  for (const auto& r : body) line(r);
  return out.str();
}

std::string markdownTable(const std::vector<std::string>& header,
                          const std::vector<std::vector<std::string>>& body) {
  std::ostringstream out;
  out << "|";
  for (const auto& h : header) out << " " << h << " |";
  out << "\n|";
  for (std::size_t i = 0; i < header.size(); ++i) out << (i == 0 ? "---|" : "---:|");
  out << "\n";
  for (const auto& r : body) {
    out << "|";
    for (const auto& c : r) out << " " << c << " |";
    out << "\n";
  }
  return out.str();
}

}  // namespace

std::vector<AlgorithmSummary> summarize(const std::vector<TilesRun>& runs,
                                        const std::vector<Algorithm>& algorithms, bool cpu_clock) {
  std::vector<AlgorithmSummary> out;
  for (Algorithm alg : algorithms) {
    AlgorithmSummary a;
    a.algorithm = alg;
    double expansions = 0, seconds = 0, cpu = 0;
    std::vector<double> t_init, cert;
    for (const TilesRun& r : runs) {
      if (r.algorithm != alg) continue;
      const SearchResult& res = r.result;
      ++a.runs;
      expansions += static_cast<double>(res.expansions);
      seconds += res.elapsed_s;
      cpu += r.cpu_s;
      if (res.peak_states > 0) {
        a.bytes_per_state += static_cast<double>(res.peak_memory_bytes) / res.peak_states;
      }
      a.peak_states += static_cast<double>(res.peak_states);
      a.proven_optimal += res.status == SearchStatus::kProvenOptimal;
      if (!res.hasSolution()) continue;
      ++a.solved;
      const Solution& first = res.solutions.front();
      const Solution& last = res.solutions.back();
      const double t_first = r.solutionTime(0, cpu_clock);
      const double t_last = r.solutionTime(res.solutions.size() - 1, cpu_clock);
      a.t_initial += t_first;
      a.t_final += t_last;
      if (std::isfinite(first.nominal_bound)) {
        a.eps_initial += first.nominal_bound;
        ++a.eps_initial_finite;
      }
      if (std::isfinite(last.nominal_bound)) {
        a.eps_final += last.nominal_bound;
        ++a.eps_final_finite;
      }
      a.certified_final += last.certified_bound;
      a.cost_final += static_cast<double>(last.cost);
      t_init.push_back(t_first);
      if (r.optimal) {
        ++a.with_known_optimal;
        a.at_known_optimal += last.cost == *r.optimal;
        a.below_known_optimal += last.cost < *r.optimal;
      }
      cert.push_back(last.certified_bound);
    }
    if (a.runs > 0) {
      a.bytes_per_state /= a.runs;
      a.peak_states /= a.runs;
    }
    if (a.solved > 0) {
      a.t_initial /= a.solved;
      a.t_final /= a.solved;
      a.eps_final = a.eps_final_finite > 0 ? a.eps_final / a.eps_final_finite
                                           : std::numeric_limits<double>::infinity();
      a.certified_final /= a.solved;
      a.cost_final /= a.solved;
      a.eps_initial = a.eps_initial_finite > 0 ? a.eps_initial / a.eps_initial_finite
                                               : std::numeric_limits<double>::infinity();
    }
    a.median_t_initial = median(t_init);
    a.median_certified_final = median(cert);
    a.expansions_per_s = seconds > 0 ? expansions / seconds : 0.0;
    a.expansions_per_cpu_s = cpu > 0 ? expansions / cpu : 0.0;
    out.push_back(a);
  }
  return out;
}

std::string formatTable(const std::vector<AlgorithmSummary>& s) {
  return textTable({std::begin(kHeader), std::end(kHeader)}, rows(s));
}

std::string formatOptimalityCheck(const std::vector<AlgorithmSummary>& s) {
  std::ostringstream out;
  for (const AlgorithmSummary& a : s) {
    if (a.with_known_optimal == 0) continue;
    out << algorithmName(a.algorithm) << ": final cost = the known optimal length on "
        << a.at_known_optimal << " of " << a.with_known_optimal
        << " solved runs with a known optimum (" << a.proven_optimal << " runs proved optimality)";
    if (a.below_known_optimal > 0) {
      out << "; BELOW the known optimum on " << a.below_known_optimal
          << " (the file's optimal lengths are wrong)";
    }
    out << "\n";
  }
  return out.str();
}

std::string formatMarkdownTable(const std::vector<AlgorithmSummary>& s) {
  return markdownTable({std::begin(kHeader), std::end(kHeader)}, rows(s));
}

std::vector<CommonSummary> summarizeCommon(const std::vector<TilesRun>& runs,
                                           const std::vector<Algorithm>& algorithms, bool cpu_clock,
                                           std::size_t* n_common, std::size_t* n_instances) {
  // Instances (in first-seen order) and how many of the algorithms solved each.
  std::vector<std::string> order;
  std::map<std::string, std::size_t> solved_by;
  for (const TilesRun& r : runs) {
    if (!solved_by.count(r.instance)) order.push_back(r.instance);
    solved_by[r.instance] += r.result.hasSolution() ? 1 : 0;
  }
  *n_instances = order.size();
  *n_common = 0;
  for (const auto& kv : solved_by) *n_common += kv.second == algorithms.size();
  std::vector<CommonSummary> out;
  for (Algorithm alg : algorithms) {
    CommonSummary c;
    c.algorithm = alg;
    std::vector<double> t_init;
    for (const TilesRun& r : runs) {
      if (r.algorithm != alg || solved_by[r.instance] != algorithms.size()) continue;
      const auto& sols = r.result.solutions;
      t_init.push_back(r.solutionTime(0, cpu_clock));
      c.t_final += r.solutionTime(sols.size() - 1, cpu_clock);
      c.cost_final += static_cast<double>(sols.back().cost);
      c.certified_final += sols.back().certified_bound;
      if (std::isfinite(sols.back().nominal_bound)) {
        c.eps_final += sols.back().nominal_bound;
        ++c.eps_final_finite;
      }
    }
    const double n = static_cast<double>(t_init.size());
    if (n > 0) {
      for (double t : t_init) c.t_initial += t;
      c.t_initial /= n;
      c.t_final /= n;
      c.cost_final /= n;
      c.certified_final /= n;
      c.eps_final = c.eps_final_finite > 0 ? c.eps_final / c.eps_final_finite
                                           : std::numeric_limits<double>::infinity();
      c.n = static_cast<int>(n);
    }
    c.median_t_initial = median(t_init);
    out.push_back(c);
  }
  return out;
}

namespace {

const char* kCommonHeader[] = {"algorithm", "T_initial s", "median T_initial s", "T_final s",
                               "eps_final", "cert_final",  "cost_final"};

std::vector<std::vector<std::string>> commonRows(const std::vector<CommonSummary>& s) {
  std::vector<std::vector<std::string>> out;
  for (const CommonSummary& c : s) {
    out.push_back({algorithmName(c.algorithm), num(c.t_initial), num(c.median_t_initial),
                   num(c.t_final), epsCell(c.eps_final, c.eps_final_finite, c.n),
                   num(c.certified_final, 2), num(c.cost_final, 1)});
  }
  return out;
}

const char* kLegend =
    "Means over each algorithm's solved runs (times on the %s clock). eps = nominal bound, "
    "cert = certified bound (cost / proven lower bound), exp/s per wall-clock second, exp/cpu-s "
    "per CPU second of the searching thread, bytes/state = peak memory (search + domain) / "
    "stored states.";

std::string legend(bool cpu_clock) {
  char buf[512];
  std::snprintf(buf, sizeof(buf), kLegend, cpu_clock ? "CPU" : "wall");
  return buf;
}

std::string lateNote(const std::vector<TilesRun>& runs) {
  int late = 0, late_runs = 0;
  for (const TilesRun& r : runs) {
    late += r.late_solutions;
    late_runs += r.late_solutions > 0;
  }
  if (late == 0) return "";
  return std::to_string(late) + " solution(s) of " + std::to_string(late_runs) +
         " run(s) came after the time limit (a step that does not check the clock, such as "
         "growing a table, was finishing) and are not counted.\n";
}

}  // namespace

void dropLateSolutions(TilesRun& run, double time_limit, bool cpu_clock) {
  std::size_t keep = 0;
  while (keep < run.result.solutions.size() && run.solutionTime(keep, cpu_clock) <= time_limit)
    ++keep;
  run.late_solutions += static_cast<int>(run.result.solutions.size() - keep);
  run.result.solutions.resize(keep);
  if (run.solution_cpu_s.size() > keep) run.solution_cpu_s.resize(keep);
}

std::string reportText(const std::vector<TilesRun>& runs, const std::vector<Algorithm>& algorithms,
                       bool cpu_clock) {
  const auto summary = summarize(runs, algorithms, cpu_clock);
  std::size_t n_common = 0, n_inst = 0;
  const auto common = summarizeCommon(runs, algorithms, cpu_clock, &n_common, &n_inst);
  std::ostringstream out;
  out << formatTable(summary) << legend(cpu_clock) << "\n" << lateNote(runs);
  if (algorithms.size() > 1) {
    out << "\non the " << n_common << " of " << n_inst << " instances every algorithm solved:\n";
    if (n_common > 0)
      out << textTable({std::begin(kCommonHeader), std::end(kCommonHeader)}, commonRows(common));
  }
  out << formatOptimalityCheck(summary);
  return out.str();
}

std::string reportMarkdown(const std::vector<TilesRun>& runs,
                           const std::vector<Algorithm>& algorithms, bool cpu_clock) {
  const auto summary = summarize(runs, algorithms, cpu_clock);
  std::size_t n_common = 0, n_inst = 0;
  const auto common = summarizeCommon(runs, algorithms, cpu_clock, &n_common, &n_inst);
  std::ostringstream out;
  out << formatMarkdownTable(summary) << "\n" << legend(cpu_clock) << "\n";
  const std::string late = lateNote(runs);
  if (!late.empty()) out << "\n" << late;
  if (algorithms.size() > 1) {
    out << "\nOn the " << n_common << " of " << n_inst << " instances every algorithm solved:\n\n";
    if (n_common > 0) {
      out << markdownTable({std::begin(kCommonHeader), std::end(kCommonHeader)},
                           commonRows(common));
    }
  }
  const std::string check = formatOptimalityCheck(summary);
  if (!check.empty()) {
    out << "\n";
    std::istringstream lines(check);
    for (std::string l; std::getline(lines, l);) out << "- " << l << "\n";
  }
  return out.str();
}

bool writeBoundPlot(const std::string& path, const std::vector<TilesRun>& runs,
                    const std::vector<Algorithm>& algorithms, double time_limit, bool cpu_clock,
                    int board_size, std::size_t n_instances) {
  const auto curves = medianBoundCurves(runs, algorithms, time_limit, cpu_clock);
  const bool drawable = std::any_of(curves.begin(), curves.end(), [](const PlotSeries& c) {
    return std::any_of(c.y.begin(), c.y.end(), [](double y) { return std::isfinite(y); });
  });
  if (!drawable) return false;
  PlotOptions po;
  po.title = std::to_string(board_size * board_size - 1) +
             "-puzzle: median certified bound vs time (" + std::to_string(n_instances) +
             " instances)";
  po.x_label = cpu_clock ? "CPU time [s] (log)" : "time [s] (log)";
  po.y_label = "median certified bound";
  po.log_x = true;
  writeLinePlot(path, curves, po);
  return true;
}

std::vector<PlotSeries> medianBoundCurves(const std::vector<TilesRun>& runs,
                                          const std::vector<Algorithm>& algorithms,
                                          double time_limit, bool cpu_clock) {
  const double inf = std::numeric_limits<double>::infinity();
  // Log-spaced grid from 1 ms (or limit / 10^4) to the time limit.
  const double t0 = std::min(1e-3, time_limit / 1e4);
  std::vector<double> grid;
  for (int i = 0; i <= 400; ++i) grid.push_back(t0 * std::pow(time_limit / t0, i / 400.0));
  std::vector<PlotSeries> out;
  for (Algorithm alg : algorithms) {
    PlotSeries s;
    s.label = algorithmName(alg);
    double last = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> best;
    for (double t : grid) {
      best.clear();
      for (const TilesRun& r : runs) {
        if (r.algorithm != alg) continue;
        double b = inf;
        for (std::size_t k = 0; k < r.result.solutions.size(); ++k) {
          if (r.solutionTime(k, cpu_clock) <= t)
            b = std::min(b, r.result.solutions[k].certified_bound);
        }
        best.push_back(b);
      }
      if (best.empty()) break;
      const double m = median(best);
      if (!(m == last) || t == grid.back()) {
        s.x.push_back(t);
        s.y.push_back(m);
        last = m;
      }
    }
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace cli
}  // namespace amha
