// The one compatibility switch of the VDA 5050 layer. Off by default: rondo speaks the standard.
//
//   Compatibility c{.vda5050_lib_1_4 = true};   // only in tests against vda-5050-lib 1.4.0
//
// `vda5050_lib_1_4` works around the known deviations of the npm package vda-5050-lib 1.4.0
// (docs/vda5050.md lists them):
//   - it reads instant actions only under the pre-2.0 key `instantActions`: the encoder then
//     writes the array under both `actions` (the standard key) and `instantActions`;
//   - it reads a node's allowed deviation only as `allowedDeviationXy` (the 2.0.0 schema file's
//     spelling; the specification says allowedDeviationXY): the encoder then writes both;
//   - its factsheet is only a header: the decoder then accepts a header-only factsheet
//     (Factsheet::header_only) instead of ignoring it as malformed;
//   - it does not republish ONLINE on `connection` after an automatic reconnect: a fresh state
//     message then counts as the vehicle being online again (ConnectionWatch, connection_watch.h).
// Its `connection` at QoS 0 needs no workaround: rondo subscribes at QoS 1 and reads what comes.
#pragma once

namespace rondo::vda5050 {

struct Compatibility {
  bool vda5050_lib_1_4 = false;
  bool operator==(const Compatibility&) const = default;
};

}  // namespace rondo::vda5050
