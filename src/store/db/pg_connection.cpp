#include "db/pg_connection.h"

#include <libpq-fe.h>

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <string_view>
#include <type_traits>
#include <vector>

namespace rondo::store::db {
namespace {

// libpq's messages end with a newline (and may hold several lines): one line for ours.
std::string one_line(std::string_view text) {
  std::string out;
  for (char c : text) out += (c == '\n' || c == '\r') ? ' ' : c;
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

// Frees a PGresult on every way out.
struct Result {
  PGresult* r;
  ~Result() { PQclear(r); }
};

// The text form of each parameter (libpq's text format; the server types them).
struct TextParams {
  std::vector<std::string> storage;
  std::vector<const char*> values;
  explicit TextParams(const Params& params) {
    storage.reserve(params.size());
    for (const Param& p : params) {
      std::visit(
          [&](const auto& v) {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, std::monostate>)
              storage.emplace_back();
            else if constexpr (std::is_same_v<T, std::string>)
              storage.push_back(v);
            else
              storage.push_back(fmt::format("{}", v));  // shortest text that reads back the same
          },
          p.value());
    }
    for (std::size_t i = 0; i < params.size(); ++i) values.push_back(params[i].is_null() ? nullptr : storage[i].c_str());
  }
};

[[noreturn]] void fail(pg_conn* conn, PGresult* r) {
  const char* state = r ? PQresultErrorField(r, PG_DIAG_SQLSTATE) : nullptr;
  std::string message = one_line(r ? PQresultErrorMessage(r) : PQerrorMessage(conn));
  if (message.empty()) message = one_line(PQerrorMessage(conn));
  if (PQstatus(conn) == CONNECTION_BAD) throw Failure(FailureKind::kStorage, "the connection is lost: " + message);
  if (state && std::string_view(state).starts_with("XX0")) throw Failure(FailureKind::kCorrupt, message);
  if (state && std::string_view(state) == "RF001") throw Failure(FailureKind::kFenced, message);  // pg_schema.cpp, v6
  throw Failure(FailureKind::kStorage, message);
}

bool succeeded(const PGresult* r) {
  const ExecStatusType status = r ? PQresultStatus(r) : PGRES_FATAL_ERROR;
  return status == PGRES_COMMAND_OK || status == PGRES_TUPLES_OK;
}

void ignore_notice(void* /*arg*/, const char* /*message*/) {}

std::int64_t parse_int64(const char* text) {
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text, &end, 10);
  if (errno != 0 || end == text) {  // a numeric aggregate ("12.0"): read as a real
    return static_cast<std::int64_t>(std::strtod(text, nullptr));
  }
  return v;
}

class PgRows final : public Rows {
 public:
  explicit PgRows(PGresult* r) : result_(r), count_(PQntuples(r)) {}
  ~PgRows() override { PQclear(result_); }
  PgRows(const PgRows&) = delete;
  PgRows& operator=(const PgRows&) = delete;

  bool next() override { return ++row_ < count_; }
  bool is_null(int column) const override { return PQgetisnull(result_, row_, column) != 0; }
  std::int64_t int64(int column) const override {
    return is_null(column) ? 0 : parse_int64(PQgetvalue(result_, row_, column));
  }
  double real(int column) const override {
    return is_null(column) ? 0.0 : std::strtod(PQgetvalue(result_, row_, column), nullptr);
  }
  std::string text(int column) const override {
    return std::string(PQgetvalue(result_, row_, column), static_cast<std::size_t>(PQgetlength(result_, row_, column)));
  }

 private:
  PGresult* result_;
  int count_;
  int row_ = -1;
};

}  // namespace

std::unique_ptr<PgConnection> PgConnection::connect(const PgAddress& address) {
  // Earlier keywords are overridden by what the conninfo names (expand_dbname), later ones override it.
  const std::string timeout = std::to_string(address.connect_timeout.count());
  // TCP keepalives: a server that vanished without closing the connection (a power cut, a
  // partition) is noticed within about 20 s instead of the system's two hours; the server side
  // notices a vanished client the same way (its own tcp_keepalives_* settings).
  std::vector<const char*> keys{"connect_timeout", "application_name", "keepalives", "keepalives_idle",
                                "keepalives_interval", "keepalives_count", "dbname"};
  std::vector<const char*> values{timeout.c_str(), address.application_name.c_str(), "1", "10", "3", "3",
                                  address.conninfo.c_str()};
  if (address.password) {
    keys.push_back("password");
    values.push_back(address.password->c_str());
  }
  keys.push_back(nullptr);
  values.push_back(nullptr);
  pg_conn* conn = PQconnectdbParams(keys.data(), values.data(), /*expand_dbname=*/1);
  if (conn == nullptr) throw Failure(FailureKind::kUnreachable, "libpq could not allocate a connection");
  if (PQstatus(conn) != CONNECTION_OK) {
    const std::string why = one_line(PQerrorMessage(conn));
    PQfinish(conn);
    throw Failure(FailureKind::kUnreachable, why);
  }
  PQsetNoticeProcessor(conn, ignore_notice, nullptr);
  return std::unique_ptr<PgConnection>(new PgConnection(conn));
}

PgConnection::~PgConnection() {
  PQfinish(conn_);
}

PGresult* PgConnection::run(std::string_view sql, const Params& params) {
  const std::string text(sql);
  if (!deferred_.empty()) return run_pipelined(text, params);
  const TextParams p(params);
  PGresult* r = PQexecParams(conn_, text.c_str(), static_cast<int>(p.values.size()), nullptr, p.values.data(), nullptr,
                             nullptr, 0);
  if (!succeeded(r)) {
    Result owned{r};
    fail(conn_, r);
  }
  return r;
}

// The deferred statements and `sql` queued in pipeline mode and synced once: one round trip. The
// server runs them in order and skips the rest after a failure; the first failure is thrown.
PGresult* PgConnection::run_pipelined(const std::string& sql, const Params& params) {
  std::vector<std::string> before;
  before.swap(deferred_);
  if (PQenterPipelineMode(conn_) == 0) fail(conn_, nullptr);
  const TextParams p(params);
  bool sent = true;
  for (const std::string& d : before)
    sent = sent && PQsendQueryParams(conn_, d.c_str(), 0, nullptr, nullptr, nullptr, nullptr, 0) != 0;
  sent = sent && PQsendQueryParams(conn_, sql.c_str(), static_cast<int>(p.values.size()), nullptr, p.values.data(),
                                   nullptr, nullptr, 0) != 0;
  sent = sent && PQpipelineSync(conn_) != 0;
  // Each statement's result is followed by a null; the sync's own result ends the round trip.
  PGresult* failed = nullptr;
  PGresult* last = nullptr;
  std::size_t ends = 0;
  while (sent) {
    PGresult* r = PQgetResult(conn_);
    if (r == nullptr) {
      if (++ends > before.size() + 2) break;  // the connection is gone: no sync will come
      continue;
    }
    const ExecStatusType status = PQresultStatus(r);
    if (status == PGRES_PIPELINE_SYNC) {
      PQclear(r);
      break;
    }
    if (!failed && status != PGRES_PIPELINE_ABORTED && !succeeded(r)) {
      failed = r;
      continue;
    }
    PQclear(last);
    last = r;
  }
  PQexitPipelineMode(conn_);
  if (!sent || failed || last == nullptr) {
    PQclear(last);
    Result owned{failed};
    fail(conn_, failed);
  }
  return last;
}

std::int64_t PgConnection::exec(std::string_view sql, const Params& params) {
  Result r{run(sql, params)};
  const char* tuples = PQcmdTuples(r.r);
  return (tuples && *tuples) ? parse_int64(tuples) : 0;
}

void PgConnection::exec_script(std::string_view sql) {
  std::string text;
  for (const std::string& d : deferred_) text += d + "; ";
  deferred_.clear();
  text += sql;
  // The simple query protocol: several statements in one message, results read to the last.
  if (PQsendQuery(conn_, text.c_str()) == 0) fail(conn_, nullptr);
  PGresult* failed = nullptr;
  while (PGresult* r = PQgetResult(conn_)) {
    const ExecStatusType status = PQresultStatus(r);
    if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK && !failed) {
      failed = r;
      continue;
    }
    PQclear(r);
  }
  if (failed) {
    Result owned{failed};
    fail(conn_, failed);
  }
}

std::unique_ptr<Rows> PgConnection::query(std::string_view sql, const Params& params) {
  return std::make_unique<PgRows>(run(sql, params));
}

void PgConnection::exec_deferred(std::string_view sql) {
  deferred_.emplace_back(sql);
}

bool PgConnection::in_transaction() const {
  if (!deferred_.empty()) return true;  // a deferred BEGIN, or a savepoint's statement inside one
  const PGTransactionStatusType status = PQtransactionStatus(conn_);
  return status == PQTRANS_INTRANS || status == PQTRANS_INERROR || status == PQTRANS_ACTIVE;
}

}  // namespace rondo::store::db
