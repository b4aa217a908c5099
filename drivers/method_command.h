// One command class for every method (sketch, edit, formation, collide, split, merge, transform, stitch,
// timewarp, tile): a command file gives what is particular to its method — a MethodSpec (names, arguments, help
// texts) and, where needed, Hooks — and MethodCommand does the rest the same way for all of them: the arguments,
// the job (file, flags, --set), the flags from the method's schema, --print-config (which reads no data), the
// inputs, the ranks, the output, the provenance, the report (stdout and the output's record, from one list) and
// the exit code when the method falls short; and the same again as a step of `throng run`.
//
//   std::unique_ptr<Command> make_collide_command() {
//     return std::make_unique<MethodCommand<collide::Job>>(MethodSpec{.name = "collide", ...},
//         MethodCommand<collide::Job>::Hooks{.fails = [](const collide::Job& job, bool) { return !job.allow_remaining; }});
//   }
//
// Everything else is found by the Job's and the Run's types (argument-dependent lookup), so a method says it once
// where it belongs: `describe(OptionBinder&, Job&)` (its schema) and `run(inputs, job, progress, communicator)`
// (whose result, the Run, holds the crowd made, the report, warnings and a shortfall) and
// `describe(ReportWriter&, const Run&)` (solver/<method>/runner.h), `read_job`, `effective_job` and `write_data`
// (io/<method>_job.h, defaults in io/job_file.h). A job with `options.seed` gets --seed.
#pragma once

#include "command.h"
#include "input_crowds.h"
#include "option_flags.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/job_file.h>
#include <throng/io/report_record.h>

#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace throng::cli {

/// Where a method's job comes from on the command line.
enum class JobArgument {
  positional,  ///< `throng sketch JOB.yaml -o OUT.h5`
  required,    ///< `--job JOB.yaml`, required
  optional,    ///< `--job JOB.yaml`, optional: flags and --set alone may make the job
};

inline constexpr std::size_t any_number = std::numeric_limits<std::size_t>::max();

/// The crowd files a method reads.
struct InputSpec {
  std::size_t min = 0, max = 0;        ///< how many (max any_number: no limit; 0: the method starts a crowd)
  const char* name = "crowd";          ///< the positional argument
  const char* help = "";
  const char* second_flag = nullptr;   ///< a second input given by a flag (timewarp's --reference)
  const char* second_help = "";
  const char* count_text = "";         ///< a step with another count fails: "<count_text>, found N"
  bool on_command_line = true;         ///< false: only a step's inputs (formation's from_crowd without a file)
};

/// What is particular to a method's command.
struct MethodSpec {
  const char* name;             ///< the subcommand, the step's name, the prefix of its messages
  const char* summary;          ///< one line for `throng --help`
  JobArgument job;
  const char* job_help;
  InputSpec inputs;
  const char* output_help;
  const char* record = nullptr; ///< the output's record /parameters/throng/<record> (default: the name)
  const char* made = "crowd";   ///< what a shortfall's message says was written ("the crowd was written to ...")
};

/// What a method's run gets besides its inputs and its job, and what it tells the command.
struct MethodRun {
  Context& context;
  std::string where;                      ///< the job, for messages ("job.yaml", "--set ...")
  bool second_output = false;             ///< the command writes the method's second output too (split --other)
  std::filesystem::path output;           ///< the command's output (empty in a step): a file the job names must differ
  std::vector<std::string> files_read;    ///< files the method read itself (named in the job): provenance
  std::vector<std::string> credits;       ///< credits of the data the method read itself
  [[nodiscard]] Progress& progress() { return context.progress(); }
  [[nodiscard]] const Communicator& communicator() const { return context.communicator(); }
};

namespace detail {

/// The method's runner, found by the job's type (outside MethodCommand, whose own `run` would hide it).
template <class Job>
auto runner(const Crowds& inputs, const Job& job, MethodRun& r) {
  return run(inputs, job, r.progress(), r.communicator());
}

}  // namespace detail

template <class Job, class Run = decltype(detail::runner(std::declval<const Crowds&>(), std::declval<const Job&>(),
                                                          std::declval<MethodRun&>()))>
class MethodCommand : public Command {
 public:
  /// What a method does besides the defaults.
  struct Hooks {
    /// Work before the runner, which it calls itself (formation takes its keyframes from a crowd, tile imports
    /// its recorded crowd). Empty: the method's runner.
    std::function<Run(const Crowds&, Job&, MethodRun&)> run;
    /// Whether a shortfall fails (exit 5) or warns. Empty: a command fails, a step warns.
    std::function<bool(const Job&, bool step)> fails;
  };

  explicit MethodCommand(MethodSpec spec, Hooks hooks = {}) : spec_(spec), hooks_(std::move(hooks)) {}

  std::string name() const override { return spec_.name; }
  std::string summary() const override { return spec_.summary; }
  bool reads_crowds() const override { return spec_.inputs.max > 0; }

  void setup(CLI::App& app) override {
    const MethodSpec& s = spec_;
    if (s.job == JobArgument::positional) app.add_option("job", job_path_, s.job_help)->required();
    if (s.inputs.max > 0 && s.inputs.on_command_line) {
      const std::size_t positional = s.inputs.second_flag ? 1 : s.inputs.max;
      app.add_option(s.inputs.name, inputs_, s.inputs.help)
          ->required()
          ->expected(static_cast<int>(std::min(s.inputs.min, positional)), positional == any_number ? -1 : static_cast<int>(positional));
      if (s.inputs.second_flag) app.add_option(s.inputs.second_flag, second_, s.inputs.second_help)->required();
    }
    app.add_option("-o,--output", output_, s.output_help)->required();
    if (s.job != JobArgument::positional) {
      auto* job = app.add_option("--job", job_path_, s.job_help);
      if (s.job == JobArgument::required) job->required();
    }
    more_arguments(app);
    flags_.add(app, [](OptionBinder& b) {
      Job defaults{};
      describe(b, defaults);
    });
  }

  void run(Context& context) override {
    const ConfigNode node = context.job(job_path_, flags_.overrides(), spec_.name);
    Job job{};
    read_job(node, job);
    const YAML::Node effective = effective_job(job);
    if (context.print_config_if_asked(effective)) return;
    std::vector<std::filesystem::path> inputs = inputs_;
    if (!second_.empty()) inputs.push_back(second_);
    for (const auto& in : inputs) check_distinct(in, output_);
    if (!job_path_.empty()) check_distinct(job_path_, output_);
    check_outputs(inputs);
    context.limit_threads();
    (void)AtomicOutput(output_);  // a missing or read-only output folder fails now (exit 4), not after the work

    const InputCrowds in = read_input_crowds(inputs, job_path_);
    MethodRun r{context, job_path_.empty() ? std::string(spec_.name) : job_path_.string(), wants_second_output(), output_, {}, {}};
    auto run = std::make_shared<Run>(run_method(in.crowds, job, r));
    if (context.writer()) {  // one file and one report, from rank 0
      tell(*run, context);
      auto fields = std::make_shared<ReportFields>(report_fields(*run));
      CrowdFile out;
      static_cast<Crowd&>(out) = std::move(run->crowd);
      std::vector<std::string> names = in.names, credits = in.credits;
      names.insert(names.end(), r.files_read.begin(), r.files_read.end());
      credits.insert(credits.end(), r.credits.begin(), r.credits.end());
      out.provenance = context.provenance(effective, names, credits);
      write(out, record_writer(run, fields), *run, context);
      Report report;
      report["output"] = output_.string();
      ReportJson json(report);
      fields->replay(json);
      amend(report, *run);
      if constexpr (requires { job.options.seed; }) report["seed"] = context.global.seed;
      context.print(report);
    }
    if (run->shortfall.empty()) return;
    if (fails(job, false)) {
      throw NumericalError(std::string(spec_.name) + ": " + run->shortfall + "; the " + spec_.made + " was written to " +
                           output_.string());
    }
    if (context.writer()) context.warn(std::string(spec_.name) + ": " + run->shortfall);
  }

  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs,
                                     Context& context) override {
    Job job{};
    read_job(step, job);
    const InputSpec& s = spec_.inputs;
    if (inputs.size() < s.min || inputs.size() > s.max) step.fail(std::string(s.count_text) + ", found " + std::to_string(inputs.size()));
    MethodRun r{context, step.where(), false, {}, {}, {}};
    auto run = std::make_shared<Run>(run_method(s.max > 0 ? Crowds(inputs.begin(), inputs.end()) : Crowds{}, job, r));
    tell(*run, context);
    auto fields = std::make_shared<ReportFields>(report_fields(*run));
    StepResult result;
    static_cast<Crowd&>(result.crowd) = std::move(run->crowd);
    if (s.max > 0 && s.on_command_line) {  // a method that always reads its inputs derives from them
      for (const CrowdFile* c : inputs) result.crowd.provenance.add_credits(c->provenance.credits);
    }
    result.crowd.provenance.add_credits(r.credits);
    result.extra = record_writer(run, fields);
    Report report;
    ReportJson json(report);
    fields->replay(json);
    context.info(std::string(spec_.name) + ": " + report.dump());
    if (!run->shortfall.empty()) {
      if (fails(job, true)) throw NumericalError(std::string(spec_.name) + ": " + run->shortfall);
      context.warn(std::string(spec_.name) + ": " + run->shortfall);
    }
    return result;
  }

 protected:
  /// More arguments of one command (split's --other).
  virtual void more_arguments(CLI::App&) {}
  /// More outputs to check before the work (they must exist as folders and differ from the inputs).
  virtual void check_outputs(const std::vector<std::filesystem::path>&) {}
  [[nodiscard]] virtual bool wants_second_output() const { return false; }
  /// Adds to the printed report what the command did besides the method's output (split's other part).
  virtual void amend(Report&, const Run&) {}
  /// Writes the output (rank 0) with its record.
  virtual void write(const CrowdFile& out, const ExtraWriter& record, const Run&, Context& context) {
    write_crowd_file(output_, out, record, context.global.storage);
  }

  /// Writes a method's record: its data, then its report's fields, into /parameters/throng/<record>.
  ExtraWriter record_writer(std::shared_ptr<const Run> run, std::shared_ptr<const ReportFields> fields) const {
    return [run = std::move(run), fields = std::move(fields), spec = spec_](const h5::Group& parameters) {
      const h5::Group g = parameters.create_group(spec.record ? spec.record : spec.name);
      write_data(g, *run);
      ReportRecord record(g);
      fields->replay(record);
    };
  }

  MethodSpec spec_;
  Hooks hooks_;
  std::vector<std::filesystem::path> inputs_;
  std::filesystem::path second_, output_, job_path_;
  OptionFlags flags_;

 private:
  Run run_method(const Crowds& inputs, Job& job, MethodRun& r) const {
    if constexpr (requires { job.options.seed; }) job.options.seed = r.context.global.seed;
    if (hooks_.run) return hooks_.run(inputs, job, r);
    if constexpr (std::is_constructible_v<Run, decltype(detail::runner(inputs, job, r))>) {
      return Run(detail::runner(inputs, job, r));
    } else {
      throw std::logic_error(std::string(spec_.name) + ": a command whose Run is not its runner's needs Hooks::run");
    }
  }
  bool fails(const Job& job, bool step) const { return hooks_.fails ? hooks_.fails(job, step) : !step; }
  /// A run's warnings, and its notes (information) when it has any.
  void tell(const Run& run, Context& context) const {
    for (const std::string& w : run.warnings) context.warn(std::string(spec_.name) + ": " + w);
    if constexpr (requires { run.notes; }) {
      for (const std::string& n : run.notes) context.info(std::string(spec_.name) + ": " + n);
    }
  }
};

}  // namespace throng::cli
