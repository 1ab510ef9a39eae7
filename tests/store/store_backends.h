// Test helper: the store tests run on both backends. A test suite derives from BackendTest (a
// TEST_P fixture over Backend) and is instantiated with RONDO_ON_BOTH_BACKENDS; each test gets a
// fresh, unopened store: a temporary SQLite file, or a new database in the binary's PostgreSQL
// cluster (pg_cluster.h).
//
//   class Events : public BackendTest {};
//   TEST_P(Events, AppendsInOrder) { Store db = open_store(); ... }
//   RONDO_ON_BOTH_BACKENDS(Events);
//
// The PostgreSQL instances are named ".../Postgres": CTest runs them together in one process
// (tests/store/CMakeLists.txt), so one cluster serves them all.
#pragma once

#include <SQLiteCpp/Database.h>
#include <gtest/gtest.h>

#include <optional>
#include <stdexcept>
#include <string>

#include "rondo/store/store.h"
#include "store/pg_cluster.h"
#include "store/temp_db.h"

namespace rondo::store::testing {

enum class Backend { kSqlite, kPostgres };

inline void PrintTo(Backend backend, std::ostream* out) {
  *out << (backend == Backend::kSqlite ? "SQLite" : "PostgreSQL");
}

inline std::string backend_name(const ::testing::TestParamInfo<Backend>& info) {
  return info.param == Backend::kSqlite ? "Sqlite" : "Postgres";
}

// A fresh store of one backend, removed (SQLite) or left to the cluster's end (PostgreSQL).
class TempStore {
 public:
  explicit TempStore(Backend backend) : backend_(backend) {
    if (backend == Backend::kPostgres) url_ = PgCluster::get().create_database();
  }
  Backend backend() const { return backend_; }
  StoreLocation location() const {
    if (backend_ == Backend::kSqlite) return StoreLocation::sqlite(file_.path());
    return StoreLocation::postgres(url_).value();
  }
  Result<Store> open(const StoreOptions& options = {}) const { return Store::open(location(), options); }
  // Runs `sql` on the store's database outside rondo (its own connection, as the database's owner):
  // the error text, empty when the database allowed it.
  std::string raw_sql(const std::string& sql) const {
    if (backend_ == Backend::kPostgres) return run_sql(url_, sql);
    try {
      SQLite::Database raw(file_.path(), SQLite::OPEN_READWRITE);
      raw.exec(sql);
      return "";
    } catch (const SQLite::Exception& e) {
      return e.what();
    }
  }
  // The SQLite file (its -wal beside it); only for SQLite.
  const TempDb& file() const { return file_; }
  // The libpq URL; only for PostgreSQL.
  const std::string& url() const { return url_; }

 private:
  Backend backend_;
  TempDb file_;
  std::string url_;
};

class BackendTest : public ::testing::TestWithParam<Backend> {
 protected:
  void SetUp() override {
    try {
      temp_.emplace(GetParam());
    } catch (const std::exception& e) {
      FAIL() << e.what();
    }
  }
  bool postgres() const { return GetParam() == Backend::kPostgres; }
  TempStore& temp() { return *temp_; }
  // Opens the test's store; a failure to open fails the test.
  Store open_store(const StoreOptions& options = {}) {
    auto opened = temp_->open(options);
    if (!opened) throw std::runtime_error("cannot open the test store: " + opened.error().message);
    return std::move(*opened);
  }

 private:
  std::optional<TempStore> temp_;
};

#define RONDO_ON_BOTH_BACKENDS(Suite)                                                                          \
  INSTANTIATE_TEST_SUITE_P(Backends, Suite,                                                                    \
                           ::testing::Values(::rondo::store::testing::Backend::kSqlite,                       \
                                             ::rondo::store::testing::Backend::kPostgres),                    \
                           ::rondo::store::testing::backend_name)

}  // namespace rondo::store::testing
