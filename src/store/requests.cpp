#include "rondo/store/requests.h"

#include <SQLiteCpp/Statement.h>
#include <SQLiteCpp/Transaction.h>

#include <fmt/format.h>

#include "event_rows.h"
#include "request_rows.h"
#include "sqlite_error.h"

namespace rondo::store {
namespace {

constexpr const char* kSelect = "SELECT id, queued_ms, source, sentence, body_json, taken_ms, outcome FROM requests";

Result<std::vector<RequestRow>> read_rows(const Store& store, const std::string& sql) {
  return guarded(store, "reading the request queue", [&]() -> Result<std::vector<RequestRow>> {
    SQLite::Statement query(connection(store), sql);
    std::vector<RequestRow> out;
    while (query.executeStep()) {
      RequestRow r;
      r.id = query.getColumn(0).getInt64();
      r.queued = time_from_db(query.getColumn(1).getInt64());
      r.source = query.getColumn(2).getString();
      r.sentence = query.getColumn(3).getString();
      r.body = Json::parse(query.getColumn(4).getString(), nullptr, /*allow_exceptions=*/false);
      if (r.body.is_discarded())
        return Error::storage(
            fmt::format("{}: request {}: the stored JSON does not parse", store.file().string(), r.id));
      if (!query.getColumn(5).isNull()) r.taken = time_from_db(query.getColumn(5).getInt64());
      r.outcome = query.getColumn(6).getString();
      out.push_back(std::move(r));
    }
    return out;
  });
}

}  // namespace

Status mark_request_taken(SQLite::Database& db, const std::filesystem::path& file, const RequestTaken& taken) {
  SQLite::Statement update(db, "UPDATE requests SET taken_ms = ?, outcome = ? WHERE id = ? AND taken_ms IS NULL");
  update.bind(1, to_db(taken.at));
  update.bind(2, taken.outcome.empty() ? std::string("taken") : taken.outcome);
  update.bind(3, taken.id);
  if (update.exec() == 1) {
    for (const auto& [key, value] : taken.meta) {
      SQLite::Statement set(
          db, "INSERT INTO meta (key, value) VALUES (?, ?) ON CONFLICT (key) DO UPDATE SET value = excluded.value");
      set.bind(1, key);
      set.bind(2, value);
      set.exec();
    }
    return {};
  }
  SQLite::Statement exists(db, "SELECT 1 FROM requests WHERE id = ?");
  exists.bind(1, taken.id);
  if (!exists.executeStep()) return Error::not_found(fmt::format("{}: no request {}", file.string(), taken.id));
  return Error{ErrorCode::kConflict, fmt::format("{}: request {} is already taken", file.string(), taken.id)};
}

Result<std::int64_t> queue_request(Store& store, const RequestRow& request) {
  if (!request.body.is_object())
    return Error::invalid(fmt::format("{}: a request's body must be a JSON object", store.file().string()));
  return guarded(store, "queueing a request", [&]() -> Result<std::int64_t> {
    SQLite::Database& db = connection(store);
    SQLite::Transaction tx(db, SQLite::TransactionBehavior::IMMEDIATE);
    SQLite::Statement insert(db, "INSERT INTO requests (queued_ms, source, sentence, body_json) VALUES (?, ?, ?, ?)");
    insert.bind(1, to_db(request.queued));
    insert.bind(2, request.source);
    insert.bind(3, request.sentence);
    insert.bind(4, request.body.dump());
    insert.exec();
    const std::int64_t id = db.getLastInsertRowid();
    tx.commit();
    return id;
  });
}

Result<std::vector<RequestRow>> waiting_requests(const Store& store) {
  return read_rows(store, std::string(kSelect) + " WHERE taken_ms IS NULL ORDER BY id");
}

Result<std::vector<RequestRow>> list_requests(const Store& store) {
  return read_rows(store, std::string(kSelect) + " ORDER BY id");
}

Status take_request(Store& store, const RequestTaken& taken, const Event* event) {
  return guarded(store, fmt::format("taking request {}", taken.id), [&]() -> Status {
    SQLite::Database& db = connection(store);
    SQLite::Transaction tx(db, SQLite::TransactionBehavior::IMMEDIATE);
    RONDO_RETURN_IF_ERROR(mark_request_taken(db, store.file(), taken));
    if (event) insert_event_row(db, *event);
    tx.commit();
    return {};
  });
}

}  // namespace rondo::store
