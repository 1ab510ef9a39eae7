// Test helper: runs a function in a forked child process and reports how the child ended, so
// tests can kill a writer halfway (SIGKILL) and check what reached the disk.
//
//   ChildEnd end = run_in_child([&] { add_task(...); ::raise(SIGKILL); });
//   EXPECT_TRUE(end.killed_by(SIGKILL));
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <exception>
#include <functional>

namespace rondo::store::testing {

struct ChildEnd {
  int status = 0;
  bool exited_with(int code) const { return WIFEXITED(status) && WEXITSTATUS(status) == code; }
  bool killed_by(int signal) const { return WIFSIGNALED(status) && WTERMSIG(status) == signal; }
};

// Forks; the child runs `body` and leaves with _exit(0) (no destructors, no atexit handlers:
// nothing is closed cleanly), or _exit(3) if `body` throws. The parent waits for it.
inline ChildEnd run_in_child(const std::function<void()>& body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    try {
      body();
    } catch (...) {
      ::_exit(3);
    }
    ::_exit(0);
  }
  ChildEnd end;
  if (pid < 0 || ::waitpid(pid, &end.status, 0) != pid) end.status = -1;
  return end;
}

}  // namespace rondo::store::testing
