// Which nodes can reach a target through usable edges (p > 0, finite τ): the nodes every solver
// must give a finite value, and the only ones value iteration may iterate over.
#pragma once

#include <vector>

#include "rondo/plan/mdp.h"

namespace rondo::plan {

// One flag per node: true when `target` can be reached from it (the target itself included).
// Precondition: target < mdp.node_count().
std::vector<bool> can_reach(const Mdp& mdp, NodeIndex target);

}  // namespace rondo::plan
