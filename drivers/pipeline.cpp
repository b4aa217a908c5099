#include "pipeline.h"

#include "checkpoint.h"
#include "rank_outcome.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>

#include <cstdio>
#include <exception>
#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <iostream>
#include <map>
#include <set>
#include <unistd.h>

namespace throng::cli {
namespace {

const std::set<std::string> pipeline_keys{"step", "name", "input", "inputs", "job", "output"};

void flush_stdout() {
  std::cout.flush();
  std::fflush(stdout);
}

// Runs `step` on rank 0 alone and gives every rank its outcome: rank 0 rethrows its own error, the others throw
// one of the same kind (exit code) and message, so all ranks leave the pipeline at the same step. The other
// ranks get no result (the steps run this way make no crowd). One rank: just runs it.
template <class Step>
std::optional<StepResult> on_rank_0(Step&& step, const Communicator& ranks) {
  if (ranks.size() == 1) return step();
  std::optional<StepResult> result;
  std::exception_ptr failure;
  std::vector<std::byte> outcome;  // empty: done; else the exit code, then the message
  if (ranks.rank() == 0) {
    try {
      result = step();
    } catch (...) {
      failure = std::current_exception();
      outcome = encoded_outcome(failure);
    }
  }
  ranks.broadcast(outcome, 0);
  if (failure) std::rethrow_exception(failure);
  if (outcome.empty()) return result;
  throw_encoded(outcome);
}

// A step's `output` path as an absolute normal path (as given when it cannot be made absolute); empty when the
// step names none. named_outputs() and output_rewritten() compare outputs this way.
std::filesystem::path output_path_of(const YAML::Node& step) {
  if (!step.IsMap() || !step["output"] || !step["output"].IsScalar()) return {};
  const std::string given = step["output"].Scalar();
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::absolute(given, ec);
  return ec ? std::filesystem::path(given) : p.lexically_normal();
}

// A pipeline names its outputs, so the folders they go in are made as the run reaches each step (as a build tool
// makes its output folders). A single command's -o into a missing folder stays an I/O error (exit 4): there a
// missing folder is more likely a typo than a plan.
void make_output_folder(const std::string& output) {
  const std::filesystem::path folder = std::filesystem::path(output).parent_path();
  if (folder.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw IoError(output + ": cannot make the folder " + folder.string() + ": " + ec.message());
}

Command* find(const std::vector<Command*>& commands, const std::string& which) {
  for (Command* c : commands) {
    if (c->name() == which && c->name() != "run") return c;
  }
  return nullptr;
}

// The step's own keys: its job file's, then its inline keys over them, without the pipeline keys (and without
// `output` when the step makes a crowd: the pipeline writes it). Each key keeps its file for messages and paths.
ConfigNode own_keys(const ConfigNode& step, bool makes_crowd) {
  std::vector<ConfigNode> layers;
  std::string source = step.source();
  if (auto j = step.find("job")) {
    const std::filesystem::path path = j->as_path();
    layers.push_back(ConfigNode::load_file(path));
    if (!layers.back().is_null() && !layers.back().is_map()) layers.back().fail("a step's job file must hold a mapping of keys");
    source = path.string() + " and " + source;
  }
  YAML::Node inline_keys(YAML::NodeType::Map);
  for (auto it = step.yaml().begin(); it != step.yaml().end(); ++it) {
    const std::string key = it->first.Scalar();
    if (pipeline_keys.count(key) && !(key == "output" && !makes_crowd)) continue;
    inline_keys.force_insert(it->first, it->second);  // the key nodes themselves: messages give their line
  }
  layers.push_back(ConfigNode(inline_keys, step.source()));
  return ConfigNode::layered(layers, source);
}

// The crowds a step reads: named steps or files (relative to the job's folder), else the last crowd made (when
// the step's command reads crowds at all).
std::vector<const CrowdFile*> inputs_of(const ConfigNode& step, std::map<std::string, CrowdFile>& named,
                                        const std::optional<CrowdFile>& last, bool reads_crowds) {
  auto resolve = [&](const ConfigNode& ref) -> const CrowdFile* {
    if (auto it = named.find(ref.as_string()); it != named.end()) return &it->second;
    const std::filesystem::path path = ref.as_path();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
      throw IoError(ref.where() + ": '" + ref.as_string() + "' is neither an earlier step's name nor an existing crowd file");
    }
    return &named.emplace(path.string(), read_crowd_file(path)).first->second;
  };
  std::vector<const CrowdFile*> inputs;
  if (auto in = step.find("input")) inputs.push_back(resolve(*in));
  if (auto ins = step.find("inputs")) {
    for (const auto& in : ins->elements()) inputs.push_back(resolve(in));
  }
  if (!step.has("input") && !step.has("inputs") && last && reads_crowds) inputs.push_back(&*last);
  return inputs;
}

// A step that writes its own file (export, plot) never writes onto a crowd file it reads: the input is left
// untouched, as `throng export CROWD.h5 -o CROWD.h5` leaves it (ConfigError, exit 2).
void check_output_is_not_an_input(const ConfigNode& step) {
  const auto output = step.find("output");
  if (!output) return;
  auto check = [&](const ConfigNode& ref) {
    std::error_code ec;
    if (std::filesystem::exists(ref.as_path(), ec)) check_distinct(ref.as_path(), output->as_string());
  };
  if (auto in = step.find("input")) check(*in);
  if (auto ins = step.find("inputs")) {
    for (const auto& in : ins->elements()) check(in);
  }
}

// For each step that makes a crowd: whether a later step reads it, by its name or as the last crowd made (a later
// step that names no input and reads crowds, with no crowd made in between). Only those a checkpoint keeps.
std::vector<bool> read_later(const std::vector<ConfigNode>& steps, const std::vector<Command*>& commands) {
  // Read from the YAML itself: a malformed input is the step's error, reported (with its step) when it runs.
  auto names_input = [](const ConfigNode& step, const std::string& name) {
    const YAML::Node in = step.yaml()["input"], ins = step.yaml()["inputs"];
    if (in && in.IsScalar() && in.Scalar() == name) return true;
    if (ins && ins.IsSequence()) {
      for (const YAML::Node& e : ins) {
        if (e.IsScalar() && e.Scalar() == name) return true;
      }
    }
    return false;
  };
  std::vector<bool> read(steps.size(), false);
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const YAML::Node n = steps[i].yaml()["name"];
    const std::string name = n && n.IsScalar() ? n.Scalar() : "";
    bool is_last = true, name_bound = !name.empty();
    for (std::size_t j = i + 1; j < steps.size() && !read[i] && (is_last || name_bound); ++j) {
      const ConfigNode& later = steps[j];
      const Command* command = find(commands, later.at("step").as_string());
      if (name_bound && names_input(later, name)) read[i] = true;
      if (is_last && command->reads_crowds() && !later.has("input") && !later.has("inputs")) read[i] = true;
      if (command->makes_crowd()) {
        is_last = false;
        if (const YAML::Node m = later.yaml()["name"]; m && m.IsScalar() && m.Scalar() == name) name_bound = false;
      }
    }
  }
  return read;
}

// What a checkpoint of this pipeline must agree with to be resumed (drivers/checkpoint.h): the program, the job
// as loaded (with --set), the seed, the number of ranks running it, and every step's job file as it is now.
std::string fingerprint_of(const ConfigNode& job, const std::vector<ConfigNode>& steps, const Context& context, int ranks) {
  std::string text = std::string(THRONG_VERSION) + '\0' + to_yaml_text(job.yaml()) + '\0' + std::to_string(context.global.seed) +
                     '\0' + std::to_string(ranks);
  for (const ConfigNode& step : steps) {
    const auto j = step.find("job");
    if (!j || !j->yaml().IsScalar()) continue;  // a malformed one is the step's error when it runs
    std::ifstream in(j->as_path(), std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    text += '\0' + j->as_path().string() + '\0' + bytes.str();
  }
  return stable_hash(text);
}

// For each step: whether a later step writes its `output` path again (then the checkpoint cannot name that file as
// the holder of this step's crowd). Compared as absolute normal paths, as named_outputs() gives them.
std::vector<bool> output_rewritten(const std::vector<ConfigNode>& steps) {
  std::vector<bool> rewritten(steps.size(), false);
  std::map<std::filesystem::path, std::size_t> last_writer;
  for (std::size_t i = steps.size(); i-- > 0;) {
    const std::filesystem::path out = output_path_of(steps[i].yaml());
    if (out.empty()) continue;
    rewritten[i] = last_writer.count(out) > 0;
    last_writer[out] = i;
  }
  return rewritten;
}

}  // namespace

StdoutRedirect::StdoutRedirect(int target) {
  flush_stdout();
  saved_ = ::fcntl(1, F_DUPFD_CLOEXEC, 0);
  const int fd = target >= 0 ? target : ::open("/dev/null", O_WRONLY);
  if (saved_ < 0 || fd < 0 || ::dup2(fd, 1) < 0) throw IoError("run: cannot redirect standard output");
  if (target < 0) ::close(fd);
}

StdoutRedirect::~StdoutRedirect() {
  flush_stdout();
  if (saved_ >= 0) {
    ::dup2(saved_, 1);
    ::close(saved_);
  }
}

std::vector<std::filesystem::path> named_outputs(const ConfigNode& job) {
  std::vector<std::filesystem::path> out;
  const YAML::Node steps = job.yaml()["steps"];
  if (!steps || !steps.IsSequence()) return out;
  for (const YAML::Node& step : steps) {
    if (std::filesystem::path p = output_path_of(step); !p.empty()) out.push_back(std::move(p));
  }
  return out;
}

std::optional<Report> run_pipeline(const std::filesystem::path& job_path, const std::vector<Command*>& commands,
                                   Context& context, bool collective, const CheckpointOptions& checkpoints) {
  const bool writer = !collective || context.writer();
  const ConfigNode job = context.load_job(job_path);
  if (context.print_config_if_asked(job.yaml())) return std::nullopt;
  const std::vector<ConfigNode> steps = job.at("steps").elements();
  if (steps.empty()) job.at("steps").fail("the pipeline has no steps");
  for (const ConfigNode& step : steps) {
    if (!step.is_map()) step.fail("a step is a mapping with at least the key 'step'");
    (void)step.keys();  // every key of a step is either a pipeline key or the step's own (checked by the step)
    if (!find(commands, step.at("step").as_string())) step.at("step").fail("unknown step '" + step.at("step").as_string() + "'");
  }
  job.finish();
  context.limit_threads();

  std::map<std::string, CrowdFile> named;  // results of named steps and crowds read from files
  std::optional<CrowdFile> last;           // the last crowd made
  std::size_t written = 0;
  std::size_t first = 0;
  // A pipeline run by every rank is checkpointed by rank 0; each job of a batch by the rank that runs it, which
  // keeps the finished job's record until the batch has succeeded.
  const bool in_batch = !collective;
  const Communicator& ranks = collective ? context.communicator() : Communicator::single();
  PipelineCheckpoint checkpoint(checkpoints, job_path, fingerprint_of(job, steps, context, ranks.size()), steps.size(), ranks,
                                context);
  const std::vector<bool> crowd_read_later = read_later(steps, commands);
  const std::vector<bool> rewritten_later = output_rewritten(steps);
  if (auto restored = checkpoint.restore()) {
    if (restored->report) {
      checkpoint.completed(*restored->report, in_batch);
      return restored->report;
    }
    named = std::move(restored->named);
    last = std::move(restored->last);
    written = restored->written;
    first = restored->done;
  }
  for (std::size_t i = first; i < steps.size(); ++i) {
    const ConfigNode& step = steps[i];
    Command* command = find(commands, step.at("step").as_string());
    const std::string label = "step " + std::to_string(i + 1) + "/" + std::to_string(steps.size()) + " " + command->name();
    checkpoint.starting(i);
    std::optional<StepResult> result;
    std::vector<const CrowdFile*> inputs;
    {
      Context::ProgressScope scope(context, static_cast<double>(i) / steps.size(), 1.0 / steps.size(), label);
      try {
        inputs = inputs_of(step, named, last, command->reads_crowds());
        if (!command->makes_crowd()) check_output_is_not_an_input(step);
        // Every rank makes it (the same folder on a shared file system, or its own): a failure is then every
        // rank's, never rank 0's alone while the others wait in a collective step.
        if (const auto o = step.find("output")) make_output_folder(o->as_string());
        const ConfigNode own = own_keys(step, command->makes_crowd());
        if (collective && !command->makes_crowd()) {
          result = on_rank_0([&] { return command->run_step(own, inputs, context); }, context.communicator());
        } else {
          result = command->run_step(own, inputs, context);
        }
      } catch (const Error& e) {
        throw_as(e.exit_code(), label + ": " + e.what());
      }
    }
    if (!result) {
      checkpoint.finished(i, nullptr, "", written, {}, false, false);
      continue;
    }
    if (step.has("output")) ++written;
    const auto o = step.find("output");
    if (o && writer) {
      // Credits of everything the crowd derives from are kept; the options are the whole pipeline's.
      std::vector<std::string> credits;
      for (const CrowdFile* c : inputs) credits.insert(credits.end(), c->provenance.credits.begin(), c->provenance.credits.end());
      credits.insert(credits.end(), result->crowd.provenance.credits.begin(), result->crowd.provenance.credits.end());
      result->crowd.provenance = context.provenance(job.yaml(), {job_path.string()}, credits);
      write_crowd_file(o->as_string(), result->crowd, result->extra, context.global.storage);
      context.info(label + ": wrote " + o->as_string());
    }
    const auto n = step.find("name");
    checkpoint.finished(i, &result->crowd, n ? n->as_string() : "", written, o ? std::filesystem::path(o->as_string()) : std::filesystem::path(),
                        crowd_read_later[i], rewritten_later[i]);
    if (n) named.insert_or_assign(n->as_string(), result->crowd);
    last = std::move(result->crowd);
  }
  Report r;
  r["job"] = job_path.string();
  r["steps"] = steps.size();
  r["crowd_files_written"] = written;
  checkpoint.completed(r, in_batch);
  return r;
}

}  // namespace throng::cli
