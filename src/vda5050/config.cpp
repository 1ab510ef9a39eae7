#include "rondo/vda5050/config.h"

#include "rondo/vda5050/mqtt_client.h"

namespace rondo::vda5050 {
namespace {

Result<std::string> required_text(const Field& f, std::string_view key) {
  RONDO_ASSIGN_OR_RETURN(Field v, f.required(key));
  RONDO_ASSIGN_OR_RETURN(std::string s, v.as_string());
  if (s.empty()) return v.error("must not be empty");
  return s;
}

// One of the names that make the topics: non-empty and usable as one MQTT topic level, with the
// error at its own line.
Result<std::string> topic_level(const Field& robot, std::string_view key) {
  RONDO_ASSIGN_OR_RETURN(std::string s, required_text(robot, key));
  Topics t{.interface_name = "i", .manufacturer = "m", .serial_number = "s"};
  (key == "interface_name" ? t.interface_name : key == "manufacturer" ? t.manufacturer : t.serial_number) = s;
  if (auto ok = validate(t); !ok) {
    const std::string& m = ok.error().message;  // "serial_number: ..."
    const auto colon = m.find(": ");
    RONDO_ASSIGN_OR_RETURN(Field v, robot.required(key));
    return v.error(colon == std::string::npos ? m : m.substr(colon + 2));
  }
  return s;
}

}  // namespace

Result<Vda5050Config> parse_vda5050_config(const Field& robot, std::span<const std::string_view> also_allowed) {
  std::vector<std::string_view> keys{"kind",   "broker",        "interface_name", "manufacturer", "serial_number",
                                     "map_id", "offline_after", "compatibility",  "information"};
  keys.insert(keys.end(), also_allowed.begin(), also_allowed.end());
  RONDO_RETURN_IF_ERROR(robot.expect_keys(keys));
  RONDO_ASSIGN_OR_RETURN(std::string kind, required_text(robot, "kind"));
  if (kind != "vda5050") return robot.error_at("kind", "is '" + kind + "', not vda5050");
  Vda5050Config c;
  RONDO_ASSIGN_OR_RETURN(c.broker, required_text(robot, "broker"));
  if (auto uri = paho_server_uri(c.broker); !uri) return robot.error_at("broker", uri.error().message);
  RONDO_ASSIGN_OR_RETURN(c.topics.interface_name, topic_level(robot, "interface_name"));
  RONDO_ASSIGN_OR_RETURN(c.topics.manufacturer, topic_level(robot, "manufacturer"));
  RONDO_ASSIGN_OR_RETURN(c.topics.serial_number, topic_level(robot, "serial_number"));
  RONDO_ASSIGN_OR_RETURN(c.map_id, required_text(robot, "map_id"));
  if (auto f = robot.optional("offline_after")) {
    RONDO_ASSIGN_OR_RETURN(c.offline_after, f->as_duration());
    if (c.offline_after <= Duration{0}) return f->error("must be longer than 0s");
  }
  if (auto f = robot.optional("compatibility")) {
    RONDO_ASSIGN_OR_RETURN(std::string mode, f->as_string());
    if (mode != "vda5050-lib-1.4") {
      return f->error("'" + mode + "' is not a known compatibility mode (only vda5050-lib-1.4)");
    }
    c.compat.vda5050_lib_1_4 = true;
  }
  if (auto f = robot.optional("information")) {
    RONDO_ASSIGN_OR_RETURN(c.information, parse_information_rules(*f));
  }
  return c;
}

}  // namespace rondo::vda5050
