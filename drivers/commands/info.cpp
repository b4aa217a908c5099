// throng info CROWD.h5: what a crowd file holds — agents, frames, duration, extent, obstacles, provenance.
#include "factories.h"

#include <throng/io/crowd_file.h>

#include <cmath>
#include <limits>
#include <set>

namespace throng::cli {
namespace {

class InfoCommand final : public Command {
 public:
  std::string name() const override { return "info"; }
  std::string summary() const override { return "Describe a crowd file: agents, frames, duration, extent, obstacles, provenance"; }

  void setup(CLI::App& app) override { app.add_option("crowd", input_, "Crowd file (.h5)")->required(); }

  void run(Context& context) override {
    context.job({}, {}, name()).finish();  // info has no options: a --set is an unknown key
    YAML::Node effective(YAML::NodeType::Map);
    effective["crowd"] = input_.string();
    if (context.print_config_if_asked(effective)) return;
    const CrowdFile file = read_crowd_file(input_);
    context.print(describe(file, input_.string()));
  }

  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs, Context& context) override {
    step.finish();
    if (inputs.size() != 1) step.fail("info takes one crowd, found " + std::to_string(inputs.size()));
    context.print(describe(*inputs.front(), "(pipeline)"));
    return std::nullopt;
  }
  bool makes_crowd() const override { return false; }

 private:
  static Report describe(const CrowdFile& file, const std::string& name) {
    const CrowdMotion& m = file.motion;
    Report r;
    r["file"] = name;
    r["agents"] = m.agent_count();
    r["frames"] = m.frame_count();
    if (m.frame_count() > 0) {
      r["start_s"] = m.times.front();
      r["end_s"] = m.times.back();
      r["duration_s"] = m.times.back() - m.times.front();
      if (m.frame_count() > 1) {
        double min_dt = std::numeric_limits<double>::infinity(), max_dt = 0;
        for (std::size_t t = 1; t < m.frame_count(); ++t) {
          min_dt = std::min(min_dt, m.times[t] - m.times[t - 1]);
          max_dt = std::max(max_dt, m.times[t] - m.times[t - 1]);
        }
        if (max_dt - min_dt <= 1e-9 * max_dt) r["frame_rate_hz"] = 1.0 / min_dt;
        else r["frame_interval_s"] = {min_dt, max_dt};
      }
    }
    std::array<double, 3> lo{}, hi{};
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
    std::size_t present = 0;
    for (std::size_t i = 0; i < m.positions.size(); i += 3) {
      if (!std::isfinite(m.positions[i])) continue;
      ++present;
      for (std::size_t k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], m.positions[i + k]);
        hi[k] = std::max(hi[k], m.positions[i + k]);
      }
    }
    if (present > 0) r["extent_m"] = {{"min", lo}, {"max", hi}};
    r["present_samples"] = present;
    std::set<std::int32_t> species(m.species.begin(), m.species.end());
    r["species"] = species.size();
    std::size_t circles = 0, polygons = 0, walls = 0, moving = 0;
    for (const Obstacle& o : file.scene.obstacles) {
      circles += std::holds_alternative<Circle>(o.shape);
      polygons += std::holds_alternative<ConvexPolygon>(o.shape);
      walls += std::holds_alternative<Wall>(o.shape);
      moving += o.is_moving();
    }
    r["obstacles"] = {{"circles", circles}, {"polygons", polygons}, {"walls", walls}, {"moving", moving}};
    if (const auto& g = file.scene.region) {
      r["region"] = {{"min", {g->min.x(), g->min.y()}}, {"max", {g->max.x(), g->max.y()}}, {"time", {g->t0, g->t1}},
                     {"periodic", {g->periodic[0], g->periodic[1], g->periodic[2]}}};
    }
    if (!file.formation_edges.empty()) r["formation_edges"] = file.formation_edges.size();
    const Provenance& p = file.provenance;
    Report prov;
    prov["program_version"] = p.program_version;
    prov["command_line"] = p.command_line;
    prov["seed"] = p.seed;
    prov["inputs"] = p.inputs;
    if (!p.credits.empty()) prov["credits"] = p.credits;
    r["provenance"] = prov;
    return r;
  }

  std::filesystem::path input_;
};

}  // namespace

std::unique_ptr<Command> make_info_command() { return std::make_unique<InfoCommand>(); }

}  // namespace throng::cli
