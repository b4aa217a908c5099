#include <throng/core/errors.h>
#include <throng/core/format.h>
#include <throng/core/schema.h>

#include <cmath>
#include <numbers>

namespace throng {
namespace {

std::string join(const std::string& path, const char* key) { return path.empty() ? key : path + "." + key; }

// The first value out of its range or choices: ConfigError naming the key path.
class Checker final : public OptionBinder {
 public:
  Checker(std::string what, std::string path) : what_(std::move(what)), path_(std::move(path)) {}
  using OptionBinder::choice;
  using OptionBinder::field;
  void field(const Field& f, double& v) override { number(f, v); }
  void field(const Field& f, int& v) override { number(f, static_cast<double>(v)); }
  void field(const Field& f, std::size_t& v) override { number(f, static_cast<double>(v)); }
  void field(const Field& f, std::int64_t& v) override { number(f, static_cast<double>(v)); }
  void field(const Field& f, std::int64_t& v, const Words& words) override {
    for (const auto& w : words) {
      if (w.second == v) return;
    }
    number(f, static_cast<double>(v));
  }
  void field(const Field&, bool&) override {}
  void field(const Field&, std::string&) override {}
  void field(const Field& f, std::vector<double>& v) override {
    for (double x : v) number(f, x);
  }
  void field(const Field& f, std::vector<std::int64_t>& v) override {
    for (std::int64_t x : v) number(f, static_cast<double>(x));
  }
  // Words are checked where they are read (the job reader) and used (an enum cannot hold another value; a
  // backend name is checked by the factory that makes the backend, naming what this build has).
  void choice(const Field&, std::string&, const std::vector<std::string>&) override {}
  void section(const char* key, const std::function<void(OptionBinder&)>& body) override {
    Checker inner(what_, join(path_, key));
    body(inner);
  }
  bool present(const Field&, bool has_value) override { return has_value; }

 private:
  void number(const Field& f, double v) const {
    if (!f.range.contains(v)) {
      throw ConfigError(what_ + join(path_, f.key) + " " + shortest(v) + ": expected " + f.range.describe());
    }
  }
  std::string what_, path_;
};

// Lists the fields with their defaults.
class Lister final : public OptionBinder {
 public:
  Lister(std::vector<FieldInfo>& out, std::string path) : out_(out), path_(std::move(path)) {}
  using OptionBinder::choice;
  using OptionBinder::field;
  void field(const Field& f, double& v) override { add(f, "number", shortest(v)); }
  void field(const Field& f, int& v) override { add(f, "integer", std::to_string(v)); }
  void field(const Field& f, std::size_t& v) override { add(f, "count", std::to_string(v)); }
  void field(const Field& f, std::int64_t& v) override { add(f, "integer", std::to_string(v)); }
  void field(const Field& f, std::int64_t& v, const Words& words) override {
    std::string text = std::to_string(v);
    for (const auto& w : words) {
      if (w.second == v) text = w.first;
    }
    add(f, "integer or word", text);
    for (const auto& w : words) out_.back().words.push_back(w.first);
  }
  void field(const Field& f, bool& v) override { add(f, "boolean", v ? "true" : "false"); }
  void field(const Field& f, std::string& v) override { add(f, "text", v); }
  void field(const Field& f, std::vector<double>& v) override {
    std::string text;
    for (double x : v) text += (text.empty() ? "" : ", ") + shortest(x);
    add(f, "numbers", "[" + text + "]");
  }
  void field(const Field& f, std::vector<std::int64_t>& v) override {
    std::string text;
    for (std::int64_t x : v) text += (text.empty() ? "" : ", ") + std::to_string(x);
    add(f, "integers", "[" + text + "]");
  }
  void choice(const Field& f, std::string& v, const std::vector<std::string>& allowed) override {
    add(f, "choice", v);
    out_.back().words = allowed;
  }
  void section(const char* key, const std::function<void(OptionBinder&)>& body) override {
    Lister inner(out_, join(path_, key));
    body(inner);
  }
  bool present(const Field& f, bool has_value) override {
    optional_ = f.key;
    (void)has_value;
    return true;
  }

 private:
  void add(const Field& f, const char* type, std::string default_text) {
    FieldInfo info;
    info.path = join(path_, f.key);
    info.field = f;
    info.type = type;
    info.default_text = std::move(default_text);
    info.optional = optional_ == f.key;
    optional_ = nullptr;
    out_.push_back(std::move(info));
  }
  std::vector<FieldInfo>& out_;
  std::string path_;
  const char* optional_ = nullptr;  // the key whose present() came just before
};

}  // namespace

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

void angle_in_degrees(OptionBinder& b, const Field& f, double& radians) {
  constexpr double degree = std::numbers::pi / 180.0;
  double d = std::round(radians / degree * 1e9) / 1e9;
  b.field(f, d);
  radians = d * degree;
}

namespace detail {

void check_options(const std::function<void(OptionBinder&)>& visit, const std::string& what) {
  Checker checker(what, "");
  visit(checker);
}

std::vector<FieldInfo> list_fields(const std::function<void(OptionBinder&)>& visit) {
  std::vector<FieldInfo> out;
  Lister lister(out, "");
  visit(lister);
  return out;
}

}  // namespace detail

}  // namespace throng
