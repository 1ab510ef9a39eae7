#include "rondo/store/requests.h"

#include <fmt/format.h>

#include "db/dialect.h"
#include "event_rows.h"
#include "request_rows.h"
#include "store_access.h"
#include "write_tx.h"

namespace rondo::store {
namespace {

constexpr const char* kSelect = "SELECT id, queued_ms, source, sentence, body_json, taken_ms, outcome FROM requests";

Result<std::vector<RequestRow>> read_rows(const Store& store, const std::string& sql) {
  return guarded(store, "reading the request queue", [&]() -> Result<std::vector<RequestRow>> {
    auto query = connection(store).query(sql);
    std::vector<RequestRow> out;
    while (query->next()) {
      RequestRow r;
      r.id = query->int64(0);
      r.queued = time_from_db(query->int64(1));
      r.source = query->text(2);
      r.sentence = query->text(3);
      r.body = Json::parse(query->text(4), nullptr, /*allow_exceptions=*/false);
      if (r.body.is_discarded())
        return Error::storage(
            fmt::format("{}: request {}: the stored JSON does not parse", store.name(), r.id));
      if (!query->is_null(5)) r.taken = time_from_db(query->int64(5));
      r.outcome = query->text(6);
      out.push_back(std::move(r));
    }
    return out;
  });
}

}  // namespace

Status mark_request_taken(db::Connection& db, std::string_view store_name, const RequestTaken& taken) {
  const std::int64_t marked =
      db.exec("UPDATE requests SET taken_ms = $1, outcome = $2 WHERE id = $3 AND taken_ms IS NULL",
              {to_db(taken.at), taken.outcome.empty() ? std::string("taken") : taken.outcome, taken.id});
  if (marked == 1) {
    for (const auto& [key, value] : taken.meta)
      db.exec("INSERT INTO meta (key, value) VALUES ($1, $2) ON CONFLICT (key) DO UPDATE SET value = excluded.value",
              {key, value});
    return {};
  }
  if (!db::query_int64(db, "SELECT 1 FROM requests WHERE id = $1", {taken.id}))
    return Error::not_found(fmt::format("{}: no request {}", store_name, taken.id));
  return Error{ErrorCode::kConflict, fmt::format("{}: request {} is already taken", store_name, taken.id)};
}

Result<std::int64_t> queue_request(Store& store, const RequestRow& request) {
  if (!request.body.is_object())
    return Error::invalid(fmt::format("{}: a request's body must be a JSON object", store.name()));
  return guarded(store, "queueing a request", [&]() -> Result<std::int64_t> {
    db::Connection& db = connection(store);
    WriteTx tx(db);
    const auto id = db::query_int64(
        db, "INSERT INTO requests (queued_ms, source, sentence, body_json) VALUES ($1, $2, $3, $4) RETURNING id",
        {to_db(request.queued), request.source, request.sentence, request.body.dump()});
    if (id) db::notify_request_queued(db, *id);  // a running service that LISTENs takes it at once
    tx.commit();
    return id.value_or(0);
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
    db::Connection& db = connection(store);
    WriteTx tx(db);
    RONDO_RETURN_IF_ERROR(mark_request_taken(db, store.name(), taken));
    if (event) append_event_row(db, *event);
    tx.commit();
    return {};
  });
}

}  // namespace rondo::store
