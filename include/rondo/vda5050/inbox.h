// The gate of incoming messages of one vehicle: a message for another vehicle, or one whose
// headerId does not move forward on its topic, is ignored with a reason, never acted on.
//
//   Inbox inbox("acme", "agv-7");
//   if (Status ok = inbox.admit(Topic::kState, state.header); !ok) log(ok.error().message);
//
// A vehicle that restarts counts its headerIds from 0 again; it announces itself with ONLINE
// on `connection`, so an ONLINE message starts a new session: every topic's order resets.
// A CONNECTIONBROKEN is the vehicle's last will, which it composed when it connected, before its
// ONLINE: its headerId is older by nature, so it is admitted whatever its headerId.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "rondo/core/result.h"
#include "rondo/vda5050/messages.h"
#include "rondo/vda5050/topics.h"

namespace rondo::vda5050 {

class Inbox {
 public:
  Inbox(std::string manufacturer, std::string serial_number)
      : manufacturer_(std::move(manufacturer)), serial_number_(std::move(serial_number)) {}

  // OK when the message is for this vehicle and newer than the last admitted one on `topic`;
  // an error saying why it is ignored otherwise (nothing is recorded then).
  Status admit(Topic topic, const Header& header);
  // A `connection` message, with the session rules above.
  Status admit(const Connection& connection);
  // A new session of the vehicle: forget the last headerIds.
  void new_session() { last_.fill(std::nullopt); }

 private:
  std::string manufacturer_;
  std::string serial_number_;
  std::array<std::optional<std::int64_t>, kTopicCount> last_{};
};

}  // namespace rondo::vda5050
