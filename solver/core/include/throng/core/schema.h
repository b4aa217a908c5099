// Option schemas: every method describes its Options struct once, and everything that touches options is
// derived from that one description.
//
//   void describe(OptionBinder& b, collide::Options& o) {
//     b.field({.key = "margin", .unit = "m", .range = Range::non_negative(), .flag = "--margin",
//              .help = "clearance beyond the radii"}, o.margin);
//     b.choice({.key = "obstacle_pull", .flag = "--obstacle-pull"}, o.obstacle_pull,
//              {{"sideways", ObstaclePull::sideways}, {"nearest", ObstaclePull::nearest}});
//     b.section("solver", [&](OptionBinder& s) { linalg::describe(s, o.solver); });
//   }
//
// The default of an option is its member's initialiser: a binder sees the value the struct holds. The visitors:
//  * check_options (below): the solver's own validation, every range and choice (validate() adds only the rules
//    that tie several options together);
//  * io's OptionReader / OptionWriter (throng/io/config.h): the job file, with file:line in every message, and the
//    effective job that --print-config prints and every output stores;
//  * the program's flag binder (drivers/option_flags.h): a flag for each field that names one, its value written
//    into the job as an override layer, so a message about it names the flag;
//  * list_fields (below): what the schema holds, for tests and documentation.
// A binder may run `describe` on a scratch copy (the flag binder and the lister never read the values back), so a
// description only binds: it neither computes nor throws.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace throng {

/// A closed or open interval for numeric options.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;

  static constexpr Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static constexpr Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  static constexpr Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  /// True for a finite value inside the interval.
  [[nodiscard]] bool contains(double v) const;
  /// "> 0", "≥ 0", "in [0, 1]", "in (0, 1]", "a finite number".
  [[nodiscard]] std::string describe() const;
};

/// What a schema says about one option besides its value (the value's initialiser is the default).
struct Field {
  const char* key;            ///< snake_case key of the job file, within its section
  const char* unit = "";      ///< "m", "s", "Hz", "deg", "m/s", ...; "" for counts, ratios and words
  Range range = {};           ///< numbers: the accepted values (a count is also never negative)
  /// The command-line flag that sets it ("--margin"), "" for none. A switch for a true/false option sets true
  /// ("--allow-remaining"), or false when written with a leading '!' ("!--no-pin-ends").
  const char* flag = "";
  const char* help = "";      ///< one line: what it does (for --help and the docs)
  /// What a value is, for messages about a number that may also be a word ("a part count"); "" : "a whole number".
  const char* value = "";
  std::size_t length = 0;     ///< lists: exactly this many values ([x, y]: 2); 0 any
};

/// Names standing for numbers in an option that is a number or a word (`local.parts: auto`, `last_frame: end`).
using Words = std::vector<std::pair<std::string, std::int64_t>>;

/// Visits the fields of an Options struct (see the file comment). Sections nest: key paths join with '.'.
class OptionBinder {
 public:
  virtual ~OptionBinder() = default;
  virtual void field(const Field& f, double& value) = 0;
  virtual void field(const Field& f, int& value) = 0;
  virtual void field(const Field& f, std::size_t& value) = 0;
  virtual void field(const Field& f, std::int64_t& value) = 0;
  virtual void field(const Field& f, bool& value) = 0;
  virtual void field(const Field& f, std::string& value) = 0;
  virtual void field(const Field& f, std::vector<double>& value) = 0;
  virtual void field(const Field& f, std::vector<std::int64_t>& value) = 0;
  /// A whole number (checked against f.range), or one of `words`, each standing for a number outside the range.
  virtual void field(const Field& f, std::int64_t& value, const Words& words) = 0;
  /// A word from `allowed`.
  virtual void choice(const Field& f, std::string& value, const std::vector<std::string>& allowed) = 0;
  /// A nested mapping of options.
  virtual void section(const char* key, const std::function<void(OptionBinder&)>& body) = 0;
  /// Whether an optional option takes part in this visit: for a reader, the key is given; for a writer or a
  /// checker, the option holds a value; for the flag binder and the lister, always.
  virtual bool present(const Field& f, bool has_value) = 0;

  /// An optional option: absent unless given.
  template <class T>
  void field(const Field& f, std::optional<T>& value) {
    if (!present(f, value.has_value())) return;
    T v = value.value_or(T{});
    field(f, v);
    value = v;
  }

  /// An optional enum: absent unless given.
  template <class E>
  void choice(const Field& f, std::optional<E>& value, std::initializer_list<std::pair<const char*, E>> names) {
    if (!present(f, value.has_value())) return;
    E v = value.value_or(names.begin()->second);
    choice(f, v, names);
    value = v;
  }

  /// An enum through its names.
  template <class E>
    requires std::is_enum_v<E>
  void choice(const Field& f, E& value, std::initializer_list<std::pair<const char*, E>> names) {
    std::string text;
    std::vector<std::string> allowed;
    for (const auto& [name, v] : names) {
      allowed.emplace_back(name);
      if (v == value) text = name;
    }
    choice(f, text, allowed);
    for (const auto& [name, v] : names) {
      if (text == name) value = v;
    }
  }

  /// Shorthand for a field that has only a key and a range.
  template <class T>
  void field(const char* key, T& value, Range range = {}) {
    field(Field{.key = key, .range = range}, value);
  }
  void choice(const char* key, std::string& value, const std::vector<std::string>& allowed) {
    choice(Field{.key = key}, value, allowed);
  }
  template <class E>
    requires std::is_enum_v<E>
  void choice(const char* key, E& value, std::initializer_list<std::pair<const char*, E>> names) {
    choice(Field{.key = key}, value, names);
  }
};

/// An angle held in radians and written in degrees (f.range in degrees): 15° reads back as 15, not
/// 14.999999999999998.
void angle_in_degrees(OptionBinder& b, const Field& f, double& radians);

/// Checks every number of `options` against `describe`'s ranges; throws ConfigError
/// "<what><key path> <value>: expected <range>" for the first that is out. The solver's validate() calls it, so a
/// range lives in one place: the schema. (Words are checked where they are read and used.)
template <class Options>
void check_options(void (*describe)(OptionBinder&, Options&), const Options& options, const std::string& what);

/// One option as a schema lists it (for tests and documentation).
struct FieldInfo {
  std::string path;                 ///< key path from the job's top ("solver.backend")
  Field field;                      ///< key, unit, range, flag, help (pointers into the schema's literals)
  std::string type;                 ///< "number", "integer", "count", "boolean", "text", "numbers", "integers",
                                    ///< "integer or word", "choice"
  std::string default_text;         ///< the default as the job file writes it
  std::vector<std::string> words;   ///< a choice's words, or an integer option's words
  bool optional = false;            ///< absent unless given
};

/// Every option `describe` declares, in order, with the defaults of a default-constructed Options.
template <class Options>
std::vector<FieldInfo> list_fields(void (*describe)(OptionBinder&, Options&));

namespace detail {
void check_options(const std::function<void(OptionBinder&)>& visit, const std::string& what);
std::vector<FieldInfo> list_fields(const std::function<void(OptionBinder&)>& visit);
}  // namespace detail

template <class Options>
void check_options(void (*describe)(OptionBinder&, Options&), const Options& options, const std::string& what) {
  Options copy = options;
  detail::check_options([&](OptionBinder& b) { describe(b, copy); }, what);
}

template <class Options>
std::vector<FieldInfo> list_fields(void (*describe)(OptionBinder&, Options&)) {
  Options defaults{};
  return detail::list_fields([&](OptionBinder& b) { describe(b, defaults); });
}

}  // namespace throng
