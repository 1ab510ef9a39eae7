// `rondo serve` (and other rondo commands) as child processes for the process tests: spawn one,
// read its stderr until a pattern shows, wait for its exit, all with generous deadlines.
//
//   std::string port;
//   Child c = spawn_serve(dir / "data", port);     // the G4S example on a free loopback port
//   ::kill(c.pid, SIGTERM); EXPECT_EQ(c.wait_exit(), 0);
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <regex>
#include <string>
#include <thread>
#include <vector>

namespace rondo::test {

struct Child {
  pid_t pid = -1;
  int err = -1;  // its stderr
  std::string seen;
  bool reaped = false;
  Child() = default;
  Child(Child&& o) noexcept : pid(o.pid), err(o.err), seen(std::move(o.seen)), reaped(o.reaped) { o.pid = -1; }
  Child(const Child&) = delete;
  ~Child() {  // a test that failed early leaves no server behind
    if (pid > 0 && !reaped) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }
  // Reads its stderr until `pattern` matches (or the deadline); returns the first group.
  std::string wait_for(const std::regex& pattern, std::chrono::seconds deadline = std::chrono::seconds(60)) {
    const auto end = std::chrono::steady_clock::now() + deadline;
    std::smatch m;
    while (!std::regex_search(seen, m, pattern) && std::chrono::steady_clock::now() < end) {
      pollfd p{err, POLLIN, 0};
      if (::poll(&p, 1, 100) <= 0) continue;
      char buf[512];
      const ssize_t n = ::read(err, buf, sizeof buf);
      if (n <= 0) break;
      seen.append(buf, static_cast<std::size_t>(n));
    }
    return std::regex_search(seen, m, pattern) ? m[1].str() : "";
  }
  // The exit status, waiting up to the deadline; -1 if it is still running then.
  int wait_exit(std::chrono::seconds deadline = std::chrono::seconds(60)) {
    const auto end = std::chrono::steady_clock::now() + deadline;
    while (std::chrono::steady_clock::now() < end) {
      int status = 0;
      if (::waitpid(pid, &status, WNOHANG) == pid)
        return reaped = true, WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));  // polling: the deadline is the bound
    }
    return -1;
  }
};

inline Child spawn(const std::vector<std::string>& args) {
  int fds[2];
  EXPECT_EQ(::pipe(fds), 0);
  Child c;
  c.pid = ::fork();
  if (c.pid == 0) {
    ::dup2(fds[1], STDERR_FILENO);
    ::close(fds[0]);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(fds[1]);
  c.err = fds[0];
  return c;
}

// `rondo serve` of the G4S example on a free loopback port, its store in `data`, and the port it
// says it listens on (empty when it said nothing of the kind in time).
inline Child spawn_serve(const std::filesystem::path& data, std::string& port_text) {
  Child c = spawn({RONDO_BINARY, "serve", "--listen", "127.0.0.1:0", "--data", data.string(), "--speed", "10"});
  port_text = c.wait_for(std::regex(R"(on http://127\.0\.0\.1:(\d+)/)"));
  return c;
}

}  // namespace rondo::test
