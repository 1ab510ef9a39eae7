// Who may talk to the service: a loopback host or a token, and the token file's own safety.
#include <fmt/format.h>
#include <sys/stat.h>

#include <fstream>
#include <sstream>

#include "rondo/service/server.h"

namespace rondo::service {

bool is_loopback_host(const std::string& host) {
  return host == "localhost" || host == "::1" || host == "[::1]" || host.rfind("127.", 0) == 0;
}

Result<std::string> load_token_file(const std::filesystem::path& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) return Error::not_found(fmt::format("{}: no such token file", file.string()));
  if (!S_ISREG(st.st_mode))
    return Error::invalid(fmt::format("{}: the token file is not a regular file", file.string()));
  if ((st.st_mode & (S_IRGRP | S_IWGRP | S_IROTH | S_IWOTH)) != 0)
    return Error::invalid(fmt::format("{}: the token file can be read or written by others (mode {:o}); chmod 600 it",
                                      file.string(), st.st_mode & 0777));
  std::ifstream in(file, std::ios::binary);
  if (!in) return Error::io(fmt::format("{}: cannot read the token file", file.string()));
  std::stringstream text;
  text << in.rdbuf();
  std::string token = text.str();
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!token.empty() && blank(token.back())) token.pop_back();
  std::size_t start = 0;
  while (start < token.size() && blank(token[start])) ++start;
  token.erase(0, start);
  if (token.size() < 16)
    return Error::invalid(fmt::format("{}: the token file must hold a token of at least 16 characters", file.string()));
  for (char c : token)
    if (static_cast<unsigned char>(c) < 0x21 || static_cast<unsigned char>(c) > 0x7e)
      return Error::invalid(fmt::format("{}: the token must be printable ASCII without spaces", file.string()));
  return token;
}

}  // namespace rondo::service
