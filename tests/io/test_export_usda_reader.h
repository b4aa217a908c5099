// A strict reader of USD ASCII (.usda) for the export tests, written from the grammar of Pixar's text format
// (no USD library is packaged in Debian): a layer header and metadata, prims (def Type "name" (metadata) {...}),
// attributes with a default value and/or time samples, relationships, dictionaries. It accepts exactly the
// subset throng writes and refuses anything else with the line number: an unknown value type, a tuple of the
// wrong arity, a non-integer where an integer type is declared, time samples not in increasing order, a
// property declared twice with values, an unbalanced bracket, trailing text.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace throng::test::usda {

struct SyntaxError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A value: numbers (a scalar, a tuple, an array of either, flattened) or strings (a string or an array of them).
struct Value {
  std::vector<double> numbers;
  std::vector<std::string> strings;
  std::size_t elements = 0;  ///< array elements (1 for a scalar)
};

struct Attribute {
  std::string type;  ///< e.g. "point3f[]"
  bool custom = false, uniform = false;
  std::optional<Value> value;        ///< the default
  std::map<double, Value> samples;   ///< time code → value
  std::map<std::string, std::string> metadata;  ///< key → text of its value (strings unquoted)
};

struct Prim {
  std::string type, name, path;
  std::map<std::string, std::string> metadata;
  std::map<std::string, Attribute> attributes;
  std::map<std::string, std::vector<std::string>> relationships;  ///< name → target paths
  std::vector<Prim> children;

  /// The descendant at `path` (absolute), or nullptr.
  [[nodiscard]] const Prim* find(const std::string& target) const;
};

struct Layer {
  std::map<std::string, std::string> metadata;                    ///< key → value text (strings unquoted)
  std::map<std::string, std::pair<std::string, Value>> custom_layer_data;  ///< key → (type, value)
  std::vector<Prim> prims;

  [[nodiscard]] const Prim* find(const std::string& target) const;
};

/// Reads and checks the file; SyntaxError naming the line and what was expected.
[[nodiscard]] Layer read(const std::filesystem::path& path);

/// The half-precision value USD stores for a quath component written as `v` (round to nearest even).
[[nodiscard]] double to_half(double v);

}  // namespace throng::test::usda
