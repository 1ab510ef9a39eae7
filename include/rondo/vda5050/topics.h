// MQTT topics of one vehicle: interfaceName/v2/manufacturer/serialNumber/<topic>.
//
//   Topics t{.interface_name = "uagv", .manufacturer = "acme", .serial_number = "agv-7"};
//   t.of(Topic::kState);   // "uagv/v2/acme/agv-7/state"
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "rondo/core/result.h"

namespace rondo::vda5050 {

enum class Topic { kOrder, kInstantActions, kState, kConnection, kFactsheet, kVisualization };
inline constexpr std::size_t kTopicCount = 6;

// The topic's last level, as the specification names it ("instantActions").
const char* to_string(Topic t);

struct Topics {
  std::string interface_name;
  std::string manufacturer;
  std::string serial_number;

  std::string of(Topic t) const;
  // Which of this vehicle's topics `mqtt_topic` is; nothing for any other topic.
  std::optional<Topic> parse(std::string_view mqtt_topic) const;
};

// The names must be usable as single MQTT topic levels: non-empty, no '/', '+', '#' or NUL.
Status validate(const Topics& topics);

}  // namespace rondo::vda5050
