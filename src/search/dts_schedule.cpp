#include "dts_schedule.h"

#include <cmath>

#include <boost/random/normal_distribution.hpp>

namespace amha {
namespace detail {

namespace {
std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
}  // namespace

void DtsSchedule::reset(std::size_t n, std::uint64_t seed) {
  arms_.assign(n + 1, Arm());
  // splitmix64 spreads any seed (0 included) over the xoshiro state.
  std::uint64_t z = seed;
  for (auto& word : engine_.s) {
    z += 0x9E3779B97F4A7C15ull;
    std::uint64_t x = z;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    word = x ^ (x >> 31);
  }
}

void DtsSchedule::resetProgress() {
  for (Arm& arm : arms_) arm.best_h = kInfiniteHeuristic;
}

std::size_t DtsSchedule::pick() {
  // The draw of arm i is x_i / (x_i + y_i); compared by cross-multiplying, without dividing.
  std::size_t best = 1;
  double best_x = 0.0, best_sum = 1.0;
  for (std::size_t i = 1; i < arms_.size(); ++i) {
    const double x = gamma(arms_[i].alpha_shape);
    const double sum = x + gamma(arms_[i].beta_shape);
    if (i == 1 || x * best_sum > best_x * sum) {
      best = i;
      best_x = x;
      best_sum = sum;
    }
  }
  return best;
}

void DtsSchedule::reward(std::size_t i, bool progress) {
  // alpha = 1 + successes and beta = 1 + failures, the evidence faded so that it sums to at
  // most C: the uniform prior stays, so a draw never degenerates to 0 (with alpha -> 0 every
  // draw would underflow to 0 and the first arm would win every tie).
  Arm& arm = arms_[i];
  double a = arm.alpha - 1.0 + (progress ? 1.0 : 0.0);
  double b = arm.beta - 1.0 + (progress ? 0.0 : 1.0);
  if (a + b > kWindow) {  // recent outcomes weigh the most
    const double scale = kWindow / (a + b);
    a *= scale;
    b *= scale;
  }
  arm.alpha = 1.0 + a;
  arm.beta = 1.0 + b;
  arm.alpha_shape.set(arm.alpha);
  arm.beta_shape.set(arm.beta);
}

DtsSchedule::Engine::result_type DtsSchedule::Engine::operator()() {
  const std::uint64_t result = rotl(s[1] * 5, 7) * 9;
  const std::uint64_t t = s[1] << 17;
  s[2] ^= s[0];
  s[3] ^= s[1];
  s[1] ^= s[2];
  s[0] ^= s[3];
  s[2] ^= t;
  s[3] = rotl(s[3], 45);
  return result;
}

double DtsSchedule::uniform() {
  return (static_cast<double>(engine_() >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

double DtsSchedule::gamma(const GammaShape& shape) {  // Marsaglia and Tsang (2000), shape >= 1
  // Boost's normal distribution is a ziggurat: a table look-up, rarely a logarithm. (The polar
  // method's logarithm per two draws, which std::gamma_distribution uses, made DTS a third of
  // the search's time on the 15-puzzle; Boost 1.74's gamma_distribution draws a tangent.)
  boost::random::normal_distribution<double> normal;

  const double d = shape.d, c = shape.c;
  for (;;) {
    double x, v;
    do {
      x = normal(engine_);
      v = 1.0 + c * x;
    } while (v <= 0.0);
    v = v * v * v;
    const double u = uniform();
    const double x2 = x * x;
    if (u < 1.0 - 0.0331 * x2 * x2) return d * v;
    if (std::log(u) < 0.5 * x2 + d * (1.0 - v + std::log(v))) return d * v;
  }
}

}  // namespace detail
}  // namespace amha
