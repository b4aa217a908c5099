// Job files: YAML read with every key accounted for, every message placed, every path resolved.
//
// ConfigNode wraps a yaml-cpp node with where it came from and its key path, so every message says where
// ("edit.yaml:12:5 (drags[1].offset): expected 2 or 3 numbers, found 4"). Keys are tracked: after a job is read,
// finish() reports each key nobody asked for, with its line — a misspelt option is an error, never ignored. A key
// written twice in one mapping is an error naming both lines (YAML leaves it open; yaml-cpp keeps the first).
//
// Layers. A job can be assembled from several places, each key remembering its own:
//  * layered(): whole top-level keys of later layers replace earlier ones (a `throng run` step: the keys of its
//    `job:` file, then the step's own);
//  * with_overrides(): single values set from the command line, by --set or by a flag (Override), so a message
//    about one names what the user typed ("--set agents.count=-5: ...", "--margin -1: ...").
// Paths (as_path) resolve against the folder of the file that wrote them; values from the command line against
// the working directory.
//
// The visitors of an Options schema (throng/core/schema.h): OptionReader fills the struct from a ConfigNode,
// range-checked with the line of the bad value; OptionWriter writes the effective values (for --print-config and
// the provenance stored in every output file).
#pragma once

#include <throng/core/schema.h>

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace throng {

namespace detail {
struct ConfigTracking;  // which keys of a mapping were asked for (config.cpp)
struct ConfigOrigins;   // the file each top-level key came from (config.cpp)
}  // namespace detail

/// One value set from the command line: `--set key.path=value`, or a flag that stands for a job key.
struct Override {
  std::string path;   ///< key path ("agents.count")
  YAML::Node value;   ///< a scalar, a sequence or a mapping, without marks (it has no place in any file)
  std::string origin; ///< what the user typed, for messages ("--set agents.count=-5", "--margin -1")
};

/// Parses `key.path=value` (the --set flag): the value as YAML (a scalar, [a, b], {k: v}). ConfigError for a
/// malformed one, naming it.
[[nodiscard]] Override parse_set(const std::string& text);

/// Applies `key.path=value` texts to a YAML mapping, values without marks (a message about one must not point at
/// the job's line 1). ConfigError for a malformed one. ConfigNode::with_overrides does this and names the
/// overrides in messages.
void apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides);

class ConfigNode {
 public:
  /// Parses a YAML file. IoError if it cannot be read, ConfigError (with line and column) if it is not YAML or
  /// writes a key twice.
  static ConfigNode load_file(const std::filesystem::path& path);
  /// Parses YAML text; `source` names it in messages (and its folder, if any, anchors relative paths).
  static ConfigNode parse(const std::string& text, const std::string& source);
  /// Wraps an existing node; `source` names it in messages and anchors relative paths.
  ConfigNode(YAML::Node node, std::string source, std::string key_path = {});
  /// Top-level mappings merged: each later layer's keys replace the earlier ones' (a null layer adds nothing),
  /// each key keeping its own file for messages and paths. `source` names the whole in messages. ConfigError
  /// for a layer that is not a mapping.
  static ConfigNode layered(const std::vector<ConfigNode>& layers, const std::string& source);

  /// This job (a mapping, or empty) with `overrides` applied, read afresh (no key marked used). Messages about an
  /// overridden value name the override instead of a place in the file.
  [[nodiscard]] ConfigNode with_overrides(const std::vector<Override>& overrides) const;
  /// The same for `key.path=value` texts (the --set flag).
  [[nodiscard]] ConfigNode with_overrides(const std::vector<std::string>& set) const;

  /// "file:line:column (key.path)" for messages about this node ("--set ..." for a value from the command line).
  [[nodiscard]] std::string where() const;
  /// The name of where this node came from (a file, "--set ...", or the name given).
  [[nodiscard]] std::string source() const;
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
  /// A sequence of integers.
  [[nodiscard]] std::vector<std::int64_t> as_ints() const;
  /// A file or folder named in the job: relative paths resolve against the folder of the file that wrote them,
  /// values from the command line against the working directory. ConfigError for an empty text.
  [[nodiscard]] std::filesystem::path as_path() const;

  /// Throws ConfigError listing every key of this mapping (and of every mapping reached through at/find/elements)
  /// that was never asked for, each with its line, and the keys that were known at that place.
  void finish() const;

  /// Throws ConfigError "<where>: <message>".
  [[noreturn]] void fail(const std::string& message) const;

 private:
  using Tracking = detail::ConfigTracking;
  using Origins = detail::ConfigOrigins;
  ConfigNode(YAML::Node node, std::shared_ptr<const Origins> origins, std::string path, std::shared_ptr<Tracking> tracking);
  ConfigNode child(const YAML::Node& node, const std::string& path) const;
  /// The override that set this node's value, if it came from the command line.
  [[nodiscard]] const Override* override_here() const;

  YAML::Node node_;
  std::shared_ptr<const Origins> origins_;
  std::string path_;
  std::shared_ptr<Tracking> tracking_;
};

/// Fills fields from a mapping; absent keys keep their defaults; values are range-checked (ConfigError).
class OptionReader final : public OptionBinder {
 public:
  explicit OptionReader(const ConfigNode& node) : node_(node) {}
  using OptionBinder::choice;
  using OptionBinder::field;
  void field(const Field& f, double& value) override;
  void field(const Field& f, int& value) override;
  void field(const Field& f, std::size_t& value) override;
  void field(const Field& f, std::int64_t& value) override;
  void field(const Field& f, bool& value) override;
  void field(const Field& f, std::string& value) override;
  void field(const Field& f, std::vector<double>& value) override;
  void field(const Field& f, std::vector<std::int64_t>& value) override;
  void field(const Field& f, std::int64_t& value, const Words& words) override;
  void choice(const Field& f, std::string& value, const std::vector<std::string>& allowed) override;
  void section(const char* key, const std::function<void(OptionBinder&)>& body) override;
  bool present(const Field& f, bool has_value) override;

 private:
  ConfigNode node_;
};

/// YAML text of a node, block style.
[[nodiscard]] std::string to_yaml_text(const YAML::Node& node);

/// A YAML scalar holding `value` in the shortest form that reads back to the same double (yaml-cpp's own
/// conversion writes 17 digits: 0.3 becomes 0.29999999999999999). Use it for every double in an effective config.
[[nodiscard]] YAML::Node yaml_number(double value);
/// A flow sequence of numbers ([x, y]), each as yaml_number writes it.
[[nodiscard]] YAML::Node yaml_numbers(const std::vector<double>& values);
/// A flow sequence of integers.
[[nodiscard]] YAML::Node yaml_integers(const std::vector<std::int64_t>& values);

/// Writes every field into a YAML mapping, numbers as yaml_number writes them.
class OptionWriter final : public OptionBinder {
 public:
  explicit OptionWriter(YAML::Node node) : node_(std::move(node)) {}
  using OptionBinder::choice;
  using OptionBinder::field;
  void field(const Field& f, double& value) override { node_[f.key] = yaml_number(value); }
  void field(const Field& f, int& value) override { node_[f.key] = value; }
  void field(const Field& f, std::size_t& value) override { node_[f.key] = static_cast<std::uint64_t>(value); }
  void field(const Field& f, std::int64_t& value) override { node_[f.key] = value; }
  void field(const Field& f, bool& value) override { node_[f.key] = value; }
  void field(const Field& f, std::string& value) override { node_[f.key] = value; }
  void field(const Field& f, std::vector<double>& value) override { node_[f.key] = yaml_numbers(value); }
  void field(const Field& f, std::vector<std::int64_t>& value) override { node_[f.key] = yaml_integers(value); }
  /// The word standing for the value, if one does.
  void field(const Field& f, std::int64_t& value, const Words& words) override;
  void choice(const Field& f, std::string& value, const std::vector<std::string>&) override { node_[f.key] = value; }
  void section(const char* key, const std::function<void(OptionBinder&)>& body) override;
  bool present(const Field&, bool has_value) override { return has_value; }

  [[nodiscard]] const YAML::Node& yaml() const noexcept { return node_; }

 private:
  YAML::Node node_;
};

/// Reads the fields `describe` declares from `job` (OptionReader).
template <class Options>
void read_options(const ConfigNode& job, void (*describe)(OptionBinder&, Options&), Options& options) {
  OptionReader reader(job);
  describe(reader, options);
}

/// Writes the fields `describe` declares into `out`, a mapping (OptionWriter).
template <class Options>
void write_options(YAML::Node& out, void (*describe)(OptionBinder&, Options&), const Options& options) {
  Options copy = options;
  OptionWriter writer(out);
  describe(writer, copy);
}

}  // namespace throng
