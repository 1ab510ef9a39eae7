// Reading fitted models back from the JSON their to_json() wrote: the "type" member picks the kind.
//
//   Json saved = fit_fremen_binary(flags, {.order = 2})->to_json();
//   Result<BinaryModelPtr> model = binary_model_from_json(saved);   // "static" | "fremen" | "episode"
#pragma once

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/learn/temporal_model.h"

namespace rondo::learn {

Result<BinaryModelPtr> binary_model_from_json(const Json& j);
// "static" | "fremen"
Result<DurationModelPtr> duration_model_from_json(const Json& j);

}  // namespace rondo::learn
