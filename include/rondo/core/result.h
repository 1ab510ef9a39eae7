// Errors as values: `Error` names what went wrong and where, `Result<T>` is a value or an Error.
//
//   Result<TopoMap> map = load_map("office.yaml");
//   if (!map) { std::cerr << map.error().message << '\n'; return 2; }
//   use(*map);
//
// Exceptions are kept for misuse (a broken invariant in our own code), never for bad input.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

namespace rondo {

// What kind of failure an Error is. The command line maps these to exit codes: the input kinds
// (kInvalidInput, kNotFound) give 2, everything else 1.
enum class ErrorCode {
  kInvalidInput,  // malformed or meaningless input: a file, a field, a request
  kNotFound,      // a named thing (file, node, task) does not exist
  kConflict,      // the request contradicts the current state, e.g. cancelling a finished task
  kIo,            // the operating system refused a read or write
  kStorage,       // the database failed (locked, corrupt, full)
  kUnsupported,   // a valid request this build cannot do
  kInternal,      // a bug in rondo
};

const char* to_string(ErrorCode code);

struct Error {
  ErrorCode code = ErrorCode::kInternal;
  std::string message;  // for a person: where and what, e.g. "map.yaml:12: edges[3].to: no node 'B'"

  static Error invalid(std::string message) { return {ErrorCode::kInvalidInput, std::move(message)}; }
  static Error not_found(std::string message) { return {ErrorCode::kNotFound, std::move(message)}; }
  static Error io(std::string message) { return {ErrorCode::kIo, std::move(message)}; }
  static Error storage(std::string message) { return {ErrorCode::kStorage, std::move(message)}; }
  static Error unsupported(std::string message) { return {ErrorCode::kUnsupported, std::move(message)}; }
  static Error internal(std::string message) { return {ErrorCode::kInternal, std::move(message)}; }

  // The same error with "prefix: " in front of its message, e.g. the file it came from.
  [[nodiscard]] Error with_context(const std::string& prefix) const& {
    return {code, prefix + ": " + message};
  }
  bool operator==(const Error&) const = default;
};

// Thrown only when a Result is read the wrong way (value() of an error): a bug, not bad input.
class BadResultAccess : public std::logic_error {
 public:
  explicit BadResultAccess(const Error& e) : std::logic_error("value() of an error: " + e.message) {}
};

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  Result(Error error) : v_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return std::holds_alternative<T>(v_); }
  explicit operator bool() const { return ok(); }

  T& value() & { check(); return std::get<T>(v_); }
  const T& value() const& { check(); return std::get<T>(v_); }
  T&& value() && { check(); return std::get<T>(std::move(v_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T&& operator*() && { return std::move(*this).value(); }

  // Precondition: !ok().
  const Error& error() const {
    if (ok()) throw std::logic_error("error() of a successful Result");
    return std::get<Error>(v_);
  }

 private:
  void check() const {
    if (!ok()) throw BadResultAccess(std::get<Error>(v_));
  }
  std::variant<T, Error> v_;
};

// The outcome of an operation that returns nothing on success.
template <>
class [[nodiscard]] Result<void> {
 public:
  Result() = default;
  Result(Error error) : error_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return !error_.has_value(); }
  explicit operator bool() const { return ok(); }
  const Error& error() const {
    if (ok()) throw std::logic_error("error() of a successful Result");
    return *error_;
  }

 private:
  std::optional<Error> error_;
};

using Status = Result<void>;

}  // namespace rondo

// Early return of an error, for functions that return a Result:
//   RONDO_ASSIGN_OR_RETURN(auto map, load_map(file));    // declares `map` on success
//   RONDO_RETURN_IF_ERROR(validate(task));
#define RONDO_CONCAT_INNER_(a, b) a##b
#define RONDO_CONCAT_(a, b) RONDO_CONCAT_INNER_(a, b)
#define RONDO_ASSIGN_OR_RETURN(lhs, expr) RONDO_ASSIGN_OR_RETURN_IMPL_(RONDO_CONCAT_(rondo_result_, __LINE__), lhs, expr)
#define RONDO_ASSIGN_OR_RETURN_IMPL_(tmp, lhs, expr) \
  auto tmp = (expr);                                  \
  if (!tmp.ok()) return tmp.error();                  \
  lhs = std::move(tmp).value()
#define RONDO_RETURN_IF_ERROR(expr)                                          \
  do {                                                                       \
    if (auto rondo_status_ = (expr); !rondo_status_.ok()) return rondo_status_.error(); \
  } while (false)
