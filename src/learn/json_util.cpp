#include "json_util.h"

#include <cmath>

namespace rondo::learn {

Result<double> json_number(const Json& j, const char* key) {
  if (!j.is_object() || !j.contains(key)) return Error::invalid(std::string("model: missing '") + key + "'");
  const Json& v = j[key];
  if (!v.is_number() || !std::isfinite(v.get<double>())) {
    return Error::invalid(std::string("model: '") + key + "' must be a finite number");
  }
  return v.get<double>();
}

Result<std::vector<double>> json_numbers(const Json& j, const char* key) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_array()) {
    return Error::invalid(std::string("model: '") + key + "' must be an array of numbers");
  }
  std::vector<double> out;
  for (const Json& v : j[key]) {
    if (!v.is_number() || !std::isfinite(v.get<double>())) {
      return Error::invalid(std::string("model: '") + key + "' must hold finite numbers only");
    }
    out.push_back(v.get<double>());
  }
  return out;
}

}  // namespace rondo::learn
