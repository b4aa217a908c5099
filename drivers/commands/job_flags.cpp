#include "job_flags.h"

namespace throng::cli {
namespace {

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

}  // namespace

CLI::Option* JobFlags::value(CLI::App& app, const std::string& flag, const std::string& key, const std::string& help) {
  auto& e = *entries_.emplace_back(std::make_unique<Entry>(Entry{key, Kind::value, std::nullopt, false}));
  return app.add_option(flag, e.text, help + " (job key " + key + ")");
}

CLI::Option* JobFlags::list(CLI::App& app, const std::string& flag, const std::string& key, const std::string& help) {
  auto& e = *entries_.emplace_back(std::make_unique<Entry>(Entry{key, Kind::list, std::nullopt, false}));
  return app.add_option(flag, e.text, help + " (comma-separated; job key " + key + ")");
}

CLI::Option* JobFlags::flag(CLI::App& app, const std::string& flag, const std::string& key, const std::string& help) {
  auto& e = *entries_.emplace_back(std::make_unique<Entry>(Entry{key, Kind::flag, std::nullopt, false}));
  return app.add_flag(flag, e.given, help + " (job key " + key + ": true)");
}

YAML::Node JobFlags::yaml() const {
  YAML::Node out(YAML::NodeType::Map);
  for (const auto& e : entries_) {
    switch (e->kind) {
      case Kind::value:
        if (e->text) out[e->key] = scalar(*e->text);
        break;
      case Kind::list:
        if (e->text) {
          YAML::Node seq(YAML::NodeType::Sequence);
          std::string item;
          std::size_t start = 0;
          while (true) {
            const std::size_t comma = e->text->find(',', start);
            item = e->text->substr(start, comma == std::string::npos ? std::string::npos : comma - start);
            if (!item.empty() || comma != std::string::npos) seq.push_back(scalar(item));
            if (comma == std::string::npos) break;
            start = comma + 1;
          }
          out[e->key] = seq;
        }
        break;
      case Kind::flag:
        if (e->given) out[e->key] = true;
        break;
    }
  }
  return out;
}

}  // namespace throng::cli
