#include "option_flags.h"

#include <throng/core/format.h>

#include <cctype>
#include <cmath>

namespace throng::cli {
namespace {

using Entry = OptionFlags::Entry;

std::string join(const std::string& path, const char* key) { return path.empty() ? key : path + "." + key; }

/// A YAML scalar as the job file would hold it ("12" a number, "rigid" a word); text that YAML would read as
/// something else (a mapping, a sequence) stays a plain string, so the job reader reports it as a wrong value.
YAML::Node scalar(const std::string& text) {
  try {
    YAML::Node n = YAML::Load(text);
    if (n.IsScalar()) return n;
  } catch (const YAML::Exception&) {
  }
  return YAML::Node(text);
}

// A CLI11 check of a number flag against its field's range (and words), so a bad value is refused as the command
// line is read, naming the flag and the job key: "--margin: expected a finite number ≥ 0, found '-1' (job key
// margin)". CLI11's own checks would print the largest double in full, and let NaN through.
CLI::Validator number_check(const Field& f, const std::string& path, bool integer, const std::vector<std::string>& words) {
  const std::string what = *f.value ? f.value : integer ? "a whole number" : "a finite number";
  const std::string expected = what + " " + f.range.describe() + (words.empty() ? "" : " or " + join_words(words, " or "));
  const Range range = f.range;
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        for (const std::string& w : words) {
          if (text == w) return {};
        }
        double v = 0;
        std::size_t used = 0;
        try {
          v = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        const bool whole = v == std::floor(v) && std::abs(v) < 9e15;
        if (used == 0 || used != text.size() || !range.contains(v) || (integer && !whole)) {
          return "expected " + expected + ", found '" + text + "' (job key " + path + ")";
        }
        return {};
      },
      integer ? "N" : "NUMBER");
}

// Registers the flags of the fields that name one.
class FlagBinder final : public OptionBinder {
 public:
  FlagBinder(CLI::App& app, std::vector<std::unique_ptr<Entry>>& entries, std::string path)
      : app_(app), entries_(entries), path_(std::move(path)) {}
  using OptionBinder::choice;
  using OptionBinder::field;
  void field(const Field& f, double& v) override { number(f, shortest(v), false, {}); }
  void field(const Field& f, int& v) override { number(f, std::to_string(v), true, {}); }
  void field(const Field& f, std::size_t& v) override {
    Field counts = f;  // a count is never negative, whatever the range says
    if (!(counts.range.min >= 0)) counts.range.min = 0, counts.range.min_open = false;
    number(counts, std::to_string(v), true, {});
  }
  void field(const Field& f, std::int64_t& v) override { number(f, std::to_string(v), true, {}); }
  void field(const Field& f, std::int64_t& v, const Words& words) override {
    std::string text = std::to_string(v);
    std::vector<std::string> names;
    for (const auto& w : words) {
      names.push_back(w.first);
      if (w.second == v) text = w.first;
    }
    number(f, text, true, names);
  }
  void field(const Field& f, bool& v) override {
    if (!*f.flag) return;
    const bool off = f.flag[0] == '!';
    auto& e = add(f, off ? Entry::Kind::off : Entry::Kind::on, off ? f.flag + 1 : f.flag);
    app_.add_flag(e.flag, e.given, help(f, std::string("sets ") + (off ? "false" : "true") + "; default " + (v ? "true" : "false")));
  }
  void field(const Field& f, std::string& v) override { value(f, v, ""); }
  void field(const Field& f, std::vector<double>& v) override { list(f, v.size()); }
  void field(const Field& f, std::vector<std::int64_t>& v) override { list(f, v.size()); }
  void choice(const Field& f, std::string& v, const std::vector<std::string>& allowed) override {
    value(f, v, join_words(allowed, " | "));
  }
  void section(const char* key, const std::function<void(OptionBinder&)>& body) override {
    FlagBinder inner(app_, entries_, join(path_, key));
    body(inner);
  }
  bool present(const Field&, bool) override { return true; }

 private:
  void number(const Field& f, const std::string& default_text, bool integer, const std::vector<std::string>& words) {
    if (!*f.flag) return;
    std::string detail = std::string(*f.unit ? f.unit + std::string(", ") : "") + f.range.describe();
    if (!words.empty()) detail += " or " + join_words(words, " or ");
    value(f, default_text, detail)->check(number_check(f, join(path_, f.key), integer, words));
  }
  std::string help(const Field& f, const std::string& detail) const {
    std::string h = f.help;
    if (!h.empty()) h[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(h[0])));
    return h + " (" + (detail.empty() ? "" : detail + "; ") + "job key " + join(path_, f.key) + ")";
  }
  Entry& add(const Field& f, Entry::Kind kind, const char* flag) {
    return *entries_.emplace_back(std::make_unique<Entry>(Entry{kind, join(path_, f.key), flag, std::nullopt, false}));
  }
  CLI::Option* value(const Field& f, const std::string& default_text, const std::string& detail) {
    if (!*f.flag) return nullptr;
    auto& e = add(f, Entry::Kind::value, f.flag);
    return app_.add_option(e.flag, e.text, help(f, detail + (detail.empty() ? "" : "; ") + "default " +
                                                        (default_text.empty() ? "none" : default_text)));
  }
  void list(const Field& f, std::size_t) {
    if (!*f.flag) return;
    auto& e = add(f, Entry::Kind::list, f.flag);
    app_.add_option(e.flag, e.text, help(f, "comma-separated"));
  }

  CLI::App& app_;
  std::vector<std::unique_ptr<Entry>>& entries_;
  std::string path_;
};

}  // namespace

void OptionFlags::add(CLI::App& app, const std::function<void(OptionBinder&)>& describe) {
  FlagBinder binder(app, entries_, "");
  describe(binder);
}

std::vector<Override> OptionFlags::overrides() const {
  std::vector<Override> out;
  for (const auto& e : entries_) {
    switch (e->kind) {
      case Entry::Kind::value:
        if (e->text) out.push_back({e->path, scalar(*e->text), e->flag + " " + *e->text + " (" + e->path + ")"});
        break;
      case Entry::Kind::list:
        if (e->text) {
          YAML::Node seq(YAML::NodeType::Sequence);
          std::size_t start = 0;
          while (true) {
            const std::size_t comma = e->text->find(',', start);
            const std::string item = e->text->substr(start, comma == std::string::npos ? std::string::npos : comma - start);
            if (!item.empty() || comma != std::string::npos) seq.push_back(scalar(item));
            if (comma == std::string::npos) break;
            start = comma + 1;
          }
          out.push_back({e->path, seq, e->flag + " " + *e->text + " (" + e->path + ")"});
        }
        break;
      case Entry::Kind::on:
      case Entry::Kind::off:
        if (e->given) out.push_back({e->path, YAML::Node(e->kind == Entry::Kind::on), e->flag + " (" + e->path + ")"});
        break;
    }
  }
  return out;
}

}  // namespace throng::cli
