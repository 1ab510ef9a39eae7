// Headers of outgoing messages: headerId counted per topic, a UTC timestamp with milliseconds.
//
//   HeaderCounter headers("rondo-fleet", "agv-7");
//   Header h = headers.next(Topic::kOrder, now);    // header_id 0, 1, 2... per topic
//   format_timestamp(h.timestamp);                  // "2026-12-01T20:58:07.120Z"
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "rondo/core/time.h"
#include "rondo/vda5050/messages.h"
#include "rondo/vda5050/topics.h"

namespace rondo::vda5050 {

// ISO 8601 in UTC, always with three fractional digits: "2026-12-01T20:58:07.000Z".
std::string format_timestamp(Time t);

class HeaderCounter {
 public:
  HeaderCounter(std::string manufacturer, std::string serial_number)
      : manufacturer_(std::move(manufacturer)), serial_number_(std::move(serial_number)) {}

  // The header of the next message on `topic`; its header_id is one more than the previous one
  // on the same topic (the first is 0).
  Header next(Topic topic, Time now);

 private:
  std::string manufacturer_;
  std::string serial_number_;
  std::array<std::int64_t, kTopicCount> next_id_{};
};

}  // namespace rondo::vda5050
