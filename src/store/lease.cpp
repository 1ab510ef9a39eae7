// The lease of the active executive and the fencing of its writes (lease.h). The SQL of the check
// itself is the trigger of schema version 6 (pg_schema.cpp).
#include "rondo/store/lease.h"

#include <fmt/format.h>
#include <unistd.h>

#include <random>

#include "db/dialect.h"
#include "migrations.h"
#include "open_backend.h"
#include "store_access.h"
#include "write_tx.h"

namespace rondo::store {
namespace {

// The database server's clock in ms since the Unix epoch: every process compares the renewal's age
// on the same clock, whatever their machines' clocks say.
constexpr std::string_view kServerNowMs = "CAST(FLOOR(EXTRACT(EPOCH FROM clock_timestamp()) * 1000) AS BIGINT)";

// The advisory lock of the lease: the application id and 1 (the two-key form, apart from the
// one-key lock the migrations take).
constexpr int kLeaseLockKey = 1;

// Ends every session named `holder` but this one, waiting up to 2 s for each to go: its locks
// (the lease's advisory lock, the lease row's share lock of a write in progress) go with it.
void end_sessions_of(db::Connection& db, const std::string& holder) {
  if (holder.empty()) return;
  db.query(
        "SELECT COUNT(pg_terminate_backend(pid, 2000)) FROM pg_stat_activity "
        "WHERE application_name = $1 AND pid <> pg_backend_pid() AND datname = current_database()",
        {holder})
      ->next();
}

// The lease row read on `db`, the renewal's age by the server's clock (SQLite: none, 0).
LeaseState lease_row(db::Connection& db) {
  const std::string now = db.backend() == db::Backend::kPostgres ? std::string(kServerNowMs) : "renewed_ms";
  auto rows = db.query("SELECT epoch, holder, taken_ms, renewed_ms, " + now + " - renewed_ms FROM lease WHERE id = 1");
  LeaseState state;
  if (!rows->next()) return state;
  state.epoch = rows->int64(0);
  state.holder = rows->text(1);
  state.taken = time_from_db(rows->int64(2));
  state.renewed = time_from_db(rows->int64(3));
  state.age = duration_from_db(rows->int64(4));
  return state;
}

}  // namespace

Result<LeaseState> read_lease(const Store& store) {
  return guarded(store, "reading the lease", [&]() -> Result<LeaseState> { return lease_row(connection(store)); });
}

Result<LeaseState> Lease::read() const {
  return guarded(std::string_view(name_), "reading the lease", [&]() -> Result<LeaseState> { return lease_row(*db_); });
}

Status fence_writes(Store& store, std::int64_t epoch, std::string_view holder) {
  if (!store.is_postgres()) return {};
  return guarded(store, "carrying the epoch", [&]() -> Status {
    connection(store)
        .query("SELECT set_config('application_name', $1, false), set_config('rondo.epoch', $2, false)",
               {holder, std::to_string(epoch)})
        ->next();
    return {};
  });
}

std::string Lease::new_holder_name() {
  std::random_device device;
  return fmt::format("rondo-serve-{}-{:08x}", ::getpid(), device());
}

Result<Lease> Lease::connect(const StoreLocation& where, std::string holder) {
  if (where.kind != StoreLocation::Kind::kPostgres)
    return Error::unsupported(
        fmt::format("{}: a lease needs a PostgreSQL store (an SQLite store serves one process)", where.name()));
  RONDO_ASSIGN_OR_RETURN(std::unique_ptr<db::Connection> db, connect_postgres(where, holder));
  // A renewal or a takeover that cannot finish in time fails rather than hangs: the caller then
  // counts the lease as lost (or not taken) and tries again.
  RONDO_RETURN_IF_ERROR(guarded(where.name(), "setting the lease's session up", [&]() -> Status {
    db->exec_script("SET lock_timeout = 2000; SET statement_timeout = 5000; SET client_min_messages = warning");
    return {};
  }));
  return Lease(where.name(), std::move(holder), std::move(db));
}

Lease::Lease(std::string name, std::string holder, std::unique_ptr<db::Connection> db)
    : name_(std::move(name)), holder_(std::move(holder)), db_(std::move(db)) {}
Lease::Lease(Lease&& other) noexcept = default;
Lease& Lease::operator=(Lease&& other) noexcept = default;
Lease::~Lease() = default;

Result<std::optional<std::int64_t>> Lease::try_take(Duration stale_after) {
  if (epoch_) return epoch_;
  return guarded(std::string_view(name_), "taking the lease", [&]() -> Result<std::optional<std::int64_t>> {
    db::Connection& db = *db_;
    const bool free =
        db::query_int64(db, "SELECT CASE WHEN pg_try_advisory_lock($1, $2) THEN 1 ELSE 0 END",
                        {std::int64_t{kApplicationId}, kLeaseLockKey}) == 1;
    auto rows = db.query(fmt::format("SELECT holder, {} - renewed_ms FROM lease WHERE id = 1", kServerNowMs));
    if (!rows->next()) return Error::storage(fmt::format("{}: taking the lease: the lease row is missing", name_));
    const std::string previous = rows->text(0);
    const std::int64_t age_ms = rows->int64(1);
    rows.reset();
    if (!free) {
      // Held, and renewed lately: the active is alive. Renewed too long ago: it is frozen or cut
      // off; its sessions are ended, and with them its lock.
      if (age_ms > stale_after.count()) end_sessions_of(db, previous);
      return std::optional<std::int64_t>{};
    }
    // Ours from here; a failure below lets go of the lock again (it stacks per try).
    struct UnlockUnlessTaken {
      db::Connection& db;
      bool taken = false;
      ~UnlockUnlessTaken() {
        if (taken) return;
        try {
          db.query("SELECT pg_advisory_unlock($1, $2)", {std::int64_t{kApplicationId}, kLeaseLockKey})->next();
        } catch (const db::Failure&) {  // a lost connection has let go of it already
        }
      }
    } unlock{db};
    // What is left of the previous holder (a write connection whose process is frozen or
    // partitioned away) ends first: a write of it in progress holds the lease row, which the
    // update below would otherwise wait for.
    if (previous != holder_) end_sessions_of(db, previous);
    WriteTx tx(db);
    const std::optional<std::int64_t> epoch = db::query_int64(
        db,
        fmt::format("UPDATE lease SET epoch = epoch + 1, holder = $1, taken_ms = {0}, renewed_ms = {0} "
                    "WHERE id = 1 RETURNING epoch",
                    kServerNowMs),
        {holder_});
    if (!epoch) return Error::storage(fmt::format("{}: taking the lease: the lease row is missing", name_));
    tx.commit();
    unlock.taken = true;
    epoch_ = *epoch;
    return epoch_;
  });
}

Status Lease::renew() {
  if (!epoch_) return Error{ErrorCode::kConflict, fmt::format("{}: renewing the lease: it is not held", name_)};
  return guarded(std::string_view(name_), "renewing the lease", [&]() -> Status {
    const std::int64_t changed =
        db_->exec(fmt::format("UPDATE lease SET renewed_ms = {} WHERE id = 1 AND epoch = $1 AND holder = $2",
                              kServerNowMs),
                  {*epoch_, holder_});
    if (changed != 1)
      return Error{ErrorCode::kConflict,
                   fmt::format("{}: renewing the lease: epoch {} is over (another rondo serve took the lease)", name_,
                               *epoch_)};
    return {};
  });
}

void Lease::release() {
  if (!epoch_ || !db_) return;
  epoch_.reset();
  try {
    db_->query("SELECT pg_advisory_unlock($1, $2)", {std::int64_t{kApplicationId}, kLeaseLockKey})->next();
  } catch (const db::Failure&) {  // a lost connection has let go of the lock already
  }
}

}  // namespace rondo::store
