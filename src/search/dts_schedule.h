// Dynamic Thompson Sampling over the inadmissible queues of MHA* (Phillips, Narayanan, Aine,
// Likhachev: "Efficient Search with an Ensemble of Heuristics", IJCAI 2015). Each queue is an
// arm with a Beta(alpha, beta) belief that an expansion from it makes progress; the next queue
// is the arm with the largest draw. "Dynamic": the evidence (successes + failures) is capped at
// C by scaling both down, so old evidence fades and a queue that stops making progress loses its
// share quickly. Both parameters keep the uniform prior's 1, so no arm's draws collapse to 0.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "amha_planner/search/types.h"

namespace amha {
namespace detail {

class DtsSchedule {
 public:
  /// Arms 1..n (0, the anchor, is never drawn); uniform Beta(1, 1) beliefs.
  void reset(std::size_t n, std::uint64_t seed);
  /// Forgets the smallest h seen per queue (a new iteration rebuilds the queues).
  void resetProgress();
  /// The arm with the largest Beta draw.
  std::size_t pick();
  /// OPEN_i received a state with heuristic h; true if that is the smallest h_i so far.
  bool noteQueued(std::size_t i, HeuristicValue h) {
    if (h >= arms_[i].best_h) return false;
    arms_[i].best_h = h;
    return true;
  }
  /// An expansion from arm i made progress (or not).
  void reward(std::size_t i, bool progress);

  static constexpr double kWindow = 10.0;  // C: the cap on the evidence, alpha + beta - 2

 private:
  /// xoshiro256**: fast, and a valid engine for Boost's distributions.
  struct Engine {
    using result_type = std::uint64_t;
    static constexpr result_type min() { return 0; }
    static constexpr result_type max() { return ~result_type{0}; }
    result_type operator()();
    std::uint64_t s[4] = {1, 2, 3, 4};
  };
  /// Marsaglia and Tsang's constants for one shape, computed when the shape changes rather
  /// than at every draw (a square root and a division each).
  struct GammaShape {
    double d, c;
    explicit GammaShape(double shape = 1.0) { set(shape); }
    void set(double shape) {
      d = shape - 1.0 / 3.0;
      c = 1.0 / std::sqrt(9.0 * d);
    }
  };
  /// One queue's belief Beta(alpha, beta) and the smallest h_i queued in it so far.
  struct Arm {
    double alpha = 1.0, beta = 1.0;
    GammaShape alpha_shape, beta_shape;
    HeuristicValue best_h = kInfiniteHeuristic;
  };
  double uniform();                       // in (0, 1)
  double gamma(const GammaShape& shape);  // Gamma(shape, 1), shape >= 1

  std::vector<Arm> arms_;  // arms_[0] (the anchor) is unused
  Engine engine_;
};

}  // namespace detail
}  // namespace amha
