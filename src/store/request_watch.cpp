// RequestWatch on PostgreSQL: LISTEN on a connection of its own, poll() on its socket and on a
// pipe that stop() writes to (request_watch.h).
#include "rondo/store/request_watch.h"

#include <fcntl.h>
#include <libpq-fe.h>
#include <poll.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "db/dialect.h"
#include "db/pg_connection.h"
#include "open_backend.h"
#include "store_access.h"

namespace rondo::store {
namespace {

class PgRequestWatch final : public RequestWatch {
 public:
  PgRequestWatch(std::unique_ptr<db::PgConnection> db, std::string name, int wake_read, int wake_write)
      : db_(std::move(db)), name_(std::move(name)), wake_read_(wake_read), wake_write_(wake_write) {}
  ~PgRequestWatch() override {
    ::close(wake_read_);
    ::close(wake_write_);
  }
  PgRequestWatch(const PgRequestWatch&) = delete;
  PgRequestWatch& operator=(const PgRequestWatch&) = delete;

  Result<bool> wait(Duration timeout) override {
    if (stopped_) return false;
    if (take_notifications()) return true;
    pollfd fds[2] = {{PQsocket(db_->raw()), POLLIN, 0}, {wake_read_, POLLIN, 0}};
    const auto ms = std::clamp<Duration::rep>(timeout.count(), 0, std::numeric_limits<int>::max());
    const int ready = ::poll(fds, 2, static_cast<int>(ms));
    if (stopped_ || ready <= 0) return false;  // stopped, timed out, or interrupted (EINTR): no news
    if (PQconsumeInput(db_->raw()) == 0)
      return Error::storage(fmt::format("{}: watching the request queue: {}", name_, PQerrorMessage(db_->raw())));
    return take_notifications();
  }

  void stop() override {
    stopped_ = true;
    const char byte = 1;
    (void)!::write(wake_write_, &byte, 1);
  }

 private:
  bool take_notifications() {
    bool any = false;
    while (PGnotify* n = PQnotifies(db_->raw())) {
      any = true;
      PQfreemem(n);
    }
    return any;
  }

  std::unique_ptr<db::PgConnection> db_;
  std::string name_;
  int wake_read_;
  int wake_write_;
  std::atomic<bool> stopped_{false};
};

}  // namespace

Result<std::unique_ptr<RequestWatch>> RequestWatch::open(const StoreLocation& location) {
  if (location.kind != StoreLocation::Kind::kPostgres)
    return Error::unsupported(fmt::format("{}: an SQLite store sends no notifications; poll the queue", location.name()));
  RONDO_ASSIGN_OR_RETURN(std::unique_ptr<db::Connection> opened,
                         open_postgres(location, {.mode = OpenMode::kMustExist}));
  std::unique_ptr<db::PgConnection> pg(static_cast<db::PgConnection*>(opened.release()));  // open_postgres' kind
  RONDO_RETURN_IF_ERROR(guarded(location.name(), "listening for queued requests", [&]() -> Status {
    pg->exec_script(std::string("LISTEN ") + std::string(db::kRequestChannel));
    return {};
  }));
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC | O_NONBLOCK) != 0)
    return Error::io(fmt::format("{}: watching the request queue: cannot make a pipe", location.name()));
  return std::unique_ptr<RequestWatch>(
      new PgRequestWatch(std::move(pg), location.name(), pipe_fds[0], pipe_fds[1]));
}

}  // namespace rondo::store
