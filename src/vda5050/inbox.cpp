#include "rondo/vda5050/inbox.h"

namespace rondo::vda5050 {

Status Inbox::admit(Topic topic, const Header& header) {
  const std::string where = std::string(to_string(topic)) + " headerId " +
                            std::to_string(header.header_id) + ": ignored: ";
  if (header.manufacturer != manufacturer_ || header.serial_number != serial_number_) {
    return Error::invalid(where + "it is from " + header.manufacturer + "/" +
                          header.serial_number + ", not " + manufacturer_ + "/" + serial_number_);
  }
  auto& last = last_.at(static_cast<std::size_t>(topic));
  if (last && header.header_id <= *last) {
    return Error::invalid(where + "not after the last one admitted (" + std::to_string(*last) +
                          "): a duplicate or out of order");
  }
  last = header.header_id;
  return {};
}

}  // namespace rondo::vda5050
