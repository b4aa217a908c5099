#include "checkpoint.h"

#include "rank_outcome.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

namespace throng::cli {
namespace {

namespace fs = std::filesystem;

constexpr int state_format = 2;

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

// Opens and locks (flock, exclusive, without waiting) the folder `folder`, created first when `create`: its
// descriptor, -1 when another process holds the lock, -2 when there is no such folder (and not `create`). Tries
// again when the folder was removed or replaced between the open and the lock (its holder finished and removed it).
int lock_folder(const fs::path& folder, bool create) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    if (create) make_folder(folder);
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) {
      if (!create && errno == ENOENT) return -2;
      continue;
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      ::close(fd);
      if (error == EWOULDBLOCK) return -1;
      throw IoError(folder.string() + ": cannot lock the checkpoint folder (" + std::strerror(error) + ")");
    }
    struct stat held {}, now {};
    if (::fstat(fd, &held) == 0 && ::stat(folder.c_str(), &now) == 0 && held.st_dev == now.st_dev && held.st_ino == now.st_ino) {
      return fd;
    }
    ::close(fd);
  }
  throw IoError(folder.string() + ": cannot lock the checkpoint folder (it keeps being removed)");
}

// Empties the checkpoint folder `folder`, its state first: a run killed part-way leaves either the whole
// checkpoint or a folder without a state (which --resume takes for no checkpoint), never a state naming a crowd
// copy already removed (the order of a directory's entries is the file system's).
// A state that cannot be removed (a permission, an I/O error) leaves the copies it names where they are.
void clear_folder(const fs::path& folder) {
  std::error_code ec;
  if (!fs::remove(folder / "state.json", ec) && ec && ec != std::errc::no_such_file_or_directory) return;
  for (const auto& entry : fs::directory_iterator(folder, ec)) fs::remove_all(entry.path(), ec);
}

// `path` as it is now (size and modification time), for a KeptFile.
PipelineCheckpoint::KeptFile stamp_of(const fs::path& path) {
  PipelineCheckpoint::KeptFile kept{path};
  std::error_code ec;
  kept.size = fs::file_size(path, ec);
  if (ec) throw IoError(path.string() + ": cannot read its size (" + ec.message() + ")");
  const auto modified = fs::last_write_time(path, ec);
  if (ec) throw IoError(path.string() + ": cannot read its modification time (" + ec.message() + ")");
  kept.modified = std::chrono::duration_cast<std::chrono::nanoseconds>(modified.time_since_epoch()).count();
  return kept;
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
  for (const fs::path& job : jobs) {
    const fs::path folder = checkpoint_folder(options, job);
    int fd = -2;
    try {
      fd = lock_folder(folder, false);
    } catch (const Error&) {
      continue;  // left as it is: a later run of the job replaces it
    }
    if (fd < 0) continue;  // none, or another run of the job holds it
    std::error_code ec;
    clear_folder(folder);
    fs::remove(folder, ec);
    ::close(fd);
  }
  std::error_code ec;
  fs::remove(options.folder, ec);  // only when empty: another run's checkpoints stay
}

PipelineCheckpoint::PipelineCheckpoint(const CheckpointOptions& options, const fs::path& job_path, std::string fingerprint,
                                       std::size_t steps, const Communicator& ranks, Context& context)
    : folder_(checkpoint_folder(options, job_path)),
      job_(job_path.string()),
      fingerprint_(std::move(fingerprint)),
      steps_(steps),
      resume_(options.resume),
      ranks_(ranks),
      owner_(ranks.rank() == 0),
      writing_(ranks.rank() == 0),
      context_(context) {}

PipelineCheckpoint::~PipelineCheckpoint() {
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

fs::path PipelineCheckpoint::crowd_path(std::size_t index) const {
  return folder_ / ("step-" + std::to_string(index + 1) + ".h5");
}

void PipelineCheckpoint::remove_folder() {
  std::error_code ec;
  clear_folder(folder_);
  fs::remove(folder_, ec);
  fs::remove(folder_.parent_path(), ec);  // only when empty: other jobs' checkpoints stay
}

void PipelineCheckpoint::disable(const std::string& why) {
  if (!writing_) return;
  writing_ = false;
  if (owner_) remove_folder();  // what was written would resume from a point this run has passed
  context_.warn("run: " + job_ + ": no checkpoint (" + why + "); this run cannot be resumed if it is interrupted");
}

std::string PipelineCheckpoint::take_folder() {
  try {
    lock_fd_ = lock_folder(folder_, true);
  } catch (const Error& e) {
    owner_ = false;  // not locked: nothing here is this run's to remove
    disable(e.what());
    if (resume_) context_.info("run: " + job_ + ": no checkpoint in " + folder_.string() + ", starting from the first step");
    return {};
  }
  if (lock_fd_ == -1) {
    if (resume_) {
      throw ConfigError("run --resume: another run of " + job_ + " is under way (it holds the checkpoint " + folder_.string() +
                        "); wait for it to end, or stop it and resume then");
    }
    owner_ = writing_ = false;
    context_.warn("run: " + job_ + ": another run of this job is under way (it holds the checkpoint " + folder_.string() +
                  "): this run is not checkpointed and cannot be resumed if it is interrupted");
    return {};
  }
  std::error_code ec;
  const fs::path state_path = folder_ / "state.json";
  if (!resume_) {
    clear_folder(folder_);
    return {};
  }
  if (!fs::exists(state_path, ec)) {
    context_.info("run: " + job_ + ": no checkpoint in " + folder_.string() + ", starting from the first step");
    return {};
  }
  return read_text(state_path);
}

std::optional<RestoredPipeline> PipelineCheckpoint::restore() {
  // Rank 0 takes the folder and reads the state; every rank parses it and reads the crowds it keeps; all agree
  // (a collective) before rank 0 goes on to write.
  std::string text;
  on_every_rank([&] { if (ranks_.rank() == 0) text = take_folder(); }, ranks_);
  if (ranks_.size() > 1) {
    std::vector<std::byte> bytes = bytes_of(text);
    ranks_.broadcast(bytes, 0);
    text = text_of(bytes);
  }
  std::optional<RestoredPipeline> restored;
  on_every_rank([&] { restored = parse_state(text); }, ranks_);
  return restored;
}

std::optional<RestoredPipeline> PipelineCheckpoint::parse_state(const std::string& text) {
  if (text.empty()) return std::nullopt;
  const fs::path state_path = folder_ / "state.json";
  const bool speaks = ranks_.rank() == 0;
  auto damaged = [&](const std::string& what) {
    return InputError(state_path.string() + ": a damaged checkpoint (" + what + "); run without --resume to start over");
  };
  try {
    const Report state = Report::parse(text);
    if (state.at("format").get<int>() != state_format) throw damaged("format " + state.at("format").dump() + " is not this program's");
    if (state.at("fingerprint").get<std::string>() != fingerprint_) {
      throw ConfigError("run --resume: the checkpoint " + folder_.string() + " was made by another version of " + job_ +
                        " (its job files, --set, --seed, the number of MPI ranks or the program differ); run without --resume"
                        " to start over");
    }
    RestoredPipeline r;
    r.done = state.at("done").get<std::size_t>();
    r.written = state.at("written").get<std::size_t>();
    if (r.done > steps_) throw damaged("more steps done than the job has");
    done_ = r.done;
    written_ = r.written;
    if (const auto& running = state.at("running"); !running.is_null() && speaks) {
      context_.info("run: " + job_ + ": the run being resumed stopped during step " + std::to_string(running.get<std::size_t>()) +
                    "/" + std::to_string(steps_) + " on rank " + std::to_string(state.at("rank").get<int>()) + " (pid " +
                    std::to_string(state.at("pid").get<long>()) + " on " + state.at("host").get<std::string>() + ")");
    }
    if (state.contains("report")) {
      r.report = state.at("report");
      if (speaks) context_.info("run: " + job_ + ": finished in the run being resumed");
      return r;
    }
    if (r.done == steps_) {
      // Every step was done and the run stopped before it removed its checkpoint: nothing is left to run, so no
      // kept crowd is read (the removal may have taken some of them).
      if (speaks) context_.info("run: " + job_ + ": every step was done in the run being resumed");
      return r;
    }
    for (const auto& [index, file] : state.at("files").items()) {
      files_[std::stoul(index)] = KeptFile{file.at("path").get<std::string>(), file.at("size").get<std::uintmax_t>(),
                                           file.at("modified").get<std::int64_t>()};
    }
    // Each kept crowd is read once, however many names share it.
    std::map<std::size_t, CrowdFile> crowds;
    auto crowd_of = [&](std::size_t index) -> const CrowdFile& {
      if (index >= r.done || !files_.count(index)) throw damaged("it names the crowd of step " + std::to_string(index + 1) + ", which it does not keep");
      auto it = crowds.find(index);
      if (it != crowds.end()) return it->second;
      const KeptFile& kept = files_.at(index);
      const std::string what = "the checkpoint " + folder_.string() + " keeps step " + std::to_string(index + 1) + "'s crowd in " +
                               kept.path.string();
      std::error_code ec;
      if (fs::exists(kept.path, ec)) {
        const KeptFile now = stamp_of(kept.path);
        if (now.size != kept.size || now.modified != kept.modified) {
          throw ConfigError("run --resume: " + what + ", which changed after the run being resumed wrote it; run without"
                            " --resume to start over");
        }
      }
      try {
        return crowds.emplace(index, read_crowd_file(kept.path)).first->second;
      } catch (const Error& e) {
        throw_as(e.exit_code(), "run --resume: " + what + ", which cannot be read: " + e.what());
      }
    };
    for (const auto& [name, index] : state.at("crowds").items()) {
      crowds_[name] = index.get<std::size_t>();
      r.named.insert_or_assign(name, crowd_of(crowds_[name]));
    }
    if (const auto& last = state.at("last"); !last.is_null()) {
      last_ = last.get<std::size_t>();
      r.last = crowd_of(*last_);
    }
    if (speaks) {
      context_.info("run: " + job_ + ": resuming after step " + std::to_string(r.done) + "/" + std::to_string(steps_) +
                    " (checkpoint " + folder_.string() + ")");
    }
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw damaged(e.what());
  } catch (const std::logic_error& e) {  // std::stoul on a step index that is not one
    throw damaged(e.what());
  }
}

void PipelineCheckpoint::write_state(std::optional<std::size_t> running, const Report* report) {
  if (!writing_) return;
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
  for (const auto& [index, kept] : files_) {
    files[std::to_string(index)] = {{"path", kept.path.string()}, {"size", kept.size}, {"modified", kept.modified}};
  }
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
                                  const fs::path& output, bool read_later, bool output_rewritten) {
  done_ = index + 1;
  written_ = written;
  if (crowd && writing_) {
    // A crowd no later step reads is not kept (nor named: no later step names it either).
    last_.reset();
    if (!name.empty()) crowds_.erase(name);
    if (read_later) {
      try {
        std::error_code ec;
        fs::path file = output.empty() || output_rewritten ? fs::path() : fs::absolute(output, ec);
        if (file.empty() || ec) {
          file = crowd_path(index);
          make_folder(folder_);
          write_crowd_file(file, *crowd, {}, CrowdStorage::plain);  // read back soon: deflate is not worth its time
        }
        files_[index] = stamp_of(file);
        last_ = index;
        if (!name.empty()) crowds_[name] = index;
      } catch (const Error& e) {
        disable(e.what());
      }
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
    if (writing_ && it->second.path == crowd_path(it->first)) fs::remove(it->second.path, ec);
    it = files_.erase(it);
  }
}

void PipelineCheckpoint::completed(const Report& report, bool keep) {
  if (!keep || !writing_) {
    if (owner_) remove_folder();
    return;
  }
  crowds_.clear();
  last_.reset();
  files_.clear();
  write_state(std::nullopt, &report);
  if (!writing_) return;
  for (std::size_t i = 0; i < steps_; ++i) {
    std::error_code ec;
    fs::remove(crowd_path(i), ec);
  }
}

}  // namespace throng::cli
