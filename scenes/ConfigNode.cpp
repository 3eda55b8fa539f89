#include "scenes/ConfigNode.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <set>
#include <sstream>

#include "core/Errors.h"
#include "scenes/IntList.h"

namespace cdb {
namespace {

std::string formatNumber(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// std::from_chars over the whole text; YAML's optional leading '+' is allowed.
template <class T>
bool parseWhole(std::string_view text, T& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size();
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

}  // namespace

std::string describeInterval(NumberLimits limits) {
  return std::string(limits.minExclusive ? "(" : "[") + formatNumber(limits.min) + ", " +
         formatNumber(limits.max) + "]";
}

std::string describeLimits(NumberLimits limits) {
  return "a number in " + describeInterval(limits);
}

std::string describeLimits(IntLimits limits) {
  return "an integer in [" + std::to_string(limits.min) + ", " + std::to_string(limits.max) + "]";
}

ConfigNode::ConfigNode(YAML::Node node, std::string path, int line,
                       std::shared_ptr<const std::string> file)
    : node_(std::move(node)), path_(std::move(path)), line_(line), file_(std::move(file)) {}

ConfigNode ConfigNode::root(const YAML::Node& node, const std::string& file) {
  return ConfigNode(node, "(top level)", 1, std::make_shared<const std::string>(file))
      .child(node, "(top level)");
}

ConfigNode ConfigNode::child(const YAML::Node& node, std::string path) const {
  int line = line_;
  // Absent keys have no position of their own: report the map that lacks them.
  if (node.IsDefined() && node.Mark().line >= 0) line = node.Mark().line + 1;
  return ConfigNode(node, std::move(path), line, file_);
}

ConfigNode ConfigNode::operator[](std::string_view key) const {
  const std::string path =
      path_ == "(top level)" ? std::string(key) : path_ + "." + std::string(key);
  if (node_.IsMap()) {
    for (const auto& entry : node_) {
      if (!entry.first.IsScalar() || entry.first.Scalar() != key) continue;
      // The key's line, not the value's: an empty value has no line of its own, and a block
      // value starts on the line after its key.
      ConfigNode found = child(entry.second, path);
      if (entry.first.Mark().line >= 0) found.line_ = entry.first.Mark().line + 1;
      return found;
    }
  }
  return ConfigNode(YAML::Node(YAML::NodeType::Undefined), path, line_, file_);
}

std::vector<ConfigNode> ConfigNode::items(std::string_view expected) const {
  if (!node_.IsSequence()) fail(expected);
  std::vector<ConfigNode> out;
  std::size_t i = 0;
  for (const auto& element : node_)
    out.push_back(child(element, path_ + "[" + std::to_string(i++) + "]"));
  return out;
}

void ConfigNode::expectKeys(std::initializer_list<std::string_view> allowed,
                            std::string_view what) const {
  std::string list;
  for (auto k : allowed) list += (list.empty() ? "" : ", ") + std::string(k);
  if (!node_.IsMap()) fail("a map with keys " + list);
  std::set<std::string> seen;
  for (const auto& entry : node_) {
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : std::string("?");
    const ConfigNode at = child(entry.first, path_ == "(top level)" ? key : path_ + "." + key);
    if (!entry.first.IsScalar()) at.fail("a key that is a plain name", at.describe());
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      at.fail(std::string(what) + " (one of " + list + ")", "unknown key '" + key + "'");
    }
    if (!seen.insert(key).second) at.fail("each key once", "'" + key + "' a second time");
  }
}

void ConfigNode::require(std::string_view expected) const {
  if (!present()) fail(std::string(expected) + " (required)", "no such key");
}

std::string ConfigNode::describe() const {
  if (!node_.IsDefined()) return "no such key";
  if (node_.IsNull()) return "an empty value";
  if (node_.IsSequence()) {
    return "a list of " + std::to_string(node_.size()) + (node_.size() == 1 ? " item" : " items");
  }
  if (node_.IsMap()) return "a map";
  double ignored = 0;
  const std::string& s = node_.Scalar();
  if (parseWhole(s, ignored)) return s;
  return "'" + s + "'";
}

void ConfigNode::fail(std::string_view expected, std::string_view got) const {
  throw InputError(*file_ + ":" + std::to_string(line_) + ": " + path_ + ": expected " +
                   std::string(expected) + ", got " + std::string(got));
}

const std::string& ConfigNode::scalarOrFail(std::string_view expected) const {
  if (!node_.IsScalar()) fail(expected);
  return node_.Scalar();
}

double ConfigNode::number(NumberLimits limits) const {
  const std::string expected = describeLimits(limits);
  double v = 0;
  if (!parseWhole(scalarOrFail(expected), v) || !std::isfinite(v)) fail(expected);
  const bool aboveMin = limits.minExclusive ? v > limits.min : v >= limits.min;
  if (!aboveMin || v > limits.max) fail(expected);
  return v;
}

long long ConfigNode::integer(IntLimits limits) const {
  const std::string expected = describeLimits(limits);
  long long v = 0;
  if (!parseWhole(scalarOrFail(expected), v) || v < limits.min || v > limits.max) fail(expected);
  return v;
}

std::uint64_t ConfigNode::unsignedInteger() const {
  constexpr std::string_view expected = "an integer in [0, 18446744073709551615]";
  std::uint64_t v = 0;
  const std::string& s = scalarOrFail(expected);
  if (s.starts_with('-') || !parseWhole(s, v)) fail(expected);
  return v;
}

bool ConfigNode::boolean() const {
  constexpr std::string_view expected = "true or false";
  const std::string s = lower(scalarOrFail(expected));
  if (s == "true" || s == "yes" || s == "on") return true;
  if (s == "false" || s == "no" || s == "off") return false;
  fail(expected);
}

std::string ConfigNode::string(bool allowEmpty) const {
  const std::string_view expected = allowEmpty ? "a string" : "a non-empty string";
  if (!node_.IsScalar() || (!allowEmpty && node_.Scalar().empty())) fail(expected);
  return node_.Scalar();
}

Vec3 ConfigNode::vec3(NumberLimits limits) const {
  const std::string expected = "a list of 3 numbers, each in " + describeInterval(limits);
  if (!node_.IsSequence() || node_.size() != 3) fail(expected);
  Vec3 v{};
  const auto elements = items(expected);
  for (std::size_t i = 0; i < 3; ++i) v[i] = elements[i].number(limits);
  return v;
}

std::vector<int> ConfigNode::intList(IntLimits limits) const {
  const std::string each = describeLimits(limits);
  const std::string expected =
      "a list of integers, one integer, or a range {from, to, step}, each " + each;
  std::vector<int> values;
  if (node_.IsScalar()) {
    values.push_back(int(integer(limits)));
  } else if (node_.IsSequence()) {
    if (node_.size() == 0) fail(expected);
    for (const auto& item : items(expected)) values.push_back(int(item.integer(limits)));
  } else if (node_.IsMap()) {
    expectKeys({"from", "to", "step"});
    const ConfigNode from = (*this)["from"], to = (*this)["to"], step = (*this)["step"];
    from.require(each);
    to.require(each);
    step.require("an integer >= 1");
    const int first = int(from.integer(limits));
    const int last = int(to.integer(limits));
    if (last < first) to.fail("an integer >= from (" + std::to_string(first) + ")");
    const int stride = int(step.integer({1, limits.max}));
    values = expandIntRange(first, last, stride);
  } else {
    fail(expected);
  }
  std::set<int> seen;
  for (int v : values) {
    if (!seen.insert(v).second) fail("distinct values", std::to_string(v) + " twice");
  }
  return values;
}

}  // namespace cdb
