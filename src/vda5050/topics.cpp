#include "rondo/vda5050/topics.h"

#include <array>

namespace rondo::vda5050 {
namespace {

constexpr std::array<Topic, kTopicCount> kAllTopics = {
    Topic::kOrder, Topic::kInstantActions, Topic::kState, Topic::kConnection, Topic::kFactsheet, Topic::kVisualization};

Status check_level(const std::string& value, const char* field) {
  if (value.empty()) return Error::invalid(std::string(field) + ": must not be empty");
  for (char c : value) {
    if (c == '/' || c == '+' || c == '#' || c == '\0') {
      return Error::invalid(std::string(field) + ": '" + value +
                            "' must not contain '/', '+', '#' or NUL (it is one MQTT topic level)");
    }
  }
  return {};
}

}  // namespace

const char* to_string(Topic t) {
  switch (t) {
    case Topic::kOrder:
      return "order";
    case Topic::kInstantActions:
      return "instantActions";
    case Topic::kState:
      return "state";
    case Topic::kConnection:
      return "connection";
    case Topic::kFactsheet:
      return "factsheet";
    case Topic::kVisualization:
      return "visualization";
  }
  return "?";
}

std::string Topics::of(Topic t) const {
  return interface_name + "/v2/" + manufacturer + "/" + serial_number + "/" + to_string(t);
}

std::optional<Topic> Topics::parse(std::string_view mqtt_topic) const {
  for (Topic t : kAllTopics) {
    if (mqtt_topic == of(t)) return t;
  }
  return std::nullopt;
}

Status validate(const Topics& topics) {
  RONDO_RETURN_IF_ERROR(check_level(topics.interface_name, "interface_name"));
  RONDO_RETURN_IF_ERROR(check_level(topics.manufacturer, "manufacturer"));
  return check_level(topics.serial_number, "serial_number");
}

}  // namespace rondo::vda5050
