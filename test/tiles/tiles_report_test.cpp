// The tiles report: which solutions count towards success and the means.
#include <gtest/gtest.h>

#include "tiles_report.h"

namespace amha {
namespace cli {
namespace {

TEST(TilesReport, SolutionsAfterTheTimeLimitDoNotCount) {
  TilesRun run;
  run.instance = "x";
  for (double t : {0.5, 9.9, 10.4}) {
    Solution s;
    s.cost = 100;
    s.nominal_bound = s.certified_bound = 2.0;
    s.elapsed_s = t + 0.2;  // the wall clock, a little ahead of the CPU clock
    run.result.solutions.push_back(s);
    run.solution_cpu_s.push_back(t);
  }
  TilesRun wall = run;
  dropLateSolutions(run, 10.0, /*cpu_clock=*/true);
  EXPECT_EQ(run.result.solutions.size(), 2u);
  EXPECT_EQ(run.late_solutions, 1);
  dropLateSolutions(wall, 10.0, /*cpu_clock=*/false);  // 10.1 s wall > 10 s: dropped too
  EXPECT_EQ(wall.result.solutions.size(), 1u);
  EXPECT_EQ(wall.late_solutions, 2);

  // A run whose only solution came late is unsolved, and the report says why.
  TilesRun late = run;
  late.result.solutions.resize(1);
  late.solution_cpu_s = {10.2};
  late.late_solutions = 0;
  dropLateSolutions(late, 10.0, true);
  const auto summary = summarize({late}, {Algorithm::kAmhaStar}, true);
  ASSERT_EQ(summary.size(), 1u);
  EXPECT_EQ(summary[0].solved, 0);
  EXPECT_NE(reportText({late}, {Algorithm::kAmhaStar}, true).find("after the time limit"),
            std::string::npos);
}

}  // namespace
}  // namespace cli
}  // namespace amha
