// throng edit CROWD.h5 --job EDIT.yaml -o OUT.h5 [--backend eigen|petsc]: deform a group motion by pinning and
// dragging agents while keeping its formations and trajectories (group motion editing, solver/edit/runner.h).
// The job format is in io/edit/include/throng/io/edit_job.h; docs/commands/edit.md is the README section.
// Output: the whole input crowd with the edited clip put back (solver/edit output.h), or only the clip with
// --clip-only (job key clip_only).
// With local.parts > 0 or auto (or --local-parts) the edit is local (solver/edit local_edit.h): only the parts it
// reaches are solved; the report gives the step across the region's edge in time and a warning says when it
// is a jump (edit::BoundaryStep); docs/commands/scale.md describes it.
//
// Under mpiexec every rank reads the input and builds the problem; the petsc backend shares the solves between
// the ranks; rank 0 writes the output and prints the report.
//
// With --session (and no -o) the command is a long-lived edit: requests as JSON lines on stdin, one answer line
// each on stdout, the editor and its factorisation kept between them (edit_session.h).
#include "../method_command.h"
#include "edit_session.h"
#include "factories.h"

#include <throng/io/edit_job.h>

#include <iostream>

namespace throng::cli {
namespace {

class EditCommand final : public MethodCommand<edit::Job> {
 public:
  using MethodCommand::MethodCommand;

  void setup(CLI::App& app) override {
    MethodCommand::setup(app);
    // -o is required for a one-shot edit (run() says so); a session writes where each request says.
    app.get_option("--output")->required(false);
    app.add_flag("--session", session_,
                 "Answer edit requests (JSON lines on stdin) until end of input, keeping the factorisation; no -o")
        ->excludes("--output");
  }

  void run(Context& context) override {
    if (!session_) {
      if (output_.empty()) throw ConfigError("--output is required (or --session: requests on stdin)");
      MethodCommand::run(context);
      return;
    }
    const ConfigNode node = context.job(job_path_, flags_.overrides(), spec_.name);
    if (context.global.print_config) {  // the base job's effective options, as a one-shot edit prints them
      edit::Job job;
      read_job(node, job);
      (void)context.print_config_if_asked(effective_job(job));
      return;
    }
    run_edit_session(context, inputs_.at(0), job_path_, node, std::cin, std::cout);
  }

 private:
  bool session_ = false;
};

}  // namespace

std::unique_ptr<Command> make_edit_command() {
  return std::make_unique<EditCommand>(MethodSpec{
      .name = "edit",
      .summary = "Deform a group motion by pinning and dragging agents, keeping formations and trajectories",
      .job = JobArgument::required, .job_help = "Edit job (.yaml): clip, pins, drags, constraints, weights, solver",
      .inputs = {.min = 1, .max = 1, .help = "Crowd file to edit (.h5)", .count_text = "edit takes one crowd"},
      .output_help = "Crowd file to write (.h5): the input crowd with the clip edited (not with --session)"});
}

}  // namespace throng::cli
