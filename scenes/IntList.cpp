#include "scenes/IntList.h"

#include <charconv>
#include <limits>
#include <string>

#include "core/Errors.h"

namespace cdb {
namespace {

std::string_view trimmed(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

// Built by appending: GCC 12 warns falsely (-Wrestrict) on "'" + std::string(...).
std::string quoted(std::string_view s) {
  std::string out;
  out.reserve(s.size() + 2);
  out += '\'';
  out += s;
  out += '\'';
  return out;
}

[[noreturn]] void fail(std::string_view text, std::string_view expected, std::string_view got) {
  throw InputError(quoted(text) + ": expected " + std::string(expected) + ", got " +
                   std::string(got));
}

int parseInt(std::string_view text, std::string_view item) {
  const std::string_view s = trimmed(item);
  std::string_view digits = s;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  int value = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec == std::errc::result_out_of_range && end == digits.data() + digits.size()) {
    fail(text,
         "an integer in [" + std::to_string(std::numeric_limits<int>::min()) + ", " +
             std::to_string(std::numeric_limits<int>::max()) + "]",
         quoted(s));
  }
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size()) {
    fail(text, "an integer", quoted(s));
  }
  return value;
}

}  // namespace

std::vector<int> expandIntRange(int from, int to, int step) {
  if (step < 1 || from > to) {
    throw InputError("range " + std::to_string(from) + ":" + std::to_string(to) + ":" +
                     std::to_string(step) + ": expected from <= to and step >= 1");
  }
  const long long n = (static_cast<long long>(to) - from) / step + 1;
  if (n > kMaxIntListLength) {
    throw InputError("range " + std::to_string(from) + ":" + std::to_string(to) + ":" +
                     std::to_string(step) + ": expected at most " +
                     std::to_string(kMaxIntListLength) + " values, got " + std::to_string(n));
  }
  std::vector<int> values;
  values.reserve(std::size_t(n));
  for (long long i = 0; i < n; ++i) values.push_back(int(from + i * step));
  return values;
}

std::vector<int> parseIntList(std::string_view text) {
  constexpr std::string_view kForm =
      "integers like 500,600 or a range from:to:step like 500:1200:100";
  std::vector<int> values;
  if (trimmed(text).empty()) fail(text, kForm, "nothing");
  std::string_view rest = text;
  while (true) {
    const auto comma = rest.find(',');
    const std::string_view item = trimmed(rest.substr(0, comma));
    if (item.empty()) fail(text, kForm, "an empty item");
    if (item.find(':') == std::string_view::npos) {
      values.push_back(parseInt(text, item));
    } else {
      std::vector<std::string_view> parts;
      std::string_view r = item;
      while (true) {
        const auto colon = r.find(':');
        parts.push_back(r.substr(0, colon));
        if (colon == std::string_view::npos) break;
        r = r.substr(colon + 1);
      }
      if (parts.size() != 3) fail(text, "a range from:to:step", quoted(item));
      const int from = parseInt(text, parts[0]), to = parseInt(text, parts[1]);
      const int step = parseInt(text, parts[2]);
      if (step < 1) fail(text, "a range step >= 1", std::to_string(step));
      if (from > to) {
        fail(text, "a range with from <= to", std::to_string(from) + " > " + std::to_string(to));
      }
      const auto range = expandIntRange(from, to, step);
      values.insert(values.end(), range.begin(), range.end());
    }
    if (values.size() > std::size_t(kMaxIntListLength)) {
      fail(text, "at most " + std::to_string(kMaxIntListLength) + " values", "more");
    }
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  return values;
}

}  // namespace cdb
