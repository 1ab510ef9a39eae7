// An independent referee: verifies a Schedule against its Problem, sharing no code with the
// solvers. Every test runs every solver's answer through it.
//
//   CheckReport r = check_schedule(problem, schedule);
//   EXPECT_TRUE(r.ok()) << r.summary();
//
// Checked: each task at most once and scheduled-or-dropped exactly once (when status says all
// are scheduled, none dropped); start >= release; end == start + duration; deadline (on end or on
// start); no overlap; depart == previous end (or robot time); arrival >= depart + travel(depart);
// start >= arrival; precedence; capacity; never two same-looking items on board; drops after
// their pickup; the return deadline; the reported objective equals the recomputed one.
#pragma once

#include <string>
#include <vector>

#include "rondo/schedule/problem.h"
#include "rondo/schedule/schedule.h"

namespace rondo::schedule {

struct CheckReport {
  std::vector<std::string> violations;  // one human-readable line each
  Duration recomputed_objective{0};
  bool ok() const { return violations.empty(); }
  std::string summary() const;
};

CheckReport check_schedule(const Problem& problem, const Schedule& schedule);

}  // namespace rondo::schedule
