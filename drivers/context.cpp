#include "context.h"

#include "progress_reporter.h"

#include <throng/core/errors.h>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <iostream>
#include <sstream>
#include <string_view>
#include <utility>
#include <unistd.h>

#ifndef THRONG_VERSION
#define THRONG_VERSION "0.0.0"
#endif

namespace throng::cli {
namespace {

std::string shell_quote(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=:,+@%") == std::string::npos) {
    return s;
  }
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') out += "'\\''";
    else out += c;
  }
  return out + "'";
}

// "key: value" lines for a human; nested objects indent, arrays of scalars stay on one line.
void print_human(std::ostream& out, const Report& value, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  for (auto it = value.begin(); it != value.end(); ++it) {
    const Report& v = it.value();
    if (v.is_object()) {
      out << pad << it.key() << ":\n";
      print_human(out, v, indent + 2);
    } else if (v.is_array() && !v.empty() && v.front().is_object()) {
      out << pad << it.key() << ":\n";
      for (const auto& e : v) {
        out << pad << "  -\n";
        print_human(out, e, indent + 4);
      }
    } else if (v.is_string()) {
      out << pad << it.key() << ": " << v.get<std::string>() << "\n";
    } else {
      out << pad << it.key() << ": " << v.dump() << "\n";
    }
  }
}

}  // namespace

// Flags that only steer how a run proceeds, never what it computes: left out of the command line that outputs
// record, so a run resumed with `throng run --resume` writes the same bits as one never interrupted.
// (flag, takes a separate value)
constexpr std::pair<std::string_view, bool> steering_flags[] = {{"--resume", false}, {"--checkpoint-dir", true}};

Context::Context(int argc, char** argv, Process& process) : process_(process) {
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    bool steering = false;
    for (const auto& [flag, takes_value] : steering_flags) {
      if (arg == flag) {
        steering = true;
        if (takes_value) ++i;
      } else if (takes_value && arg.substr(0, flag.size() + 1) == std::string(flag) + "=") {
        steering = true;
      }
    }
    if (!steering) command_line_ += (command_line_.empty() ? "" : " ") + shell_quote(argv[i]);
  }
}

Context::~Context() = default;

struct Context::ProgressScope::View final : Progress {
  View(Progress& parent_, double first_, double span_, std::string label_)
      : parent(parent_), first(first_), span(span_), label(std::move(label_)) {}
  void update(double fraction, std::string_view stage) override {
    parent.update(first + span * std::clamp(fraction, 0.0, 1.0), label + ": " + std::string(stage));
  }
  Progress& parent;
  double first, span;
  std::string label;
};

Context::ProgressScope::ProgressScope(Context& context, double first, double span, std::string label)
    : context_(context), previous_(context.scoped_progress_) {
  view_ = std::make_unique<View>(context.progress(), first, span, std::move(label));
  context_.scoped_progress_ = view_.get();
}

Context::ProgressScope::~ProgressScope() { context_.scoped_progress_ = previous_; }

Progress& Context::progress() {
  if (scoped_progress_) return *scoped_progress_;
  if (!progress_) {
    if (global.quiet) progress_ = std::make_unique<NoProgress>();
    else progress_ = std::make_unique<ProgressReporter>(::isatty(STDERR_FILENO) != 0);
  }
  return *progress_;
}

void Context::limit_threads() {
  if (threads_limited_) return;
  process_.limit_threads(global.threads);
  threads_limited_ = true;
}

ConfigNode Context::load_job(const std::filesystem::path& path) const {
  ConfigNode job = ConfigNode::load_file(path);
  if (global.set.empty()) return job;
  return job.with_overrides(global.set);
}

ConfigNode Context::job(const std::filesystem::path& path, const std::vector<Override>& flags, const std::string& name) const {
  std::vector<Override> overrides = flags;
  for (const std::string& s : global.set) overrides.push_back(parse_set(s));
  const ConfigNode file = path.empty() ? ConfigNode(YAML::Node(YAML::NodeType::Map), name) : ConfigNode::load_file(path);
  if (overrides.empty()) return file;  // keeps the file as it is (a null job stays null)
  return file.with_overrides(overrides);
}

Provenance Context::provenance(const YAML::Node& effective_options, const std::vector<std::string>& inputs,
                               const std::vector<std::string>& credits) const {
  Provenance p;
  p.program_version = THRONG_VERSION;
  p.command_line = command_line_;
  p.options = to_yaml_text(effective_options);
  p.seed = global.seed;
  p.inputs = inputs;
  p.add_credits(credits);
  return p;
}

bool Context::print_config_if_asked(const YAML::Node& effective_options) const {
  if (!global.print_config) return false;
  std::cout << to_yaml_text(effective_options);
  return true;
}

std::string Context::render(const Report& report) const {
  std::ostringstream out;
  if (global.json) out << report.dump(2) << "\n";
  else print_human(out, report, 0);
  return out.str();
}

void Context::print(const Report& report) const {
  std::cout << render(report);
  std::cout.flush();
}

spdlog::logger& Context::log() const {
  if (!logger_) {
    logger_ = spdlog::stderr_color_st("throng");
    logger_->set_pattern("%^%l%$: %v");
    logger_->set_level(global.quiet ? spdlog::level::warn : spdlog::level::info);
  }
  return *logger_;
}

void Context::info(const std::string& message) const { log().info(message); }
void Context::warn(const std::string& message) const { log().warn(message); }

}  // namespace throng::cli
