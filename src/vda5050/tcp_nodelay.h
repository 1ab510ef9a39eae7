// TCP_NODELAY on the process's sockets to one broker. Paho C (under Paho C++) leaves Nagle's
// algorithm on and gives no way to change it; with MQTT's small packets and the peer's delayed
// ACK, every message that follows another one (a PUBACK, then the order update) then waits ~40 ms
// per hop (bench/bench_vda5050_update.cpp measured it). The client calls this after each connect.
#pragma once

#include <string>

namespace rondo::vda5050 {

// Sets TCP_NODELAY on every TCP socket of this process connected to host:port (host numeric; a
// name matches any address at that port). Returns how many; failures are ignored (only speed).
int set_tcp_nodelay_to(const std::string& host, int port);

}  // namespace rondo::vda5050
