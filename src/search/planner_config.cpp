// Names and presets of the algorithms.
#include <stdexcept>
#include <string>

#include "amha_planner/search/planner.h"

namespace amha {

namespace {
struct NamedAlgorithm {
  Algorithm algorithm;
  const char* name;
};
constexpr NamedAlgorithm kAlgorithms[] = {
    {Algorithm::kAmhaStar, "amha"},        {Algorithm::kMhaStar, "mha"},
    {Algorithm::kAraStar, "ara"},          {Algorithm::kAnaStar, "ana"},
    {Algorithm::kWeightedAStar, "wastar"}, {Algorithm::kAStar, "astar"},
};
}  // namespace

const char* algorithmName(Algorithm a) {
  for (const auto& n : kAlgorithms) {
    if (n.algorithm == a) return n.name;
  }
  return "unknown";
}

bool parseAlgorithm(const std::string& name, Algorithm* out) {
  for (const auto& n : kAlgorithms) {
    if (name == n.name) {
      *out = n.algorithm;
      return true;
    }
  }
  return false;
}

const char* scheduleName(QueueSchedule s) { return s == QueueSchedule::kDts ? "dts" : "rr"; }

bool parseSchedule(const std::string& name, QueueSchedule* out) {
  if (name == "rr") {
    *out = QueueSchedule::kRoundRobin;
  } else if (name == "dts") {
    *out = QueueSchedule::kDts;
  } else {
    return false;
  }
  return true;
}

const char* weightScheduleName(WeightSchedule s) {
  return s == WeightSchedule::kCertified ? "certified" : "decrement";
}

bool parseWeightSchedule(const std::string& name, WeightSchedule* out) {
  if (name == "decrement") {
    *out = WeightSchedule::kDecrement;
  } else if (name == "certified") {
    *out = WeightSchedule::kCertified;
  } else {
    return false;
  }
  return true;
}

const char* statusName(SearchStatus s) {
  switch (s) {
    case SearchStatus::kProvenOptimal:
      return "proven_optimal";
    case SearchStatus::kBoundReached:
      return "bound_reached";
    case SearchStatus::kTimeLimit:
      return "time_limit";
    case SearchStatus::kExpansionLimit:
      return "expansion_limit";
    case SearchStatus::kMemoryLimit:
      return "memory_limit";
    case SearchStatus::kCancelled:
      return "cancelled";
    case SearchStatus::kNoSolution:
      return "no_solution";
  }
  return "unknown";
}

PlannerConfig defaultConfig(Algorithm algorithm) {
  PlannerConfig c;
  c.algorithm = algorithm;
  switch (algorithm) {
    case Algorithm::kAmhaStar:  // the paper's initial bound w1*w2 = 25, then 20.25, 16, ... 1
    case Algorithm::kMhaStar:
      c.w1 = 5.0;
      c.w2 = 5.0;
      c.dw1 = 0.5;
      c.dw2 = 0.5;
      break;
    case Algorithm::kAraStar:  // epsilon 25, 22, ..., 4, 1: as many iterations as A-MHA*'s
      c.w1 = 25.0;
      c.w2 = 1.0;
      c.dw1 = 3.0;
      c.dw2 = 0.0;
      break;
    case Algorithm::kWeightedAStar:
      c.w1 = 5.0;
      c.w2 = 1.0;
      c.dw1 = 0.0;
      c.dw2 = 0.0;
      break;
    case Algorithm::kAnaStar:
    case Algorithm::kAStar:
      c.w1 = 1.0;
      c.w2 = 1.0;
      c.dw1 = 0.0;
      c.dw2 = 0.0;
      break;
  }
  return c;
}

AlgorithmSpecs algorithmSpecs(Algorithm algorithm) {
  AlgorithmSpecs s;
  switch (algorithm) {
    case Algorithm::kAmhaStar:
      s.inadmissible_heuristics = s.w1 = s.w2 = s.dw1 = s.dw2 = s.queue_schedule = true;
      break;
    case Algorithm::kMhaStar:
      s.inadmissible_heuristics = s.w1 = s.w2 = s.queue_schedule = true;
      break;
    case Algorithm::kAraStar:
      s.w1 = s.dw1 = true;
      break;
    case Algorithm::kWeightedAStar:
      s.w1 = true;
      break;
    case Algorithm::kAnaStar:
    case Algorithm::kAStar:
      break;
  }
  return s;
}

void applyWeights(const WeightChoice& choice, PlannerConfig* config) {
  const AlgorithmSpecs reads = algorithmSpecs(config->algorithm);
  if (reads.w1 && choice.w1) config->w1 = *choice.w1;
  if (reads.w2 && choice.w2) config->w2 = *choice.w2;
  if (reads.dw1 && choice.dw1) config->dw1 = *choice.dw1;
  if (reads.dw2 && choice.dw2) config->dw2 = *choice.dw2;
}

}  // namespace amha
