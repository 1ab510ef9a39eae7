// Active and standby on one PostgreSQL store: the lease that makes one `rondo serve` the active
// executive, and the epoch that fences the others' writes in the database itself.
//
// The lease is a session-level advisory lock held on a connection of its own, plus the one row of
// the `lease` table: the epoch (bumped by each new active), its holder and when the holder last
// renewed it (the server's clock). A standby tries to take it every so often; the active renews it
// every so often. When the active's process dies its connection closes and the lock is free at
// once; when it is frozen (SIGSTOP) or cut off, its renewal grows old, and a standby that sees it
// older than `stale_after` ends the holder's sessions (pg_terminate_backend on its
// application_name), which frees the lock for the next try.
//
// Fencing: the active's store connection carries its epoch (fence_writes), and every write of a
// connection that carries one is checked by a trigger against the lease row inside the writing
// transaction: a stale epoch is refused by the database (kConflict "stale epoch ..."), whatever
// the old process believes. SQLite stores have no lease: one process uses them.
//
//   Result<Lease> lease = Lease::connect(where, Lease::new_holder_name());
//   while (!(taken = lease->try_take(seconds(3))).value_or(std::nullopt)) wait(poll);
//   fence_writes(store, *lease->epoch(), lease->holder());   // every write now carries the epoch
//   ... lease->renew() every second; an error: the lease is lost, step down.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/store/store.h"

namespace rondo::store {

// The lease row as it stands.
struct LeaseState {
  std::int64_t epoch = 0;  // 0: never taken (and always on SQLite)
  std::string holder;      // the holder's name (its sessions' application_name); '' when never taken
  Time taken{};            // when the current epoch began (the database server's clock)
  Time renewed{};          // its holder's latest renewal (the server's clock)
  Duration age{};          // since that renewal, by the server's clock when read
};

// The lease row (both backends; an SQLite store's is epoch 0, never taken).
Result<LeaseState> read_lease(const Store& store);

// Makes every later write of `store` carry `epoch`, and names its session `holder` (so that a
// takeover can end it). Once another active has taken the lease, the database refuses the writes
// with kConflict "stale epoch N: the lease is at epoch M ...". Nothing to do on SQLite.
Status fence_writes(Store& store, std::int64_t epoch, std::string_view holder);

class Lease {
 public:
  // A name for this process's sessions, unique in practice: "rondo-serve-<pid>-<8 hex digits>".
  static std::string new_holder_name();

  // Opens the lease's own connection to the PostgreSQL store at `where` (which must hold a rondo
  // store already: Store::open it first). kUnsupported for an SQLite store; kInvalidInput for a
  // server that cannot be reached.
  static Result<Lease> connect(const StoreLocation& where, std::string holder);

  Lease(Lease&& other) noexcept;
  Lease& operator=(Lease&& other) noexcept;
  Lease(const Lease&) = delete;
  Lease& operator=(const Lease&) = delete;
  ~Lease();  // closing the connection frees the lock

  // One try. When the lock is free: ends what is left of the previous holder's sessions, bumps the
  // epoch and returns it (this holder is the active from now on). When another holds it: nothing;
  // and when that holder's renewal is older than `stale_after`, its sessions are ended first, so
  // that a later try finds the lock free. Already held: the same epoch again.
  Result<std::optional<std::int64_t>> try_take(Duration stale_after);
  // Renews the held lease. kConflict when it is no longer this holder's (another took it), kStorage
  // when the connection is gone (then the lock is gone too): either way the lease is lost.
  Status renew();
  // Lets go of the lease (a clean stop): a standby may take it at once.
  void release();
  // The lease row as this connection reads it now (whoever holds it).
  Result<LeaseState> read() const;

  std::optional<std::int64_t> epoch() const { return epoch_; }
  const std::string& holder() const { return holder_; }

 private:
  Lease(std::string name, std::string holder, std::unique_ptr<db::Connection> db);

  std::string name_;    // the store, for messages
  std::string holder_;
  std::unique_ptr<db::Connection> db_;
  std::optional<std::int64_t> epoch_;
};

}  // namespace rondo::store
