// throng check-tiling TILING.h5: the independent checker of a file written by `throng tile` (solver/tiling/check.h),
// listing every failure; exit 5 when the tiling is not perfect.
#include "../option_flags.h"
#include "factories.h"

#include <throng/core/errors.h>
#include <throng/io/data_options.h>
#include <throng/io/tiling_data.h>

namespace throng::cli {
namespace {

class CheckTilingCommand final : public Command {
 public:
  std::string name() const override { return "check-tiling"; }
  std::string summary() const override {
    return "Check a tiling independently: no dangling end, no overlap, deformation within limits, seams matched";
  }

  void setup(CLI::App& app) override {
    // No ExistingFile check: a missing file is an I/O error (exit 4) from the reader, as for every other input.
    app.add_option("tiling", path_, "Tiling file written by `throng tile` (.h5)")->required();
    flags_.add(app, static_cast<void (*)(OptionBinder&, CheckTilingJob&)>(describe));
  }

  void run(Context& context) override {
    CheckTilingJob job;
    const YAML::Node effective = context.options(flags_.overrides(), name(), describe, job, {{"tiling", path_.string()}});
    if (context.print_config_if_asked(effective)) return;
    context.limit_threads();
    const TilingData data = read_tiling_data(path_);
    const tiling::CheckReport c = tiling::check_tiling(data.library, data.tiling, data.environment, data.check, job.max_failures);
    Report r;
    r["tiling"] = path_.string();
    r["perfect"] = c.perfect();
    r["instances"] = c.instances;
    r["connections"] = c.connections;
    r["character_ends"] = c.character_ends;
    r["pairs_tested"] = c.pairs_tested;
    Report totals = Report::object();
    for (std::size_t k = 0; k < tiling::failure_kind_count; ++k) {
      totals[tiling::to_string(static_cast<tiling::FailureKind>(k))] = c.totals[k];
    }
    r["failures"] = totals;
    Report listed = Report::array();
    for (const tiling::Failure& f : c.failures) listed.push_back(std::string(tiling::to_string(f.kind)) + ": " + f.message);
    r["listed"] = listed;
    context.print(r);
    if (!c.perfect()) {
      throw NumericalError("check-tiling: " + std::to_string(c.total()) + " failure(s) in " + path_.string() + " (listed above)");
    }
  }

 private:
  std::filesystem::path path_;
  OptionFlags flags_;
};

}  // namespace

std::unique_ptr<Command> make_check_tiling_command() { return std::make_unique<CheckTilingCommand>(); }

}  // namespace throng::cli
