// Shared helpers of the VDA 5050 tests: a well-formed state message to start from.
#pragma once

#include <string>

#include "rondo/core/document.h"

namespace rondo::vda5050::testing {

// A complete, valid 2.0.0 state of vehicle acme/agv-7 with no order, as JSON to edit.
inline Json sample_state_json() {
  return Json::parse(R"({
    "headerId": 5, "timestamp": "2026-12-01T10:00:00.250Z", "version": "2.0.0",
    "manufacturer": "acme", "serialNumber": "agv-7",
    "orderId": "", "orderUpdateId": 0, "lastNodeId": "A", "lastNodeSequenceId": 0,
    "nodeStates": [], "edgeStates": [], "driving": false,
    "operatingMode": "AUTOMATIC", "actionStates": [],
    "batteryState": {"batteryCharge": 87.5, "charging": false},
    "errors": [], "safetyState": {"eStop": "NONE", "fieldViolation": false},
    "agvPosition": {"x": 1.0, "y": 2.0, "theta": 0.5, "mapId": "g4s", "positionInitialized": true}
  })");
}

}  // namespace rondo::vda5050::testing
