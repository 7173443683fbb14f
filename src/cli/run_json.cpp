#include "run_json.h"

#include <cmath>
#include <fstream>
#include <stdexcept>

namespace amha {
namespace cli {

namespace {
nlohmann::json finiteOrNull(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}
}  // namespace

nlohmann::json solutionToJson(const Solution& s) {
  return {{"elapsed_s", s.elapsed_s},
          {"cost", s.cost},
          {"bound", finiteOrNull(s.nominal_bound)},
          {"certified_bound", finiteOrNull(s.certified_bound)},
          {"expansions", s.expansions},
          {"iteration", s.iteration},
          {"w1", s.w1},
          {"w2", s.w2}};
}

nlohmann::json runToJson(const std::string& instance, Algorithm algorithm,
                         const SearchResult& result, std::optional<Cost> optimal_cost) {
  std::vector<const Solution*> solutions;
  for (const Solution& s : result.solutions) solutions.push_back(&s);
  return runToJson(instance, algorithm, result, solutions, optimal_cost);
}

nlohmann::json runToJson(const std::string& instance, Algorithm algorithm,
                         const SearchSummary& result, const std::vector<const Solution*>& solutions,
                         std::optional<Cost> optimal_cost) {
  nlohmann::json sols = nlohmann::json::array();
  for (const Solution* s : solutions) sols.push_back(solutionToJson(*s));
  return {{"instance", instance},
          {"algorithm", algorithmName(algorithm)},
          {"status", statusName(result.status)},
          {"optimal_cost", optimal_cost ? nlohmann::json(*optimal_cost) : nlohmann::json(nullptr)},
          {"expansions", result.expansions},
          {"peak_states", result.peak_states},
          {"peak_memory_bytes", result.peak_memory_bytes},
          {"elapsed_s", result.elapsed_s},
          {"solutions", sols}};
}

nlohmann::json searchConfigToJson(const PlannerConfig& c) {
  return {{"w1", c.w1},
          {"w2", c.w2},
          {"dw1", c.dw1},
          {"dw2", c.dw2},
          {"weight_schedule", weightScheduleName(c.weight_schedule)},
          {"certified_ratio", c.certified_ratio},
          {"certified_split", c.certified_split},
          {"final_gap", c.final_gap},
          {"publish_within_iterations", c.publish_within_iterations},
          {"stall_expansions", c.stall_expansions},
          {"stall_w1", c.stall_w1},
          {"stall_mid_w1", c.stall_mid_w1},
          {"stall_mid_expansions", c.stall_mid_expansions},
          {"proof_anchor_only", c.proof_anchor_only},
          {"queue_schedule", scheduleName(c.schedule)}};
}

void writeRunsJson(const std::string& path, const nlohmann::json& runs,
                   const nlohmann::json& extra) {
  nlohmann::json doc = extra.is_object() ? extra : nlohmann::json::object();
  doc["runs"] = runs;
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << doc.dump(2) << "\n";
  if (!out) throw std::runtime_error("error writing " + path);
}

}  // namespace cli
}  // namespace amha
