// Maps an Algorithm and its parameters onto the engines.
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "amha_planner/search/planner.h"
#include "ana_star.h"
#include "mha_engine.h"

namespace amha {
namespace {

class MhaPlanner : public Planner {
 public:
  explicit MhaPlanner(const detail::MhaEngineOptions& o) : engine_(o) {}
  SearchResult search(SearchProblem& problem, const SearchLimits& limits,
                      const SolutionCallback& cb) override {
    return engine_.run(problem, limits, cb);
  }

 private:
  detail::MhaEngine engine_;
};

class AnaPlanner : public Planner {
 public:
  SearchResult search(SearchProblem& problem, const SearchLimits& limits,
                      const SolutionCallback& cb) override {
    return engine_.run(problem, limits, cb);
  }

 private:
  detail::AnaStar engine_;
};

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
// NaN fails both comparisons, so it is refused with the infinities.
void checkRange(double v, double lo, const char* name) {
  if (!(v >= lo && v <= kMaxWeight)) {
    throw std::invalid_argument(std::string(name) + " must be a finite number in [" + num(lo) +
                                ", " + num(kMaxWeight) + "], got " + num(v));
  }
}
void checkWeight(double w, const char* name) { checkRange(w, 1.0, name); }
void checkDecrement(double d, const char* name) { checkRange(d, 0.0, name); }

}  // namespace

std::unique_ptr<Planner> makePlanner(const PlannerConfig& c) {
  detail::MhaEngineOptions o;
  o.stop_when_certified_optimal = c.stop_when_certified_optimal;
  o.check_invariants = c.check_invariants;
  o.schedule = c.schedule;
  o.schedule_seed = c.schedule_seed;
  o.dw1 = o.dw2 = 0.0;
  o.w1 = o.w2 = 1.0;
  o.weight_schedule = c.weight_schedule;
  o.certified_ratio = c.certified_ratio;
  o.certified_split = c.certified_split;
  o.final_gap = c.final_gap;
  o.publish_improvements = c.publish_within_iterations;
  o.stall_expansions = c.stall_expansions;
  o.stall_w1 = c.stall_w1;
  o.stall_mid_w1 = c.stall_mid_w1;
  o.stall_mid_expansions = c.stall_mid_expansions;
  o.proof_anchor_only = c.proof_anchor_only;
  if (c.stall_expansions > 0) checkWeight(c.stall_w1, "stall_w1");
  if (c.stall_expansions > 0 && c.stall_mid_w1 != 0.0) checkWeight(c.stall_mid_w1, "stall_mid_w1");
  const bool certified = c.weight_schedule == WeightSchedule::kCertified;
  if (certified) {
    if (!(c.certified_ratio >= 0.0 && c.certified_ratio < 1.0)) {
      throw std::invalid_argument("certified_ratio must be in [0, 1), got " +
                                  num(c.certified_ratio));
    }
    if (!(c.certified_split >= 0.0 && c.certified_split <= 1.0)) {
      throw std::invalid_argument("certified_split must be in [0, 1], got " +
                                  num(c.certified_split));
    }
    if (!(c.final_gap >= 0.0 && c.final_gap < 1e6)) {
      throw std::invalid_argument("final_gap must be a number in [0, 1e6), got " +
                                  num(c.final_gap));
    }
  }
  o.anytime = false;
  o.max_inadmissible = 0;
  switch (c.algorithm) {
    case Algorithm::kAnaStar:
      return std::make_unique<AnaPlanner>();
    case Algorithm::kAmhaStar:
      checkWeight(c.w1, "w1");
      checkWeight(c.w2, "w2");
      checkDecrement(c.dw1, "dw1");
      checkDecrement(c.dw2, "dw2");
      if (!certified && ((c.w1 > 1.0 && c.dw1 <= 0.0) || (c.w2 > 1.0 && c.dw2 <= 0.0))) {
        throw std::invalid_argument(
            "A-MHA* needs dw1 > 0 (if w1 > 1) and dw2 > 0 (if w2 > 1) to reach bound 1");
      }
      o.w1 = c.w1;
      o.w2 = c.w2;
      o.dw1 = c.dw1;
      o.dw2 = c.dw2;
      o.anytime = true;
      o.max_inadmissible = c.max_inadmissible;
      break;
    case Algorithm::kMhaStar:
      checkWeight(c.w1, "w1");
      checkWeight(c.w2, "w2");
      o.w1 = c.w1;
      o.w2 = c.w2;
      o.max_inadmissible = c.max_inadmissible;
      break;
    case Algorithm::kAraStar:
      checkWeight(c.w1, "epsilon (w1)");
      checkDecrement(c.dw1, "epsilon decrement (dw1)");
      if (!certified && c.w1 > 1.0 && c.dw1 <= 0.0) {
        throw std::invalid_argument("ARA* needs an epsilon decrement dw1 > 0 to reach 1");
      }
      o.w1 = c.w1;
      o.dw1 = c.dw1;
      o.anytime = true;
      break;
    case Algorithm::kWeightedAStar:
      checkWeight(c.w1, "weight (w1)");
      o.w1 = c.w1;
      break;
    case Algorithm::kAStar:
      break;
  }
  return std::make_unique<MhaPlanner>(o);
}

}  // namespace amha
