// Exit codes of the `amha` command: one per kind of failure, so scripts can tell them apart.
#pragma once

namespace amha {
namespace cli {

enum ExitCode : int {
  kExitOk = 0,
  kExitInternal = 1,       ///< unexpected failure (a bug: please report)
  kExitUsage = 2,          ///< bad command-line arguments
  kExitBadMap = 3,         ///< map file unreadable or malformed
  kExitBadPrimitives = 4,  ///< motion primitives unreadable, malformed or not matching the map
  kExitBadStart = 5,       ///< start outside the map, in collision or not finite
  kExitBadGoal = 6,        ///< goal outside the map, in collision or not finite
  kExitNoSolution = 7,     ///< the search ended without any solution
  kExitBadInstances = 8,   ///< tile instance file unreadable or malformed
  kExitOutput = 9,         ///< an output file (JSON, PNG, CSV) could not be written
};

}  // namespace cli
}  // namespace amha
