// libFuzzer target: the VDA 5050 state decoder, fed whatever a broker could deliver. It must
// return a State or an Error, never crash, hang or leak; a decoded state must satisfy what the
// decoder promises (non-negative ids, a battery percentage), and decoding is deterministic.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "rondo/vda5050/decode.h"
#include "rondo/vda5050/inbox.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto state = rondo::vda5050::decode_state(text);
  if (!state) {
    if (state.error().message.empty()) std::abort();
    return 0;
  }
  if (state->header.header_id < 0 || state->order_update_id < 0 || state->last_node_sequence_id < 0) {
    std::abort();
  }
  if (!(state->battery_state.battery_charge >= 0 && state->battery_state.battery_charge <= 100)) {
    std::abort();
  }
  auto again = rondo::vda5050::decode_state(text);
  if (!again || !(*again == *state)) std::abort();
  rondo::vda5050::Inbox inbox(state->header.manufacturer, state->header.serial_number);
  if (!inbox.admit(rondo::vda5050::Topic::kState, state->header).ok()) std::abort();
  if (inbox.admit(rondo::vda5050::Topic::kState, state->header).ok()) std::abort();
  return 0;
}
