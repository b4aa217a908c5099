#include <throng/io/collide_job.h>
#include <throng/io/scene_config.h>

#include <string>

namespace throng {
namespace {

// The scalar options, described once for reading and writing.
void bind(OptionBinder& b, CollideJob& job) {
  collide::Options& o = job.options;
  b.field("margin", o.margin, Range::non_negative());
  b.field("push_fraction", o.push_fraction, Range{0.0, 1.0, true, false});
  b.field("max_iterations", o.max_iterations, Range{1, 1e9});
  b.field("smoothing_time", o.smoothing_time, Range::non_negative());
  b.field("smoothing_weight", o.smoothing_weight, Range::positive());
  b.field("catch_up_time", o.catch_up_time, Range::non_negative());
  b.field("spread", o.spread, Range{1.0, 1e6});
  b.field("velocity_weight", o.velocity_weight, Range::non_negative());
  b.choice("obstacle_pull", o.obstacle_pull,
           {{"back", collide::ObstaclePull::back}, {"sideways", collide::ObstaclePull::sideways},
            {"nearest", collide::ObstaclePull::nearest}});
  b.choice("pair_push", o.pair_push, {{"sideways", collide::PairPush::sideways}, {"apart", collide::PairPush::apart}});
  b.choice("push_size", o.push_size, {{"full", collide::PushSize::full}, {"fraction", collide::PushSize::fraction}});
  b.field("pin_ends", o.pin_ends);
  b.field("min_feature_length", o.min_feature_length, Range::positive());
  b.field("max_displacement", o.max_displacement, Range::non_negative());
  b.field("max_speed_ratio", o.max_speed_ratio, Range::non_negative());
  b.field("max_acceleration", o.max_acceleration, Range::non_negative());
  b.field("contact_patience", o.contact_patience, Range{1, 1e9});
  b.field("stall_iterations", o.stall_iterations, Range{1, 1e9});
  b.field("allow_remaining", job.allow_remaining);
}

}  // namespace

CollideJob read_collide_job(const ConfigNode& job) {
  CollideJob out;
  if (!job.is_null() && !job.is_map()) job.fail("a collide job is a mapping of options");
  if (job.is_null()) return out;
  OptionReader reader(job);
  bind(reader, out);
  if (auto ids = job.find("fixed_agents")) {
    for (const ConfigNode& id : ids->elements()) out.options.fixed_agents.push_back(id.as_int());
  }
  out.scene = read_scene(job);
  // Distances are not wrapped across periodic boundaries: a periodic region would be repaired wrongly near
  // its edges, so it is refused rather than ignored.
  if (out.scene.region) {
    const auto& periodic = out.scene.region->periodic;
    if (periodic[0] || periodic[1] || periodic[2]) {
      job.at("region").fail("collide does not support periodic regions (pairs across a periodic boundary would "
                            "not be seen); give periodic: [false, false, false] or leave the region out");
    }
  }
  job.finish();
  return out;
}

YAML::Node effective_collide_job(const CollideJob& job) {
  YAML::Node node(YAML::NodeType::Map);
  CollideJob copy = job;
  OptionWriter writer(node);
  bind(writer, copy);
  YAML::Node ids(YAML::NodeType::Sequence);
  for (std::int64_t id : job.options.fixed_agents) ids.push_back(id);
  ids.SetStyle(YAML::EmitterStyle::Flow);
  node["fixed_agents"] = ids;
  write_scene(node, job.scene);
  return node;
}

void write_collide_data(const h5::Group& throng_parameters, const collide::Report& r) {
  const h5::Group g = throng_parameters.create_group("collide");
  std::vector<std::int64_t> history(r.history.begin(), r.history.end());
  g.write("history", history, {history.size()});
  auto count = [&](const char* name, std::size_t value) { g.set_attribute(name, static_cast<std::int64_t>(value)); };
  count("iterations", r.iterations);
  count("pair_contacts", r.pair_contacts);
  count("obstacle_contacts", r.obstacle_contacts);
  count("stuck_contacts", r.stuck_contacts);
  count("initial_pair_contacts", r.initial_pair_contacts);
  count("initial_obstacle_contacts", r.initial_obstacle_contacts);
  count("constraints", r.constraints);
  count("moved_agents", r.moved_agents);
  count("abandoned_contacts", r.abandoned_contacts);
  g.set_attribute("max_displacement", r.max_displacement);
  g.set_attribute("input_max_speed", r.input_motion.max_speed);
  g.set_attribute("output_max_speed", r.output_motion.max_speed);
  g.set_attribute("input_max_acceleration", r.input_motion.max_acceleration);
  g.set_attribute("output_max_acceleration", r.output_motion.max_acceleration);
  g.set_attribute("min_pair_gap", r.min_pair_gap);
  g.set_attribute("min_obstacle_gap", r.min_obstacle_gap);
  g.set_attribute("converged", static_cast<std::int64_t>(r.converged ? 1 : 0));
  g.set_attribute("stop_reason", r.stop_reason);
}

}  // namespace throng
