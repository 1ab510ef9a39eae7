#include "rondo/vda5050/header.h"

#include <chrono>
#include <cstdio>

namespace rondo::vda5050 {

std::string format_timestamp(Time t) {
  const auto day = std::chrono::floor<std::chrono::days>(t);
  const std::chrono::year_month_day ymd{day};
  const std::chrono::hh_mm_ss<Duration> hms{t - day};
  char text[40];
  std::snprintf(text, sizeof text, "%04d-%02u-%02uT%02d:%02d:%02d.%03dZ", int(ymd.year()), unsigned(ymd.month()),
                unsigned(ymd.day()), int(hms.hours().count()), int(hms.minutes().count()), int(hms.seconds().count()),
                int(hms.subseconds().count()));
  return text;
}

Header HeaderCounter::next(Topic topic, Time now) {
  auto& id = next_id_.at(static_cast<std::size_t>(topic));
  Header h;
  h.header_id = id++;
  h.timestamp = now;
  h.manufacturer = manufacturer_;
  h.serial_number = serial_number_;
  return h;
}

}  // namespace rondo::vda5050
