// throng run JOB.yaml: a pipeline of steps, each one of the subcommands, passing crowds in memory and writing
// files only where a step asks.
//
//   steps:
//     - step: import                      # the command; its keys follow, as in its job file
//       dataset: ../shared/data/real/eth
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
// Batch: `throng run A.yaml B.yaml jobs/` runs every job (folders: their *.yaml, *.yml) spread over the MPI
// ranks; a failing job does not stop the others; a summary lists them (drivers/batch.h).
#include "../batch.h"
#include "factories.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>

#include <map>
#include <set>

namespace throng::cli {
namespace {

const std::set<std::string> pipeline_keys{"step", "name", "input", "inputs", "job", "output"};

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
      if (auto report = run_pipeline(job_paths_.front(), context)) context.print(*report);
      return;
    }
    // A batch (drivers/batch.h): several jobs or folders, spread over the MPI ranks, failures collected.
    if (context.global.print_config) throw ConfigError("--print-config takes one job file, not a batch");
    const auto jobs = expand_jobs(job_paths_);
    finish_batch(run_batch(jobs, [&](const std::filesystem::path& path) { return *run_pipeline(path, context); }, context), context);
  }

 private:
  /// Runs one pipeline and returns its report (nullopt after --print-config).
  std::optional<Report> run_pipeline(const std::filesystem::path& job_path, Context& context) {
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

      // Inputs: named steps or files, else the last crowd made.
      std::vector<const CrowdFile*> inputs;
      auto resolve = [&](const ConfigNode& ref) -> const CrowdFile* {
        const std::string key = ref.as_string();
        if (auto it = named.find(key); it != named.end()) return &it->second;
        std::error_code ec;
        if (!std::filesystem::exists(key, ec)) ref.fail("'" + key + "' is neither an earlier step's name nor a crowd file");
        return &named.emplace(key, read_crowd_file(key)).first->second;
      };
      if (auto in = step.find("input")) inputs.push_back(resolve(*in));
      if (auto ins = step.find("inputs")) {
        for (const auto& in : ins->elements()) inputs.push_back(resolve(in));
      }
      if (!step.has("input") && !step.has("inputs") && last) inputs.push_back(&*last);

      // The step's own keys: the job file's, overridden by the inline ones, without the pipeline keys.
      YAML::Node own(YAML::NodeType::Map);
      std::string source = job_path.string();
      if (auto j = step.find("job")) {
        const std::filesystem::path path = j->as_string();
        const ConfigNode file = ConfigNode::load_file(path);
        if (!file.is_null()) {
          if (!file.is_map()) file.fail("a step's job file must hold a mapping of keys");
          for (auto it = file.yaml().begin(); it != file.yaml().end(); ++it) own[it->first.Scalar()] = it->second;
        }
        source = path.string() + " + " + source;
      }
      for (const auto& key : step.keys()) {
        if (!pipeline_keys.count(key)) own[key] = step.yaml()[key];
      }
      std::optional<std::filesystem::path> output;
      if (auto o = step.find("output")) {
        if (command->makes_crowd()) output = o->as_string();
        else own["output"] = o->yaml();
      }
      const ConfigNode own_node(own, source);

      std::optional<StepResult> result;
      {
        Context::ProgressScope scope(context, static_cast<double>(i) / steps.size(), 1.0 / steps.size(), label);
        try {
          result = command->run_step(own_node, inputs, context);
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
      if (output) {
        // Credits of everything the crowd derives from are kept; the options are the whole pipeline's.
        std::vector<const Provenance*> sources;
        for (const CrowdFile* c : inputs) sources.push_back(&c->provenance);
        const Provenance made = result->crowd.provenance;
        sources.push_back(&made);
        result->crowd.provenance = context.provenance(job.yaml(), {job_path.string()}, sources);
        write_crowd_file(*output, result->crowd, result->extra);
        ++written;
        context.info(label + ": wrote " + output->string());
      }
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
