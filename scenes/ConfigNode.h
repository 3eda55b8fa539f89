#pragma once
// Typed, checked reads from a parsed YAML document. Every failure is one InputError line:
//   <file>:<line>: <key path>: expected <what>, got <what>
// so the loader only says what each key must be.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "scenes/ConfigLimits.h"
#include "scenes/ScenarioConfig.h"

namespace cdb {

class ConfigNode {
 public:
  // The document's root; `file` names it in messages.
  static ConfigNode root(const YAML::Node& node, const std::string& file);

  // A key of this map; absent keys give a node that is not present() (its line is the map's).
  [[nodiscard]] ConfigNode operator[](std::string_view key) const;
  // The elements of this list; fails unless it is a list.
  [[nodiscard]] std::vector<ConfigNode> items(std::string_view expected) const;

  [[nodiscard]] bool present() const { return node_.IsDefined(); }
  [[nodiscard]] bool isMap() const { return node_.IsMap(); }
  [[nodiscard]] bool isList() const { return node_.IsSequence(); }
  [[nodiscard]] bool isScalar() const { return node_.IsScalar(); }
  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] int line() const { return line_; }

  // Fails unless this is a map whose keys are all in `allowed`, each once; `what` names an
  // allowed key in the message.
  void expectKeys(std::initializer_list<std::string_view> allowed,
                  std::string_view what = "a known key") const;
  // Fails with "expected <expected> (required), got no such key" when absent.
  void require(std::string_view expected) const;

  [[nodiscard]] double number(NumberLimits limits) const;
  [[nodiscard]] long long integer(IntLimits limits) const;
  [[nodiscard]] std::uint64_t unsignedInteger() const;
  [[nodiscard]] bool boolean() const;
  [[nodiscard]] std::string string(bool allowEmpty = false) const;
  [[nodiscard]] Vec3 vec3(NumberLimits limits) const;
  // A list of integers, a single integer, or a range map {from, to, step}; values within
  // `limits`, no value twice.
  [[nodiscard]] std::vector<int> intList(IntLimits limits) const;

  // How this value reads in a message: 0.5, 'fast', a list of 2 items, a map, an empty value.
  [[nodiscard]] std::string describe() const;
  [[noreturn]] void fail(std::string_view expected, std::string_view got) const;
  [[noreturn]] void fail(std::string_view expected) const { fail(expected, describe()); }

 private:
  ConfigNode(YAML::Node node, std::string path, int line, std::shared_ptr<const std::string> file);
  [[nodiscard]] ConfigNode child(const YAML::Node& node, std::string path) const;
  [[nodiscard]] const std::string& scalarOrFail(std::string_view expected) const;

  YAML::Node node_;
  std::string path_;
  int line_ = 1;  // 1-based
  std::shared_ptr<const std::string> file_;
};

// "(0, 1]"; "a number in (0, 1]"; "an integer in [1, 16384]".
[[nodiscard]] std::string describeInterval(NumberLimits limits);
[[nodiscard]] std::string describeLimits(NumberLimits limits);
[[nodiscard]] std::string describeLimits(IntLimits limits);

}  // namespace cdb
