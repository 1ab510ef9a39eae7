// JSON of the messages master control sends (VDA 5050 2.0.0), ready to publish.
//
//   HeaderCounter headers(manufacturer, serial);
//   Json j = encode_order(headers.next(Topic::kOrder, now), order);
//   client.publish(topics.of(Topic::kOrder), j.dump(), 1);
//
// Optional fields are left out when they hold nothing (an empty description, no maxSpeed).
#pragma once

#include <string>

#include "rondo/core/document.h"
#include "rondo/vda5050/compat.h"
#include "rondo/vda5050/messages.h"

namespace rondo::vda5050 {

Json encode_header(const Header& header);
Json encode_action(const Action& action);
// With compat.vda5050_lib_1_4 a node's allowedDeviationXY is also written as `allowedDeviationXy`.
Json encode_order(const Header& header, const Order& order, const Compatibility& compat = {});
// With compat.vda5050_lib_1_4 the actions are also written under the old key `instantActions`.
Json encode_instant_actions(const Header& header, const InstantActions& message, const Compatibility& compat = {});

// The instant action that cancels the vehicle's order (blockingType HARD, no parameters).
Action cancel_order_action(std::string action_id);
// The instant action that asks the vehicle to publish its state now (blockingType NONE).
Action state_request_action(std::string action_id);
// The instant action that asks the vehicle to publish its factsheet (blockingType NONE).
Action factsheet_request_action(std::string action_id);

}  // namespace rondo::vda5050
