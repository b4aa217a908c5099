#include "checkpoint.h"

#include "rank_outcome.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

namespace throng::cli {
namespace {

namespace fs = std::filesystem;

constexpr int state_format = 1;

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw IoError(path.string() + ": cannot read the checkpoint");
  return text.str();
}

void write_text(const fs::path& path, const std::string& text) {
  AtomicOutput out(path);
  out.write(text);
  out.commit();
}

// Creates `folder` and its parents. Another run finishing at the same moment may remove the shared checkpoint
// folder while it is still empty (remove_checkpoints): one more try then.
void make_folder(const fs::path& folder) {
  std::error_code ec;
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (fs::create_directories(folder, ec) || fs::is_directory(folder, ec)) return;
  }
  throw IoError(folder.string() + ": cannot create the checkpoint folder (" + ec.message() + ")");
}

}  // namespace

std::string stable_hash(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

fs::path checkpoint_folder(const CheckpointOptions& options, const fs::path& job_path) {
  std::error_code ec;
  fs::path absolute = fs::absolute(job_path, ec);
  if (ec) absolute = job_path;
  fs::path folder = fs::absolute(options.folder, ec);
  if (ec) folder = options.folder;
  return folder.lexically_normal() / (job_path.stem().string() + "-" + stable_hash(absolute.lexically_normal().string()));
}

void remove_checkpoints(const CheckpointOptions& options, const std::vector<fs::path>& jobs) {
  std::error_code ec;
  for (const fs::path& job : jobs) fs::remove_all(checkpoint_folder(options, job), ec);
  fs::remove(options.folder, ec);  // only when empty: another run's checkpoints stay
}

PipelineCheckpoint::PipelineCheckpoint(const CheckpointOptions& options, const fs::path& job_path, std::string fingerprint,
                                       std::size_t steps, bool writer, Context& context)
    : folder_(checkpoint_folder(options, job_path)),
      job_(job_path.string()),
      fingerprint_(std::move(fingerprint)),
      steps_(steps),
      resume_(options.resume),
      writer_(writer),
      context_(context) {}

fs::path PipelineCheckpoint::crowd_path(std::size_t index) const {
  return folder_ / ("step-" + std::to_string(index + 1) + ".h5");
}

void PipelineCheckpoint::disable(const std::string& why) {
  if (!writer_) return;
  writer_ = false;
  context_.warn("run: " + job_ + ": no checkpoint (" + why + "); this run cannot be resumed if it is interrupted");
}

std::optional<RestoredPipeline> PipelineCheckpoint::restore() {
  std::error_code ec;
  const fs::path state_path = folder_ / "state.json";
  if (!resume_) {
    if (writer_) fs::remove_all(folder_, ec);
    return std::nullopt;
  }
  if (!fs::exists(state_path, ec)) {
    context_.info("run: " + job_ + ": no checkpoint in " + folder_.string() + ", starting from the first step");
    return std::nullopt;
  }
  auto damaged = [&](const std::string& what) {
    return InputError(state_path.string() + ": a damaged checkpoint (" + what + "); run without --resume to start over");
  };
  try {
    const Report state = Report::parse(read_text(state_path));
    if (state.at("format").get<int>() != state_format) throw damaged("format " + state.at("format").dump() + " is not this program's");
    if (state.at("fingerprint").get<std::string>() != fingerprint_) {
      throw ConfigError("run --resume: the checkpoint " + folder_.string() + " was made by another version of " + job_ +
                        " (its job files, --set, --seed or the program differ); run without --resume to start over");
    }
    RestoredPipeline r;
    r.done = state.at("done").get<std::size_t>();
    r.written = state.at("written").get<std::size_t>();
    if (r.done > steps_) throw damaged("more steps done than the job has");
    if (const auto& running = state.at("running"); !running.is_null()) {
      context_.info("run: " + job_ + ": the run being resumed stopped during step " + std::to_string(running.get<std::size_t>()) +
                    "/" + std::to_string(steps_) + " on rank " + std::to_string(state.at("rank").get<int>()) + " (pid " +
                    std::to_string(state.at("pid").get<long>()) + " on " + state.at("host").get<std::string>() + ")");
    }
    if (state.contains("report")) {
      r.report = state.at("report");
      context_.info("run: " + job_ + ": finished in the run being resumed");
      done_ = r.done;
      written_ = r.written;
      return r;
    }
    // Each kept crowd is read once, however many names share it.
    std::map<std::size_t, CrowdFile> crowds;
    for (const auto& [index, path] : state.at("files").items()) files_[std::stoul(index)] = path.get<std::string>();
    auto crowd_of = [&](std::size_t index) -> const CrowdFile& {
      if (index >= r.done || !files_.count(index)) throw damaged("it names the crowd of step " + std::to_string(index + 1) + ", which it does not keep");
      auto it = crowds.find(index);
      if (it == crowds.end()) {
        try {
          it = crowds.emplace(index, read_crowd_file(files_.at(index))).first;
        } catch (const Error& e) {
          throw_as(e.exit_code(), "run --resume: the checkpoint " + folder_.string() + " keeps step " + std::to_string(index + 1) +
                                      "'s crowd in " + files_.at(index).string() + ", which cannot be read: " + e.what());
        }
      }
      return it->second;
    };
    for (const auto& [name, index] : state.at("crowds").items()) {
      crowds_[name] = index.get<std::size_t>();
      r.named.insert_or_assign(name, crowd_of(crowds_[name]));
    }
    if (const auto& last = state.at("last"); !last.is_null()) {
      last_ = last.get<std::size_t>();
      r.last = crowd_of(*last_);
    }
    done_ = r.done;
    written_ = r.written;
    context_.info("run: " + job_ + ": resuming after step " + std::to_string(r.done) + "/" + std::to_string(steps_) +
                  " (checkpoint " + folder_.string() + ")");
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw damaged(e.what());
  }
}

void PipelineCheckpoint::write_state(std::optional<std::size_t> running, const Report* report) {
  if (!writer_) return;
  Report state;
  state["format"] = state_format;
  state["job"] = job_;
  state["fingerprint"] = fingerprint_;
  state["steps"] = steps_;
  state["done"] = done_;
  state["running"] = running ? Report(*running + 1) : Report(nullptr);
  state["rank"] = context_.process().world_rank();
  state["pid"] = static_cast<long>(::getpid());
  state["host"] = host_name();
  Report crowds = Report::object();
  for (const auto& [name, index] : crowds_) crowds[name] = index;
  state["crowds"] = crowds;
  state["last"] = last_ ? Report(*last_) : Report(nullptr);
  Report files = Report::object();
  for (const auto& [index, path] : files_) files[std::to_string(index)] = path.string();
  state["files"] = files;
  state["written"] = written_;
  if (report) state["report"] = *report;
  try {
    make_folder(folder_);
    write_text(folder_ / "state.json", state.dump(1) + "\n");
  } catch (const Error& e) {
    disable(e.what());
  }
}

void PipelineCheckpoint::starting(std::size_t index) {
  // Once per run: after that, each step's record names the next step as under way (one write per step).
  if (started_) return;
  started_ = true;
  write_state(index, nullptr);
}

void PipelineCheckpoint::finished(std::size_t index, const CrowdFile* crowd, const std::string& name, std::size_t written,
                                  const fs::path& output, bool read_later) {
  done_ = index + 1;
  written_ = written;
  if (crowd) {
    // A crowd no later step reads is not kept (nor named: no later step names it either).
    last_.reset();
    if (!name.empty()) crowds_.erase(name);
    if (read_later) {
      std::error_code ec;
      fs::path file = output.empty() ? fs::path() : fs::absolute(output, ec);
      if (file.empty() || ec) {
        file = crowd_path(index);
        if (writer_) {
          try {
            make_folder(folder_);
            write_crowd_file(file, *crowd, {}, CrowdStorage::plain);  // read back soon: deflate is not worth its time
          } catch (const Error& e) {
            disable(e.what());
          }
        }
      }
      files_[index] = file;
      last_ = index;
      if (!name.empty()) crowds_[name] = index;
    }
  }
  write_state(done_ < steps_ ? std::optional<std::size_t>(done_) : std::nullopt, nullptr);
  // Crowds no later step can read any more (neither named nor the last): their copies go.
  std::set<std::size_t> kept;
  for (const auto& [n, i] : crowds_) kept.insert(i);
  if (last_) kept.insert(*last_);
  for (auto it = files_.begin(); it != files_.end();) {
    if (kept.count(it->first)) {
      ++it;
      continue;
    }
    std::error_code ec;
    if (writer_ && it->second == crowd_path(it->first)) fs::remove(it->second, ec);
    it = files_.erase(it);
  }
}

void PipelineCheckpoint::completed(const Report& report, bool keep) {
  if (!keep) {
    if (!writer_) return;
    std::error_code ec;
    fs::remove_all(folder_, ec);
    fs::remove(folder_.parent_path(), ec);  // only when empty: other jobs' checkpoints stay
    return;
  }
  crowds_.clear();
  last_.reset();
  files_.clear();
  write_state(std::nullopt, &report);
  if (!writer_) return;
  for (std::size_t i = 0; i < steps_; ++i) {
    std::error_code ec;
    fs::remove(crowd_path(i), ec);
  }
}

}  // namespace throng::cli
