#include <throng/core/errors.h>
#include <throng/io/config.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace throng {

// Which keys of one mapping were asked for, and the trackers of the children reached from it.
struct detail::ConfigTracking {
  YAML::Node node;
  std::string path;
  std::set<std::string> asked;
  std::map<std::string, std::shared_ptr<ConfigTracking>> children;
};

namespace {

std::string mark_text(const YAML::Mark& m) {
  if (m.line < 0) return "";
  return ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1);
}

std::string join_path(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

std::string shortest(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

// True when key path `inner` is `outer` or lies below it ("a.b" and "a.b[2]" lie below "a").
bool at_or_below(const std::string& inner, const std::string& outer) {
  return inner == outer || (inner.size() > outer.size() && inner.compare(0, outer.size(), outer) == 0 &&
                            (inner[outer.size()] == '.' || inner[outer.size()] == '['));
}

// The override that made the node at `path` (its text), when the node has no place in a file (it came from
// --set) and `path` is the override's key, below it (a value inside it) or above it (a mapping the override
// created); nullptr otherwise.
const std::string* override_at(const std::vector<std::pair<std::string, std::string>>* overrides, const std::string& path,
                               const YAML::Mark& mark) {
  if (!overrides || mark.line >= 0) return nullptr;
  for (const auto& [key, text] : *overrides) {
    if (at_or_below(path, key) || (!path.empty() && at_or_below(key, path))) return &text;
  }
  return nullptr;
}

// Every key, here and below, that nobody asked for: "file:line:col: unknown key 'k' in path (known here: ...)".
void collect_unknown(const detail::ConfigTracking* t, const std::string& source,
                     const std::vector<std::pair<std::string, std::string>>* overrides, std::vector<std::string>& problems) {
  if (t->node.IsMap()) {
    for (auto it = t->node.begin(); it != t->node.end(); ++it) {
      const std::string key = it->first.Scalar();
      if (t->asked.count(key)) continue;
      std::string known;
      for (const auto& k : t->asked) known += (known.empty() ? "" : ", ") + k;
      const std::string* set = override_at(overrides, join_path(t->path, key), it->first.Mark());
      problems.push_back((set ? "--set " + *set : source + mark_text(it->first.Mark())) + ": unknown key '" + key + "'" +
                         (t->path.empty() ? "" : " in " + t->path) + (known.empty() ? "" : " (known here: " + known + ")"));
    }
  }
  for (const auto& [key, child] : t->children) collect_unknown(child.get(), source, overrides, problems);
}

// A copy of `node` built in memory: same values, no marks (so nothing points into the override's own text).
YAML::Node without_marks(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar: return YAML::Node(node.Scalar());
    case YAML::NodeType::Sequence: {
      YAML::Node out(YAML::NodeType::Sequence);
      for (const auto& e : node) out.push_back(without_marks(e));
      out.SetStyle(YAML::EmitterStyle::Flow);
      return out;
    }
    case YAML::NodeType::Map: {
      YAML::Node out(YAML::NodeType::Map);
      for (auto it = node.begin(); it != node.end(); ++it) out[it->first.Scalar()] = without_marks(it->second);
      out.SetStyle(YAML::EmitterStyle::Flow);
      return out;
    }
    default: return YAML::Node(YAML::NodeType::Null);
  }
}
}  // namespace

ConfigNode ConfigNode::load_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(path.string() + ": no such job file");
  std::ifstream in(path);
  if (!in) throw IoError(path.string() + ": cannot be opened for reading");
  std::stringstream text;
  text << in.rdbuf();
  return parse(text.str(), path.string());
}

ConfigNode ConfigNode::parse(const std::string& text, const std::string& source) {
  try {
    return ConfigNode(YAML::Load(text), source);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source + mark_text(e.mark) + ": not valid YAML (" + e.msg + ")");
  }
}

ConfigNode::ConfigNode(YAML::Node node, std::string source, std::string key_path)
    : ConfigNode(std::move(node), std::make_shared<const std::string>(std::move(source)), std::move(key_path), nullptr,
                 nullptr) {}

ConfigNode::ConfigNode(YAML::Node node, std::shared_ptr<const std::string> source, std::string path, std::shared_ptr<Tracking> tracking,
                       std::shared_ptr<const Overrides> overrides)
    : node_(std::move(node)),
      source_(std::move(source)),
      path_(std::move(path)),
      tracking_(std::move(tracking)),
      overrides_(std::move(overrides)) {
  if (!tracking_) {
    tracking_ = std::make_shared<detail::ConfigTracking>();
    tracking_->node = node_;
    tracking_->path = path_;
  }
}

ConfigNode ConfigNode::child(const YAML::Node& node, const std::string& path) const {
  auto& slot = tracking_->children[path];
  if (!slot) {
    slot = std::make_shared<detail::ConfigTracking>();
    slot->node = node;
    slot->path = path;
  }
  return ConfigNode(node, source_, path, slot, overrides_);
}

ConfigNode ConfigNode::with_overrides(const std::vector<std::string>& overrides) const {
  if (overrides.empty()) return ConfigNode(node_, source_, path_, nullptr, overrides_);
  YAML::Node root = node_;
  if (is_null()) root = YAML::Node(YAML::NodeType::Map);
  if (!root.IsMap()) fail("a job must hold a mapping of keys to apply --set to");
  apply_overrides(root, overrides);
  auto list = std::make_shared<Overrides>(overrides_ ? *overrides_ : Overrides{});
  for (const auto& o : overrides) list->emplace_back(o.substr(0, o.find('=')), o);
  return ConfigNode(root, source_, path_, nullptr, std::move(list));
}

std::string ConfigNode::where() const {
  if (const std::string* set = override_at(overrides_.get(), path_, node_.Mark())) {
    return "--set " + *set + (path_ == set->substr(0, set->find('=')) ? "" : " (" + path_ + ")");
  }
  std::string s = *source_ + mark_text(node_.Mark());
  if (!path_.empty()) s += " (" + path_ + ")";
  return s;
}

const std::string& ConfigNode::source() const noexcept { return *source_; }

void ConfigNode::fail(const std::string& message) const { throw ConfigError(where() + ": " + message); }

bool ConfigNode::has(const std::string& key) const {
  tracking_->asked.insert(key);
  return node_.IsMap() && node_[key].IsDefined();
}

std::optional<ConfigNode> ConfigNode::find(const std::string& key) const {
  if (!node_.IsMap()) {
    if (is_null()) return std::nullopt;
    fail("expected a mapping of keys to values");
  }
  tracking_->asked.insert(key);
  const YAML::Node value = node_[key];
  if (!value.IsDefined()) return std::nullopt;
  return child(value, join_path(path_, key));
}

ConfigNode ConfigNode::at(const std::string& key) const {
  auto v = find(key);
  if (!v) fail("missing key '" + key + "'");
  return *v;
}

std::vector<ConfigNode> ConfigNode::elements() const {
  if (!node_.IsSequence()) fail("expected a list");
  std::vector<ConfigNode> out;
  for (std::size_t i = 0; i < node_.size(); ++i) out.push_back(child(node_[i], path_ + "[" + std::to_string(i) + "]"));
  return out;
}

std::vector<std::string> ConfigNode::keys() const {
  if (!node_.IsMap()) fail("expected a mapping");
  std::vector<std::string> out;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    out.push_back(it->first.Scalar());
    tracking_->asked.insert(out.back());
  }
  return out;
}

double ConfigNode::as_double() const {
  if (!node_.IsScalar()) fail("expected a number");
  double v = 0;
  try {
    v = node_.as<double>();
  } catch (const YAML::Exception&) {
    fail("expected a number, found '" + node_.Scalar() + "'");
  }
  if (!std::isfinite(v)) fail("expected a finite number, found '" + node_.Scalar() + "'");
  return v;
}

std::int64_t ConfigNode::as_int() const {
  if (!node_.IsScalar()) fail("expected an integer");
  try {
    return node_.as<std::int64_t>();
  } catch (const YAML::Exception&) {
    fail("expected an integer, found '" + node_.Scalar() + "'");
  }
}

bool ConfigNode::as_bool() const {
  if (!node_.IsScalar()) fail("expected true or false");
  try {
    return node_.as<bool>();
  } catch (const YAML::Exception&) {
    fail("expected true or false, found '" + node_.Scalar() + "'");
  }
}

std::string ConfigNode::as_string() const {
  if (!node_.IsScalar()) fail("expected a text value");
  return node_.Scalar();
}

std::vector<double> ConfigNode::as_doubles(std::initializer_list<std::size_t> sizes) const {
  if (!node_.IsSequence()) fail("expected a list of numbers");
  std::vector<double> out;
  for (const auto& e : elements()) out.push_back(e.as_double());
  if (sizes.size() > 0) {
    bool ok = false;
    std::string expected;
    for (auto s : sizes) {
      ok = ok || out.size() == s;
      expected += (expected.empty() ? "" : " or ") + std::to_string(s);
    }
    if (!ok) fail("expected " + expected + " numbers, found " + std::to_string(out.size()));
  }
  return out;
}

void ConfigNode::finish() const {
  std::vector<std::string> problems;
  collect_unknown(tracking_.get(), *source_, overrides_.get(), problems);
  if (problems.empty()) return;
  std::string message = problems.front();
  for (std::size_t i = 1; i < problems.size(); ++i) message += "\n" + problems[i];
  throw ConfigError(message);
}

void apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides) {
  for (const auto& o : overrides) {
    const auto eq = o.find('=');
    if (eq == std::string::npos || eq == 0) throw ConfigError("--set " + o + ": expected key.path=value");
    const std::string path = o.substr(0, eq);
    YAML::Node value;
    try {
      value = YAML::Load(o.substr(eq + 1));
    } catch (const YAML::Exception& e) {
      throw ConfigError("--set " + o + ": value is not valid YAML (" + e.msg + ")");
    }
    // Walk with fresh handles: yaml-cpp nodes are references, so assignment below writes into `root`.
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true) {
      const auto dot = path.find('.', start);
      parts.push_back(path.substr(start, dot - start));
      if (dot == std::string::npos) break;
      start = dot + 1;
    }
    std::vector<YAML::Node> chain{root};
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      if (parts[i].empty()) throw ConfigError("--set " + o + ": empty key in '" + path + "'");
      YAML::Node next = chain.back()[parts[i]];
      if (next.IsDefined() && !next.IsMap()) throw ConfigError("--set " + o + ": '" + parts[i] + "' is not a mapping");
      chain.push_back(next);
    }
    if (parts.back().empty()) throw ConfigError("--set " + o + ": empty key in '" + path + "'");
    chain.back()[parts.back()] = without_marks(value);
  }
}

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (min_open ? !(v > min) : !(v >= min)) return false;
  if (max_open ? !(v < max) : !(v <= max)) return false;
  return true;
}

std::string Range::describe() const {
  const bool lo = std::isfinite(min), hi = std::isfinite(max);
  if (lo && hi) return std::string("in ") + (min_open ? "(" : "[") + shortest(min) + ", " + shortest(max) + (max_open ? ")" : "]");
  if (lo) return std::string(min_open ? "> " : "≥ ") + shortest(min);
  if (hi) return std::string(max_open ? "< " : "≤ ") + shortest(max);
  return "a finite number";
}

void OptionReader::field(const char* key, double& value, Range range) {
  if (auto n = node_.find(key)) {
    const double v = n->as_double();
    if (!range.contains(v)) n->fail("value " + shortest(v) + " is out of range, expected " + range.describe());
    value = v;
  }
}

void OptionReader::field(const char* key, int& value, Range range) {
  if (auto n = node_.find(key)) {
    const std::int64_t v = n->as_int();
    if (!range.contains(static_cast<double>(v)) || v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) {
      n->fail("value " + std::to_string(v) + " is out of range, expected " + range.describe());
    }
    value = static_cast<int>(v);
  }
}

void OptionReader::field(const char* key, std::size_t& value, Range range) {
  if (auto n = node_.find(key)) {
    const std::int64_t v = n->as_int();
    // A count is never negative, whatever the range says.
    Range counts = range;
    if (!(counts.min >= 0)) counts.min = 0, counts.min_open = false;
    if (!counts.contains(static_cast<double>(v))) {
      n->fail("value " + std::to_string(v) + " is out of range, expected " + counts.describe());
    }
    value = static_cast<std::size_t>(v);
  }
}

void OptionReader::field(const char* key, bool& value) {
  if (auto n = node_.find(key)) value = n->as_bool();
}

void OptionReader::field(const char* key, std::string& value) {
  if (auto n = node_.find(key)) value = n->as_string();
}

void OptionReader::field(const char* key, std::vector<double>& value) {
  if (auto n = node_.find(key)) value = n->as_doubles();
}

void OptionReader::choice(const char* key, std::string& value, const std::vector<std::string>& allowed) {
  if (auto n = node_.find(key)) {
    const std::string v = n->as_string();
    std::string list;
    for (const auto& a : allowed) {
      if (a == v) {
        value = v;
        return;
      }
      list += (list.empty() ? "" : ", ") + a;
    }
    n->fail("unknown value '" + v + "', expected one of: " + list);
  }
}

void OptionReader::section(const char* key, const std::function<void(OptionBinder&)>& body) {
  if (auto n = node_.find(key)) {
    OptionReader inner(*n);
    body(inner);
  }
}

void OptionWriter::field(const char* key, double& value, Range) { node_[key] = yaml_number(value); }
void OptionWriter::field(const char* key, int& value, Range) { node_[key] = value; }
void OptionWriter::field(const char* key, std::size_t& value, Range) { node_[key] = static_cast<std::uint64_t>(value); }
void OptionWriter::field(const char* key, bool& value) { node_[key] = value; }
void OptionWriter::field(const char* key, std::string& value) { node_[key] = value; }
void OptionWriter::field(const char* key, std::vector<double>& value) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (double v : value) list.push_back(YAML::Load(shortest(v)));
  list.SetStyle(YAML::EmitterStyle::Flow);
  node_[key] = list;
}
void OptionWriter::choice(const char* key, std::string& value, const std::vector<std::string>&) { node_[key] = value; }
void OptionWriter::section(const char* key, const std::function<void(OptionBinder&)>& body) {
  YAML::Node inner(YAML::NodeType::Map);
  OptionWriter writer(inner);
  body(writer);
  node_[key] = inner;
}

YAML::Node yaml_number(double value) { return YAML::Load(shortest(value)); }

std::string to_yaml_text(const YAML::Node& node) {
  YAML::Emitter out;
  out << node;
  return std::string(out.c_str()) + "\n";
}

}  // namespace throng
