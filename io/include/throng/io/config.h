// Job files and options: YAML read with every key accounted for.
//
// ConfigNode wraps a yaml-cpp node with its file name and key path, so every message says where
// ("edit.yaml:12:5 (drags[1].offset): expected 2 or 3 numbers, found 4"). Keys are tracked: after a job is read,
// finish() reports each key nobody asked for, with its line — a misspelt option is an error, never ignored.
//
// OptionBinder describes an Options struct once (keys, ranges, choices) and serves both directions:
// OptionReader fills the struct from a ConfigNode, OptionWriter dumps the effective values as YAML (for
// --print-config and the provenance stored in every output file).
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace throng {

namespace detail {
struct ConfigTracking;  // which keys of a mapping were asked for (config.cpp)
}

class ConfigNode {
 public:
  /// Parses a YAML file. IoError if it cannot be read, ConfigError (with line and column) if it is not YAML.
  static ConfigNode load_file(const std::filesystem::path& path);
  /// Parses YAML text; `source` names it in messages.
  static ConfigNode parse(const std::string& text, const std::string& source);
  /// Wraps an existing node (for example a step of a `throng run` job).
  ConfigNode(YAML::Node node, std::string source, std::string key_path = {});

  /// This job (a mapping, or empty) with `key.path=value` overrides applied (the --set flag; see
  /// apply_overrides), read afresh (no key marked used). Messages about an overridden value name the override
  /// ("--set agents.count=-5: value -5 is out of range ...") instead of a place in the file.
  [[nodiscard]] ConfigNode with_overrides(const std::vector<std::string>& overrides) const;

  /// "file:line:column (key.path)" for messages about this node.
  [[nodiscard]] std::string where() const;
  [[nodiscard]] const std::string& source() const noexcept;
  [[nodiscard]] const std::string& key_path() const noexcept { return path_; }
  [[nodiscard]] const YAML::Node& yaml() const noexcept { return node_; }

  [[nodiscard]] bool is_map() const { return node_.IsMap(); }
  [[nodiscard]] bool is_sequence() const { return node_.IsSequence(); }
  [[nodiscard]] bool is_scalar() const { return node_.IsScalar(); }
  [[nodiscard]] bool is_null() const { return !node_.IsDefined() || node_.IsNull(); }

  /// True if this mapping has `key` (does not mark it used).
  [[nodiscard]] bool has(const std::string& key) const;
  /// The value under `key`, marked used; ConfigError "missing key" if absent or this is not a mapping.
  [[nodiscard]] ConfigNode at(const std::string& key) const;
  /// Marks `key` used and returns its value if present.
  [[nodiscard]] std::optional<ConfigNode> find(const std::string& key) const;
  /// Elements of a sequence (ConfigError if this is not a sequence).
  [[nodiscard]] std::vector<ConfigNode> elements() const;
  /// Keys of a mapping in file order, all marked used (for maps whose keys are data, such as named obstacles).
  [[nodiscard]] std::vector<std::string> keys() const;

  /// Scalar conversions with messages naming where and what was expected.
  [[nodiscard]] double as_double() const;
  [[nodiscard]] std::int64_t as_int() const;
  [[nodiscard]] bool as_bool() const;
  [[nodiscard]] std::string as_string() const;
  /// A sequence of numbers; `sizes` lists the accepted lengths (empty: any).
  [[nodiscard]] std::vector<double> as_doubles(std::initializer_list<std::size_t> sizes = {}) const;

  /// Throws ConfigError listing every key of this mapping (and of every mapping reached through at/find/elements)
  /// that was never asked for, each with its line, and the keys that were known at that place.
  void finish() const;

  /// Throws ConfigError "<where>: <message>".
  [[noreturn]] void fail(const std::string& message) const;

 private:
  using Tracking = detail::ConfigTracking;
  /// Key path and whole text ("agents.count" and "agents.count=-5") of each override applied to this job.
  using Overrides = std::vector<std::pair<std::string, std::string>>;
  ConfigNode(YAML::Node node, std::shared_ptr<const std::string> source, std::string path, std::shared_ptr<Tracking> tracking,
             std::shared_ptr<const Overrides> overrides);
  ConfigNode child(const YAML::Node& node, const std::string& path) const;

  YAML::Node node_;
  std::shared_ptr<const std::string> source_;
  std::string path_;
  std::shared_ptr<Tracking> tracking_;
  std::shared_ptr<const Overrides> overrides_;  // null when none
};

/// Applies `key.path=value` overrides (the --set flag) to a YAML mapping; values are parsed as YAML scalars or
/// flow sequences, and carry no place in any file (a message about one must not point at the job's line 1).
/// ConfigError for a malformed override. ConfigNode::with_overrides does this and names the overrides in messages.
void apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides);

/// A closed or open interval for numeric options.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;

  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  [[nodiscard]] bool contains(double v) const;
  [[nodiscard]] std::string describe() const;  ///< "> 0", "in [0, 1]", ...
};

/// Describes the fields of an Options struct once, for reading and writing (see the file comment).
class OptionBinder {
 public:
  virtual ~OptionBinder() = default;
  virtual void field(const char* key, double& value, Range range = {}) = 0;
  virtual void field(const char* key, int& value, Range range = {}) = 0;
  virtual void field(const char* key, std::size_t& value, Range range = {}) = 0;
  virtual void field(const char* key, bool& value) = 0;
  virtual void field(const char* key, std::string& value) = 0;
  virtual void field(const char* key, std::vector<double>& value) = 0;
  /// A string restricted to `allowed`.
  virtual void choice(const char* key, std::string& value, const std::vector<std::string>& allowed) = 0;
  /// A nested mapping.
  virtual void section(const char* key, const std::function<void(OptionBinder&)>& body) = 0;

  /// An enum through its names.
  template <class E>
  void choice(const char* key, E& value, std::initializer_list<std::pair<const char*, E>> names) {
    std::string text;
    std::vector<std::string> allowed;
    for (const auto& [name, v] : names) {
      allowed.emplace_back(name);
      if (v == value) text = name;
    }
    choice(key, text, allowed);
    for (const auto& [name, v] : names) {
      if (text == name) value = v;
    }
  }
};

/// Fills fields from a mapping; absent keys keep their defaults; values are range-checked (ConfigError).
class OptionReader final : public OptionBinder {
 public:
  explicit OptionReader(const ConfigNode& node) : node_(node) {}
  void field(const char* key, double& value, Range range) override;
  void field(const char* key, int& value, Range range) override;
  void field(const char* key, std::size_t& value, Range range) override;
  void field(const char* key, bool& value) override;
  void field(const char* key, std::string& value) override;
  void field(const char* key, std::vector<double>& value) override;
  void choice(const char* key, std::string& value, const std::vector<std::string>& allowed) override;
  void section(const char* key, const std::function<void(OptionBinder&)>& body) override;
  using OptionBinder::choice;

 private:
  ConfigNode node_;
};

/// Writes every field into a YAML mapping.
class OptionWriter final : public OptionBinder {
 public:
  explicit OptionWriter(YAML::Node node) : node_(std::move(node)) {}
  void field(const char* key, double& value, Range range) override;
  void field(const char* key, int& value, Range range) override;
  void field(const char* key, std::size_t& value, Range range) override;
  void field(const char* key, bool& value) override;
  void field(const char* key, std::string& value) override;
  void field(const char* key, std::vector<double>& value) override;
  void choice(const char* key, std::string& value, const std::vector<std::string>& allowed) override;
  void section(const char* key, const std::function<void(OptionBinder&)>& body) override;
  using OptionBinder::choice;

  [[nodiscard]] const YAML::Node& yaml() const noexcept { return node_; }

 private:
  YAML::Node node_;
};

/// YAML text of a node, block style.
[[nodiscard]] std::string to_yaml_text(const YAML::Node& node);

/// A YAML scalar holding `value` in the shortest form that reads back to the same double (yaml-cpp's own
/// conversion writes 17 digits: 0.3 becomes 0.29999999999999999). Use it for every double in an effective config.
[[nodiscard]] YAML::Node yaml_number(double value);

}  // namespace throng
