// The YAML visitors of an Options schema (throng/core/schema.h): OptionReader and OptionWriter, and the YAML value
// helpers every effective job uses.
#include <throng/core/errors.h>
#include <throng/core/format.h>
#include <throng/io/config.h>

#include <limits>

namespace throng {
namespace {

std::string words_of(const Words& words) {
  std::vector<std::string> names;
  for (const auto& w : words) names.push_back(w.first);
  return join_words(names, " or ");
}

template <class Int>
Int read_integer(const ConfigNode& n, const Range& range) {
  const std::int64_t v = n.as_int();
  if (!range.contains(static_cast<double>(v)) || v < static_cast<std::int64_t>(std::numeric_limits<Int>::min()) ||
      (std::numeric_limits<Int>::max() < std::numeric_limits<std::int64_t>::max() &&
       v > static_cast<std::int64_t>(std::numeric_limits<Int>::max()))) {
    n.fail("value " + std::to_string(v) + " is out of range, expected " + range.describe() +
           (v < 0 && range.min >= 0 ? " (a count or an index is never negative)" : ""));
  }
  return static_cast<Int>(v);
}

}  // namespace

void OptionReader::field(const Field& f, double& value) {
  if (auto n = node_.find(f.key)) {
    const double v = n->as_double();
    if (!f.range.contains(v)) n->fail("value " + shortest(v) + " is out of range, expected " + f.range.describe());
    value = v;
  }
}

void OptionReader::field(const Field& f, int& value) {
  if (auto n = node_.find(f.key)) value = read_integer<int>(*n, f.range);
}

void OptionReader::field(const Field& f, std::size_t& value) {
  if (auto n = node_.find(f.key)) {
    Range counts = f.range;  // a count is never negative, whatever the range says
    if (!(counts.min >= 0)) counts.min = 0, counts.min_open = false;
    value = static_cast<std::size_t>(read_integer<std::int64_t>(*n, counts));
  }
}

void OptionReader::field(const Field& f, std::int64_t& value) {
  if (auto n = node_.find(f.key)) value = read_integer<std::int64_t>(*n, f.range);
}

void OptionReader::field(const Field& f, std::int64_t& value, const Words& words) {
  const auto n = node_.find(f.key);
  if (!n) return;
  const std::string what = *f.value ? f.value : "a whole number";
  if (!n->is_scalar()) n->fail("expected " + what + " or " + words_of(words));
  for (const auto& w : words) {
    if (n->yaml().Scalar() == w.first) {
      value = w.second;
      return;
    }
  }
  std::int64_t v = 0;
  try {
    v = n->as_int();
  } catch (const Error&) {
    n->fail("expected " + what + " " + f.range.describe() + " or " + words_of(words) + ", found '" + n->as_string() + "'");
  }
  if (!f.range.contains(static_cast<double>(v))) {
    n->fail("value " + std::to_string(v) + " is out of range, expected " + f.range.describe() + " or " + words_of(words));
  }
  value = v;
}

void OptionReader::field(const Field& f, bool& value) {
  if (auto n = node_.find(f.key)) value = n->as_bool();
}

void OptionReader::field(const Field& f, std::string& value) {
  if (auto n = node_.find(f.key)) value = n->as_string();
}

// A list of exactly f.length values when the schema says so.
static void check_length(const ConfigNode& n, const Field& f, std::size_t size, const char* what) {
  if (f.length > 0 && size != f.length) {
    n.fail("expected " + std::to_string(f.length) + " " + what + ", found " + std::to_string(size));
  }
}

void OptionReader::field(const Field& f, std::vector<double>& value) {
  if (auto n = node_.find(f.key)) {
    std::vector<double> v = n->as_doubles();
    check_length(*n, f, v.size(), "numbers");
    const std::vector<ConfigNode> items = n->elements();
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!f.range.contains(v[i])) items[i].fail("value " + shortest(v[i]) + " is out of range, expected " + f.range.describe());
    }
    value = std::move(v);
  }
}

void OptionReader::field(const Field& f, std::vector<std::int64_t>& value) {
  if (auto n = node_.find(f.key)) {
    std::vector<std::int64_t> v;
    for (const ConfigNode& item : n->elements()) v.push_back(read_integer<std::int64_t>(item, f.range));
    check_length(*n, f, v.size(), "integers");
    value = std::move(v);
  }
}

void OptionReader::choice(const Field& f, std::string& value, const std::vector<std::string>& allowed) {
  if (auto n = node_.find(f.key)) {
    const std::string v = n->as_string();
    for (const auto& a : allowed) {
      if (a == v) {
        value = v;
        return;
      }
    }
    n->fail("unknown value '" + v + "', expected one of: " + join_words(allowed));
  }
}

void OptionReader::section(const char* key, const std::function<void(OptionBinder&)>& body) {
  if (auto n = node_.find(key)) {
    OptionReader inner(*n);
    body(inner);
  }
}

bool OptionReader::present(const Field& f, bool) { return node_.find(f.key).has_value(); }

void OptionWriter::field(const Field& f, std::int64_t& value, const Words& words) {
  for (const auto& w : words) {
    if (w.second == value) {
      node_[f.key] = w.first;
      return;
    }
  }
  node_[f.key] = value;
}
void OptionWriter::section(const char* key, const std::function<void(OptionBinder&)>& body) {
  YAML::Node inner = node_[key].IsMap() ? node_[key] : YAML::Node(YAML::NodeType::Map);
  OptionWriter writer(inner);
  body(writer);
  node_[key] = inner;
}

YAML::Node yaml_number(double value) { return YAML::Load(shortest(value)); }

YAML::Node yaml_numbers(const std::vector<double>& values) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (double v : values) n.push_back(yaml_number(v));
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

YAML::Node yaml_integers(const std::vector<std::int64_t>& values) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (std::int64_t v : values) n.push_back(v);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

std::string to_yaml_text(const YAML::Node& node) {
  YAML::Emitter out;
  out << node;
  return std::string(out.c_str()) + "\n";
}

}  // namespace throng
