#include "rondo/vda5050/inbox.h"

namespace rondo::vda5050 {

Status Inbox::admit(Topic topic, const Header& header) {
  const std::string where =
      std::string(to_string(topic)) + " headerId " + std::to_string(header.header_id) + ": ignored: ";
  if (header.manufacturer != manufacturer_ || header.serial_number != serial_number_) {
    return Error::invalid(where + "it is from " + header.manufacturer + "/" + header.serial_number + ", not " +
                          manufacturer_ + "/" + serial_number_);
  }
  auto& last = last_.at(static_cast<std::size_t>(topic));
  if (last && header.header_id <= *last) {
    return Error::invalid(where + "not after the last one admitted (" + std::to_string(*last) +
                          "): a duplicate or out of order");
  }
  last = header.header_id;
  return {};
}

Status Inbox::admit(const Connection& connection) {
  switch (connection.connection_state) {
    case ConnectionState::kOnline: {
      const Header& h = connection.header;
      if (h.manufacturer != manufacturer_ || h.serial_number != serial_number_) {
        return admit(Topic::kConnection, h);  // the same "from another vehicle" reason
      }
      new_session();
      return admit(Topic::kConnection, h);
    }
    case ConnectionState::kConnectionBroken: {
      Header h = connection.header;
      auto& last = last_.at(static_cast<std::size_t>(Topic::kConnection));
      if (last && h.header_id <= *last) h.header_id = *last + 1;  // a will is older by nature
      return admit(Topic::kConnection, h);
    }
    case ConnectionState::kOffline:
      break;
  }
  return admit(Topic::kConnection, connection.header);
}

}  // namespace rondo::vda5050
