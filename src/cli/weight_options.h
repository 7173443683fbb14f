// The range checks of the weight options, the same in every command (--w1, --w2, --eps, --weight:
// [1, kMaxWeight]; --dw1, --dw2, --deps: [0, kMaxWeight]) and the same as makePlanner's, so that
// a value out of range, NaN or an infinity is a usage error naming the option before any work.
#pragma once

#include <cstdlib>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>

#include "amha_planner/search/planner.h"

namespace amha {
namespace cli {

inline CLI::Validator numberIn(double lo, double hi, const std::string& what) {
  std::ostringstream range;
  range << "[" << lo << ", " << hi << "]";
  const std::string text = range.str();
  return CLI::Validator(
      [lo, hi, what, text](std::string& in) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(in.c_str(), &end);
        if (end == in.c_str() || *end != '\0' || !(v >= lo && v <= hi)) {
          return what + " must be a finite number in " + text + ", not '" + in + "'";
        }
        return std::string();
      },
      what + " in " + text);
}

/// An inflation weight: w1, w2, epsilon.
inline CLI::Validator weightRange() { return numberIn(1.0, kMaxWeight, "a weight"); }
/// A weight's decrement per iteration.
inline CLI::Validator decrementRange() { return numberIn(0.0, kMaxWeight, "a decrement"); }

}  // namespace cli
}  // namespace amha
