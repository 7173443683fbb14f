// The JSON schema shared by `amha tiles`, `amha plan` and the benchmarks:
// {"runs": [{"instance", "algorithm", "status", "optimal_cost", "expansions", "peak_states",
//            "peak_memory_bytes", "elapsed_s", "solutions": [{"elapsed_s", "cost", "bound",
//            "certified_bound", "expansions", "iteration", "w1", "w2"}, ...]}, ...]}
// Infinite bounds (ANA*'s before its first E) are written as null: JSON has no infinity.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "amha_planner/search/planner.h"

namespace amha {
namespace cli {

nlohmann::json solutionToJson(const Solution& s);

/// A run: how its search ended and its solutions, in order.
nlohmann::json runToJson(const std::string& instance, Algorithm algorithm,
                         const SearchSummary& summary,
                         const std::vector<const Solution*>& solutions,
                         std::optional<Cost> optimal_cost);
nlohmann::json runToJson(const std::string& instance, Algorithm algorithm,
                         const SearchResult& result, std::optional<Cost> optimal_cost);

/// The search settings a run used (`amha plan --json` writes them as the run's "search"), so
/// that a result file says what produced it.
nlohmann::json searchConfigToJson(const PlannerConfig& c);

/// Writes {"runs": runs, ...extra} to `path` (pretty-printed). Throws std::runtime_error.
void writeRunsJson(const std::string& path, const nlohmann::json& runs,
                   const nlohmann::json& extra = nlohmann::json::object());

}  // namespace cli
}  // namespace amha
