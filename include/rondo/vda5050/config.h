// The deployment's description of a VDA 5050 vehicle (docs/vda5050.md):
//
//   robot:
//     kind: vda5050
//     broker: "mqtt://127.0.0.1:1883"
//     interface_name: uagv
//     manufacturer: acme
//     serial_number: agv-7
//     map_id: g4s_y2
//     offline_after: 45s            # optional; default 45s
//     compatibility: vda5050-lib-1.4  # optional; only for that peer (see compat.h)
//     information: [...]            # optional; the state's information[] entries that are
//                                   # observations (information.h)
//
//   Result<Vda5050Config> c = parse_vda5050_config(doc.root().required("robot").value());
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/vda5050/compat.h"
#include "rondo/vda5050/information.h"
#include "rondo/vda5050/topics.h"

namespace rondo::vda5050 {

struct Vda5050Config {
  std::string broker;
  Topics topics;  // interface_name, manufacturer, serial_number
  std::string map_id;
  Duration offline_after = seconds(45);  // the specification asks for a state at least every 30 s
  Compatibility compat;
  std::vector<InformationRule> information{};  // which information[] entries are observations
  bool operator==(const Vda5050Config&) const = default;
};

// Errors name the file, line and field ("deployment.yaml:7: robot.serial_number: ...").
// `also_allowed`: more keys the caller reads from the same mapping (a fleet entry's name, dock...).
Result<Vda5050Config> parse_vda5050_config(const Field& robot, std::span<const std::string_view> also_allowed = {});

}  // namespace rondo::vda5050
