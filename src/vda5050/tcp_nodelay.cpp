#include "tcp_nodelay.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace rondo::vda5050 {

int set_tcp_nodelay_to(const std::string& host, int port) {
  in_addr wanted{};
  const bool numeric = ::inet_pton(AF_INET, host.c_str(), &wanted) == 1;
  int count = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd", ec)) {
    const int fd = std::atoi(entry.path().filename().c_str());
    int type = 0;
    socklen_t len = sizeof type;
    if (::getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &len) != 0 || type != SOCK_STREAM) continue;
    sockaddr_storage peer{};
    socklen_t peer_len = sizeof peer;
    if (::getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &peer_len) != 0 || peer.ss_family != AF_INET) continue;
    const auto* in = reinterpret_cast<const sockaddr_in*>(&peer);
    if (ntohs(in->sin_port) != port || (numeric && in->sin_addr.s_addr != wanted.s_addr)) continue;
    const int on = 1;
    if (::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on) == 0) ++count;
  }
  return count;
}

}  // namespace rondo::vda5050
