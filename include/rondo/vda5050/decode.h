// Defensive decoders of what a vehicle sends. Any payload, however broken, gives a value or an
// Error naming the field and the problem ("state: nodeStates[2].sequenceId: must be an
// integer"); nothing throws and nothing recurses deeper than Document::kMaxDepth.
//
//   Result<State> s = decode_state(payload);
//   if (!s) log("state ignored: " + s.error().message);
//
// Unknown fields are allowed (the specification lets vehicles add their own); required fields
// of the 2.0.0 schemas must be there with the right type, except where noted.
#pragma once

#include <string_view>

#include "rondo/core/result.h"
#include "rondo/vda5050/compat.h"
#include "rondo/vda5050/messages.h"

namespace rondo::vda5050 {

// Fields the 2.0.0 schema requires but rondo does not use (safetyState) may be missing.
Result<State> decode_state(std::string_view payload);
Result<Connection> decode_connection(std::string_view payload);
// Without compat.vda5050_lib_1_4 a factsheet without `typeSpecification` is an error.
Result<Factsheet> decode_factsheet(std::string_view payload, const Compatibility& compat = {});
// Only the header of any message (e.g. visualization).
Result<Header> decode_header_only(std::string_view payload, std::string_view topic);

}  // namespace rondo::vda5050
