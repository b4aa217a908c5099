#include <throng/core/errors.h>
#include <throng/io/config.h>

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

// Where a job's values came from: one file for the whole (or a name), other files for some top-level keys
// (layered), and single values from the command line (overrides).
struct detail::ConfigOrigins {
  struct Origin {
    std::string name;               // for messages
    std::filesystem::path folder;   // anchors relative paths ("" : the working directory)
  };
  Origin whole;
  std::map<std::string, Origin> by_key;
  std::vector<Override> overrides;

  static Origin of(const std::string& source) { return {source, std::filesystem::path(source).parent_path()}; }
  // The origin of the node at `path`: its top-level key's.
  const Origin& at(const std::string& path) const {
    const std::string top = path.substr(0, path.find_first_of(".["));
    const auto it = by_key.find(top);
    return it == by_key.end() ? whole : it->second;
  }
};

namespace {

using Origins = detail::ConfigOrigins;

std::string mark_text(const YAML::Mark& m) {
  if (m.line < 0) return "";
  return ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1);
}

std::string join_path(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

// True when key path `inner` is `outer` or lies below it ("a.b" and "a.b[2]" lie below "a").
bool at_or_below(const std::string& inner, const std::string& outer) {
  return inner == outer || (inner.size() > outer.size() && inner.compare(0, outer.size(), outer) == 0 &&
                            (inner[outer.size()] == '.' || inner[outer.size()] == '['));
}

// The override that made the node at `path`, when the node has no place in a file (it came from the command
// line) and `path` is the override's key, below it (a value inside it) or above it (a mapping it created).
const Override* override_at(const Origins& origins, const std::string& path, const YAML::Mark& mark) {
  if (mark.line >= 0) return nullptr;
  for (const Override& o : origins.overrides) {
    if (at_or_below(path, o.path) || (!path.empty() && at_or_below(o.path, path))) return &o;
  }
  return nullptr;
}

// Every key, here and below, that nobody asked for: "file:line:col: unknown key 'k' in path (known here: ...)".
void collect_unknown(const detail::ConfigTracking* t, const Origins& origins, std::vector<std::string>& problems) {
  if (t->node.IsMap()) {
    for (auto it = t->node.begin(); it != t->node.end(); ++it) {
      const std::string key = it->first.Scalar();
      if (t->asked.count(key)) continue;
      std::string known;
      for (const auto& k : t->asked) known += (known.empty() ? "" : ", ") + k;
      const std::string path = join_path(t->path, key);
      const Override* set = override_at(origins, path, it->first.Mark());
      problems.push_back((set ? set->origin : origins.at(path).name + mark_text(it->first.Mark())) + ": unknown key '" + key +
                         "'" + (t->path.empty() ? "" : " in " + t->path) + (known.empty() ? "" : " (known here: " + known + ")"));
    }
  }
  for (const auto& [key, child] : t->children) collect_unknown(child.get(), origins, problems);
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

// YAML leaves a key written twice in one mapping open and yaml-cpp keeps the first: refuse it, naming both lines.
void refuse_duplicate_keys(const YAML::Node& node, const std::string& source) {
  if (node.IsSequence()) {
    for (const auto& e : node) refuse_duplicate_keys(e, source);
  } else if (node.IsMap()) {
    std::map<std::string, YAML::Mark> seen;
    for (auto it = node.begin(); it != node.end(); ++it) {
      const std::string key = it->first.IsScalar() ? it->first.Scalar() : "";
      if (const auto [first, fresh] = seen.emplace(key, it->first.Mark()); !fresh) {
        throw ConfigError(source + mark_text(it->first.Mark()) + ": the key '" + key + "' is written twice in one mapping" +
                          " (first at line " + std::to_string(first->second.line + 1) + ", again at line " +
                          std::to_string(it->first.Mark().line + 1) + "); keep one");
      }
      refuse_duplicate_keys(it->second, source);
    }
  }
}

YAML::Node load_yaml(const std::string& text, const std::string& source) {
  try {
    YAML::Node node = YAML::Load(text);
    refuse_duplicate_keys(node, source);
    return node;
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source + mark_text(e.mark) + ": not valid YAML (" + e.msg + ")");
  }
}

// Writes `value` at `path` into `root` (a mapping), creating the mappings on the way.
void set_at(YAML::Node& root, const Override& o) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto dot = o.path.find('.', start);
    parts.push_back(o.path.substr(start, dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  // Walk with fresh handles: yaml-cpp nodes are references, so assignment below writes into `root`.
  std::vector<YAML::Node> chain{root};
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    if (parts[i].empty()) throw ConfigError(o.origin + ": empty key in '" + o.path + "'");
    YAML::Node next = chain.back()[parts[i]];
    if (next.IsDefined() && !next.IsMap()) throw ConfigError(o.origin + ": '" + parts[i] + "' is not a mapping");
    chain.push_back(next);
  }
  if (parts.back().empty()) throw ConfigError(o.origin + ": empty key in '" + o.path + "'");
  chain.back()[parts.back()] = without_marks(o.value);
}

}  // namespace

Override parse_set(const std::string& text) {
  const auto eq = text.find('=');
  const std::string origin = "--set " + text;
  if (eq == std::string::npos || eq == 0) throw ConfigError(origin + ": expected key.path=value");
  Override o{text.substr(0, eq), {}, origin};
  try {
    o.value = YAML::Load(text.substr(eq + 1));
    refuse_duplicate_keys(o.value, origin);
  } catch (const YAML::Exception& e) {
    throw ConfigError(origin + ": value is not valid YAML (" + e.msg + ")");
  }
  return o;
}

void apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides) {
  for (const std::string& text : overrides) set_at(root, parse_set(text));
}

ConfigNode ConfigNode::load_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(path.string() + ": no such job file");
  if (std::filesystem::is_directory(path, ec)) throw IoError(path.string() + ": is a folder, not a job file");
  std::ifstream in(path);
  if (!in) throw IoError(path.string() + ": cannot be opened for reading");
  std::stringstream text;
  text << in.rdbuf();
  return parse(text.str(), path.string());
}

ConfigNode ConfigNode::parse(const std::string& text, const std::string& source) {
  return ConfigNode(load_yaml(text, source), source);
}

ConfigNode::ConfigNode(YAML::Node node, std::string source, std::string key_path)
    : ConfigNode(std::move(node), std::make_shared<Origins>(Origins{Origins::of(source), {}, {}}), std::move(key_path), nullptr) {}

ConfigNode::ConfigNode(YAML::Node node, std::shared_ptr<const Origins> origins, std::string path, std::shared_ptr<Tracking> tracking)
    : node_(std::move(node)), origins_(std::move(origins)), path_(std::move(path)), tracking_(std::move(tracking)) {
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
  return ConfigNode(node, origins_, path, slot);
}

ConfigNode ConfigNode::layered(const std::vector<ConfigNode>& layers, const std::string& source) {
  auto origins = std::make_shared<Origins>(Origins{Origins::of(source), {}, {}});
  YAML::Node root(YAML::NodeType::Map);
  for (const ConfigNode& layer : layers) {
    if (layer.is_null()) continue;
    if (!layer.is_map()) layer.fail("expected a mapping of keys to values");
    for (auto it = layer.node_.begin(); it != layer.node_.end(); ++it) {
      const std::string key = it->first.Scalar();
      root.remove(key);
      root.force_insert(it->first, it->second);  // the key's own nodes: messages keep its line
      origins->by_key[key] = layer.origins_->at(join_path(layer.path_, key));
    }
    for (const Override& o : layer.origins_->overrides) origins->overrides.push_back(o);
  }
  return ConfigNode(root, std::move(origins), "", nullptr);
}

ConfigNode ConfigNode::with_overrides(const std::vector<Override>& overrides) const {
  auto origins = std::make_shared<Origins>(*origins_);
  if (overrides.empty()) return ConfigNode(node_, std::move(origins), path_, nullptr);
  YAML::Node root = node_;
  if (is_null()) root = YAML::Node(YAML::NodeType::Map);
  if (!root.IsMap()) fail("a job must hold a mapping of keys to apply " + overrides.front().origin + " to");
  for (const Override& o : overrides) {
    set_at(root, o);
    origins->overrides.push_back(o);
  }
  return ConfigNode(root, std::move(origins), path_, nullptr);
}

ConfigNode ConfigNode::with_overrides(const std::vector<std::string>& set) const {
  std::vector<Override> overrides;
  for (const std::string& text : set) overrides.push_back(parse_set(text));
  return with_overrides(overrides);
}

const Override* ConfigNode::override_here() const { return override_at(*origins_, path_, node_.Mark()); }

std::string ConfigNode::where() const {
  if (const Override* o = override_here()) return o->origin + (path_ == o->path ? "" : " (" + path_ + ")");
  std::string s = origins_->at(path_).name + mark_text(node_.Mark());
  if (!path_.empty()) s += " (" + path_ + ")";
  return s;
}

std::string ConfigNode::source() const {
  if (const Override* o = override_here()) return o->origin;
  return origins_->at(path_).name;
}

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

std::vector<std::int64_t> ConfigNode::as_ints() const {
  if (!node_.IsSequence()) fail("expected a list of integers");
  std::vector<std::int64_t> out;
  for (const auto& e : elements()) out.push_back(e.as_int());
  return out;
}

std::filesystem::path ConfigNode::as_path() const {
  const std::string text = as_string();
  if (text.empty()) fail("expected a path, found an empty text");
  const std::filesystem::path p(text);
  if (p.is_absolute() || override_here()) return p;
  const std::filesystem::path& folder = origins_->at(path_).folder;
  return folder.empty() ? p : (folder / p).lexically_normal();
}

void ConfigNode::finish() const {
  std::vector<std::string> problems;
  collect_unknown(tracking_.get(), *origins_, problems);
  if (problems.empty()) return;
  std::string message = problems.front();
  for (std::size_t i = 1; i < problems.size(); ++i) message += "\n" + problems[i];
  throw ConfigError(message);
}

}  // namespace throng
