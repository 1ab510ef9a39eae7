// The ProductStep of taking `edge` from (from, q), shared by the product's solvers.
#pragma once

#include "rondo/plan/product_mdp.h"
#include "rondo/plan/product_policy.h"

namespace rondo::plan {

inline ProductStep product_step(const ProductMdp& product, NodeIndex from, ProductMdp::AutomatonState q,
                                EdgeIndex edge) {
  const NodeIndex to = product.mdp().topology().to_index(edge);
  const EdgeCrossing& o = product.mdp().outcome(edge);
  return {.from = from,
          .state = q,
          .edge = edge,
          .to = to,
          .next_state = product.after_reaching(q, to),
          .success_probability = o.success_probability,
          .attempt_seconds = o.expected_seconds};
}

}  // namespace rondo::plan
