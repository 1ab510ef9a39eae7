#include <libpq-fe.h>

#include <fmt/format.h>

#include <memory>

#include "rondo/store/store.h"

namespace rondo::store {
namespace {

bool is_postgres_url(std::string_view text) {
  return text.starts_with("postgresql://") || text.starts_with("postgres://");
}

}  // namespace

StoreLocation StoreLocation::sqlite(std::filesystem::path file) {
  return StoreLocation{.kind = Kind::kSqlite, .file = std::move(file), .url = {}, .password_file = std::nullopt};
}

Result<StoreLocation> StoreLocation::postgres(std::string url, std::optional<std::filesystem::path> password_file) {
  char* why = nullptr;
  PQconninfoOption* options = PQconninfoParse(url.c_str(), &why);
  if (options == nullptr) {
    std::string message = why ? why : "libpq cannot parse it";
    PQfreemem(why);
    while (!message.empty() && message.back() == '\n') message.pop_back();
    // The URL is not repeated: one that does not parse may hold a password.
    return Error::invalid(fmt::format("store URL: libpq cannot read it: {}", message));
  }
  const std::unique_ptr<PQconninfoOption, decltype(&PQconninfoFree)> owned(options, &PQconninfoFree);
  for (const PQconninfoOption* o = options; o->keyword != nullptr; ++o) {
    if (std::string_view(o->keyword) == "password" && o->val != nullptr && *o->val != '\0')
      return Error::invalid(
          "store URL: holds a password, which is refused (it would show in process lists, shell histories and "
          "logs): give it in a password_file, PGPASSWORD or ~/.pgpass");
  }
  return StoreLocation{.kind = Kind::kPostgres, .file = {}, .url = std::move(url), .password_file = std::move(password_file)};
}

Result<StoreLocation> StoreLocation::parse(std::string_view text) {
  if (is_postgres_url(text)) return postgres(std::string(text));
  if (text.empty()) return Error::invalid("store: an empty name (a file, or a postgresql:// URL)");
  return sqlite(std::filesystem::path(text));
}

std::string StoreLocation::name() const {
  return kind == Kind::kSqlite ? file.string() : url;
}

}  // namespace rondo::store
