#pragma once
// A CSV field in double quotes (RFC 4180: a quote inside is doubled), for free text such as
// descriptions that may hold commas.
#include <string>
#include <string_view>

namespace cdb {

[[nodiscard]] inline std::string csvQuoted(std::string_view text) {
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace cdb
