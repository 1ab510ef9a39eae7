#include "db/connection.h"

namespace rondo::store::db {

std::optional<std::int64_t> query_int64(Connection& db, std::string_view sql, const Params& params) {
  auto rows = db.query(sql, params);
  if (!rows->next() || rows->is_null(0)) return std::nullopt;
  return rows->int64(0);
}

std::optional<std::string> query_text(Connection& db, std::string_view sql, const Params& params) {
  auto rows = db.query(sql, params);
  if (!rows->next() || rows->is_null(0)) return std::nullopt;
  return rows->text(0);
}

}  // namespace rondo::store::db
