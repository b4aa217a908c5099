// throng run JOB.yaml: a pipeline of steps, each one of the subcommands, passing crowds in memory and writing
// files only where a step asks.
//
//   steps:
//     - step: import                      # the command; its keys follow, as in its job file
//       dataset: data/real/eth
//       name: eth                         # optional: later steps can take this result by name
//     - step: sketch
//       job: configs/sketch-paper.yaml    # optional: a job file for the step's keys (inline keys override it)
//       output: out/paper.h5              # optional: write this step's crowd here
//     - step: edit
//       input: paper                      # optional: a step name or a crowd file; default: the last crowd made
//       job: configs/edit-battlefield.yaml
//       output: out/edited.h5
//     - step: stitch
//       inputs: [eth, out/edited.h5]      # steps that read several crowds
//     - step: plot                        # steps that make pictures or tables use `output` for their file
//       overlay: paper
//       output: out/edited.png
//
// Pipeline keys: step, name, input, inputs, job, output. A failing step stops the run; files already written by
// earlier steps stay (each is complete: files are written atomically), the failing step leaves nothing.
//
// A step input that is neither an earlier step's name nor an existing file is an I/O error (exit 4, as for
// `throng edit missing.h5`); every error of a step, reading its inputs and job file included, is labelled
// "step i/n <command>".
//
// One pipeline under mpiexec: every rank runs every step that makes a crowd (the petsc backend shares the
// solves between the ranks), rank 0 alone writes the crowd files and prints (the other ranks' stdout goes to
// /dev/null). Steps that make a picture or a table (plot, export, info) write their own files: rank 0 alone
// runs them and tells the others how they ended, so a file is written once and a failing step stops every
// rank with the same exit code.
//
// Batch: `throng run A.yaml B.yaml jobs/` runs every job (folders: their *.yaml, *.yml) spread over the MPI
// ranks; a failing job does not stop the others; a summary lists them (drivers/batch.h). Before anything runs,
// two jobs naming the same output file are refused (exit 2). While the jobs run, whatever their steps print
// (an info step's report) goes to stderr, so stdout holds the summary alone (one JSON document with --json);
// the summary and the final "N of M jobs failed" come from rank 0 only.
#include "../batch.h"
#include "../rank_outcome.h"
#include "factories.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/linalg/mpi.h>
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <exception>
#include <iostream>
#include <map>
#include <set>
#include <fcntl.h>
#include <unistd.h>

namespace throng::cli {
namespace {

const std::set<std::string> pipeline_keys{"step", "name", "input", "inputs", "job", "output"};

// While alive, file descriptor 1 (stdout) points at `target` (another descriptor, or /dev/null when -1);
// restored afterwards. C++ and C streams are flushed on both edges so nothing lands on the wrong side.
class StdoutRedirect {
 public:
  explicit StdoutRedirect(int target) {
    flush();
    saved_ = ::dup(1);
    const int fd = target >= 0 ? target : ::open("/dev/null", O_WRONLY);
    if (saved_ < 0 || fd < 0 || ::dup2(fd, 1) < 0) throw IoError("run: cannot redirect standard output");
    if (target < 0) ::close(fd);
  }
  ~StdoutRedirect() {
    flush();
    if (saved_ >= 0) {
      ::dup2(saved_, 1);
      ::close(saved_);
    }
  }
  StdoutRedirect(const StdoutRedirect&) = delete;
  StdoutRedirect& operator=(const StdoutRedirect&) = delete;

 private:
  static void flush() {
    std::cout.flush();
    std::fflush(stdout);
  }
  int saved_ = -1;
};

// Runs `step` on rank 0 alone and gives every rank its outcome: rank 0 rethrows its own error, the others throw
// one of the same kind (exit code) and message, so all ranks leave the pipeline at the same step. The other
// ranks get no result (the steps run this way make no crowd). One rank: just runs it.
template <class Step>
std::optional<StepResult> on_rank_0(Step&& step) {
  if (mpi::size() == 1) return step();
  std::optional<StepResult> result;
  std::exception_ptr failure;
  std::vector<std::byte> outcome;  // empty: done; else the exit code, then the message
  if (mpi::rank() == 0) {
    try {
      result = step();
    } catch (...) {
      failure = std::current_exception();
      const ErrorOutcome e = outcome_of(failure);
      outcome = bytes_of(std::string(1, static_cast<char>(static_cast<int>(e.code))) + e.message);
    }
  }
  mpi::broadcast(outcome, 0);
  if (failure) std::rethrow_exception(failure);
  if (outcome.empty()) return result;
  const std::string text = text_of(outcome);
  throw_as(static_cast<ExitCode>(static_cast<unsigned char>(text[0])), text.substr(1));
}

// The outputs a job's steps name inline (crowd files and pictures), as absolute normal paths.
std::vector<std::filesystem::path> named_outputs(const ConfigNode& job) {
  std::vector<std::filesystem::path> out;
  const YAML::Node steps = job.yaml()["steps"];
  if (!steps || !steps.IsSequence()) return out;
  for (const YAML::Node& step : steps) {
    if (!step.IsMap() || !step["output"] || !step["output"].IsScalar()) continue;
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::absolute(step["output"].Scalar(), ec);
    out.push_back(ec ? std::filesystem::path(step["output"].Scalar()) : p.lexically_normal());
  }
  return out;
}

class RunCommand final : public Command {
 public:
  explicit RunCommand(std::vector<Command*> commands) : commands_(std::move(commands)) {}

  std::string name() const override { return "run"; }
  std::string summary() const override { return "Run a pipeline of steps (import, sketch, edit, ..., plot) from a YAML job"; }

  void setup(CLI::App& app) override {
    app.add_option("job", job_paths_, "Pipeline job (.yaml); several jobs or folders of them run as a batch over the MPI ranks")->required();
  }

  void run(Context& context) override {
    if (job_paths_.size() == 1 && !std::filesystem::is_directory(job_paths_.front())) {
      // One pipeline: under mpiexec every rank runs it (collective solves), rank 0 writes and prints.
      const bool writer = mpi::rank() == 0;  // starts MPI when launched by mpiexec
      std::optional<StdoutRedirect> silent;
      if (!writer) silent.emplace(-1);
      if (auto report = run_pipeline(job_paths_.front(), context, true)) context.print(*report);
      return;
    }
    // A batch (drivers/batch.h): several jobs or folders, spread over the MPI ranks, failures collected. Every
    // rank sees the same jobs and the same errors; only rank 0 reports an error that ends the batch.
    mpi::use_ranks_independently();
    try {
      if (context.global.print_config) throw ConfigError("--print-config takes one job file, not a batch");
      const auto jobs = expand_jobs(job_paths_);
      refuse_shared_outputs(jobs, context);
      std::vector<JobOutcome> outcomes;
      {
        const StdoutRedirect to_stderr(2);
        outcomes = run_batch(jobs, [&](const std::filesystem::path& path) { return *run_pipeline(path, context, false); }, context);
      }
      finish_batch(outcomes, context);
    } catch (...) {
      if (mpi::rank() != 0) (void)std::freopen("/dev/null", "w", stderr);  // rank 0 says it once
      throw;
    }
  }

 private:
  /// Two jobs of a batch writing the same file would race (and the later would silently win): ConfigError
  /// naming both, before any job runs. A job that cannot be read is left to fail in its turn.
  void refuse_shared_outputs(const std::vector<std::filesystem::path>& jobs, Context& context) const {
    std::map<std::filesystem::path, std::filesystem::path> writer_of;
    for (const auto& job : jobs) {
      std::vector<std::filesystem::path> outputs;
      try {
        outputs = named_outputs(context.load_job(job));
      } catch (const std::exception&) {
        continue;
      }
      for (const auto& out : outputs) {
        const auto [it, fresh] = writer_of.emplace(out, job);
        if (!fresh && it->second != job) {
          throw ConfigError("run: the jobs " + it->second.string() + " and " + job.string() + " both write " +
                            out.string() + "; give each job its own output");
        }
      }
    }
  }

  /// Runs one pipeline and returns its report (nullopt after --print-config). `collective`: every rank runs
  /// this pipeline (one job under mpiexec), so crowd files are written by rank 0 only and the steps that write
  /// their own files run on rank 0 only (on_rank_0); otherwise (a batch: each rank its own jobs) this rank
  /// writes everything.
  std::optional<Report> run_pipeline(const std::filesystem::path& job_path, Context& context, bool collective) {
    const bool writer = !collective || mpi::rank() == 0;
    const ConfigNode job = context.load_job(job_path);
    if (context.print_config_if_asked(job.yaml())) return std::nullopt;
    const std::vector<ConfigNode> steps = job.at("steps").elements();
    if (steps.empty()) job.at("steps").fail("the pipeline has no steps");
    for (const ConfigNode& step : steps) {
      if (!step.is_map()) step.fail("a step is a mapping with at least the key 'step'");
      (void)step.keys();  // every key of a step is either a pipeline key or the step's own (checked by the step)
      if (Command* c = find(step.at("step").as_string()); !c || c == this) step.at("step").fail("unknown step '" + step.at("step").as_string() + "'");
    }
    job.finish();
    context.limit_threads();

    std::map<std::string, CrowdFile> named;   // results of named steps and crowds read from files
    std::optional<CrowdFile> last;            // the last crowd made
    std::size_t written = 0;
    for (std::size_t i = 0; i < steps.size(); ++i) {
      const ConfigNode& step = steps[i];
      const std::string which = step.at("step").as_string();
      Command* command = find(which);
      const std::string label = "step " + std::to_string(i + 1) + "/" + std::to_string(steps.size()) + " " + which;

      std::optional<StepResult> result;
      std::optional<std::filesystem::path> output;
      std::vector<const CrowdFile*> inputs;
      {
        Context::ProgressScope scope(context, static_cast<double>(i) / steps.size(), 1.0 / steps.size(), label);
        try {
          // Inputs: named steps or files, else the last crowd made.
          auto resolve = [&](const ConfigNode& ref) -> const CrowdFile* {
            const std::string key = ref.as_string();
            if (auto it = named.find(key); it != named.end()) return &it->second;
            std::error_code ec;
            if (!std::filesystem::exists(key, ec)) {
              throw IoError(ref.where() + ": '" + key + "' is neither an earlier step's name nor an existing crowd file");
            }
            return &named.emplace(key, read_crowd_file(key)).first->second;
          };
          if (auto in = step.find("input")) inputs.push_back(resolve(*in));
          if (auto ins = step.find("inputs")) {
            for (const auto& in : ins->elements()) inputs.push_back(resolve(in));
          }
          if (!step.has("input") && !step.has("inputs") && last) inputs.push_back(&*last);

          // The step's own keys: the job file's, overridden by the inline ones, without the pipeline keys. The
          // key nodes themselves are kept (force_insert), so a message about an unknown key gives its line.
          YAML::Node own(YAML::NodeType::Map);
          std::string source = job_path.string();
          if (auto j = step.find("job")) {
            const std::filesystem::path path = j->as_string();
            const ConfigNode file = ConfigNode::load_file(path);
            if (!file.is_null()) {
              if (!file.is_map()) file.fail("a step's job file must hold a mapping of keys");
              for (auto it = file.yaml().begin(); it != file.yaml().end(); ++it) own.force_insert(it->first, it->second);
            }
            source = path.string() + " + " + source;
          }
          for (auto it = step.yaml().begin(); it != step.yaml().end(); ++it) {
            const std::string key = it->first.Scalar();
            if (pipeline_keys.count(key)) continue;
            own.remove(key);
            own.force_insert(it->first, it->second);
          }
          if (auto o = step.find("output")) {
            if (command->makes_crowd()) {
              output = o->as_string();
            } else {
              own.remove("output");
              own.force_insert(YAML::Node("output"), o->yaml());
            }
          }
          const ConfigNode own_node(own, source);
          if (collective && !command->makes_crowd()) {
            result = on_rank_0([&] { return command->run_step(own_node, inputs, context); });
          } else {
            result = command->run_step(own_node, inputs, context);
          }
        } catch (const ConfigError& e) {
          throw ConfigError(label + ": " + e.what());
        } catch (const InputError& e) {
          throw InputError(label + ": " + e.what());
        } catch (const IoError& e) {
          throw IoError(label + ": " + e.what());
        } catch (const NumericalError& e) {
          throw NumericalError(label + ": " + e.what());
        }
      }
      if (!result) continue;
      if (output && writer) {
        // Credits of everything the crowd derives from are kept; the options are the whole pipeline's.
        std::vector<const Provenance*> sources;
        for (const CrowdFile* c : inputs) sources.push_back(&c->provenance);
        const Provenance made = result->crowd.provenance;
        sources.push_back(&made);
        result->crowd.provenance = context.provenance(job.yaml(), {job_path.string()}, sources);
        write_crowd_file(*output, result->crowd, result->extra);
        context.info(label + ": wrote " + output->string());
      }
      if (output) ++written;
      if (auto n = step.find("name")) named.insert_or_assign(n->as_string(), result->crowd);
      last = std::move(result->crowd);
    }
    Report r;
    r["job"] = job_path.string();
    r["steps"] = steps.size();
    r["crowd_files_written"] = written;
    return r;
  }

  Command* find(const std::string& which) const {
    for (Command* c : commands_) {
      if (c->name() == which) return c;
    }
    return nullptr;
  }

  std::vector<Command*> commands_;
  std::vector<std::filesystem::path> job_paths_;
};

}  // namespace

std::unique_ptr<Command> make_run_command(std::vector<Command*> commands) {
  return std::make_unique<RunCommand>(std::move(commands));
}

}  // namespace throng::cli
