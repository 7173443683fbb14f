// --schedule: the order of A-MHA*/MHA*'s inadmissible queues, the same option in every command.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "amha_planner/search/planner.h"

namespace amha {
namespace cli {

inline CLI::Option* addScheduleOption(CLI::App& app, QueueSchedule* out) {
  return app
      .add_option_function<std::string>(
          "--schedule", [out](const std::string& name) { parseSchedule(name, out); },
          "A-MHA*/MHA* order of the inadmissible queues: rr (round robin, the paper's) or dts "
          "(Dynamic Thompson Sampling; docs/search.md) (default rr)")
      ->check(CLI::IsMember(
          {scheduleName(QueueSchedule::kRoundRobin), scheduleName(QueueSchedule::kDts)}));
}

}  // namespace cli
}  // namespace amha
