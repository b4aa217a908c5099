#include <throng/core/errors.h>
#include <throng/io/edge_edits_job.h>
#include <throng/io/stitch_job.h>

#include <algorithm>

namespace throng {
namespace {

void bind_solver(OptionBinder& b, linalg::SolverOptions& s) {
  b.choice("backend", s.backend, {"eigen", "petsc"});
  b.field("blas_threads", s.blas_threads, Range::closed(0, 1024));
  b.field("relative_tolerance", s.relative_tolerance, Range{0.0, 1.0, true, true});
  b.field("max_iterations", s.max_iterations, Range::closed(1, 1e9));
  b.field("petsc_prefix", s.petsc_prefix);
  b.field("petsc_options", s.petsc_options);
  b.field("constraint_tolerance", s.constraint_tolerance, Range{0.0, 1.0, true, true});
  b.field("schur_cache_megabytes", s.schur_cache_megabytes, Range::non_negative());
}

void bind(OptionBinder& b, stitch::Options& o) {
  b.field("blend_window", o.blend_window, Range::non_negative());
  b.field("max_blend_vertices", o.max_blend_vertices, Range::closed(0, 1e12));
  b.choice("matching", o.matching, {{"world", stitch::Matching::world}, {"centred", stitch::Matching::centred}});
  b.choice("alignment", o.alignment,
           {{"rigid", stitch::Alignment::rigid}, {"translation", stitch::Alignment::translation}, {"none", stitch::Alignment::none}});
  b.field("sample_step", o.sample_step, Range::closed(1, 1e9));
  b.section("formation", [&](OptionBinder& f) { f.field("max_edge_length", o.formation.max_edge_length, Range::non_negative()); });
  b.section("weights", [&](OptionBinder& w) {
    w.field("alpha", o.weights.alpha, Range::non_negative());
    w.field("beta", o.weights.beta, Range::non_negative());
    w.field("alpha_prime", o.weights.alpha_prime, Range::non_negative());
    w.field("beta_prime", o.weights.beta_prime, Range::non_negative());
  });
  b.field("scale_compensation", o.weights.scale_compensation);
  b.section("features", [&](OptionBinder& f) {
    f.field("min_length", o.features.min_length, Range::positive());
    f.field("degenerate_ratio", o.features.degenerate_ratio, Range{0.0, 1.0, false, true});
  });
  b.section("solver", [&](OptionBinder& s) { bind_solver(s, o.solver); });
  b.section("guard", [&](OptionBinder& g) {
    g.field("enabled", o.guard.enabled);
    g.field("max_speed_ratio", o.guard.max_speed_ratio, Range::positive());
    g.field("max_acceleration", o.guard.max_acceleration, Range::positive());
    g.field("ramp_time", o.guard.ramp_time, Range::positive());
    g.field("smoothing_time", o.guard.smoothing_time, Range::positive());
    g.field("max_window_time", o.guard.max_window_time, Range::positive());
  });
}

// Maps [0, 1] of one joint into its share of the whole.
class JointProgress final : public Progress {
 public:
  JointProgress(Progress& whole, std::size_t joint, std::size_t joints) : whole_(whole), joint_(joint), joints_(joints) {}
  void update(double fraction, std::string_view stage) override {
    whole_.update((static_cast<double>(joint_) + fraction) / static_cast<double>(joints_),
                  "stitch joint " + std::to_string(joint_ + 1) + "/" + std::to_string(joints_) + ": " + std::string(stage));
  }

 private:
  Progress& whole_;
  std::size_t joint_, joints_;
};

}  // namespace

StitchJob read_stitch_job(const ConfigNode& job) {
  StitchJob s;
  OptionReader reader(job);
  bind(reader, s.options);
  read_edge_edits(job, s.options.formation, "the stitched output");
  job.finish();
  try {
    stitch::validate(s.options);
  } catch (const Error& e) {
    job.fail(e.what());
  }
  return s;
}

YAML::Node effective_stitch_job(const StitchJob& job) {
  YAML::Node out(YAML::NodeType::Map);
  stitch::Options options = job.options;
  OptionWriter writer(out);
  bind(writer, options);
  write_edge_edits(out, options.formation);
  return out;
}

StitchedCrowds stitch_crowds(const std::vector<const CrowdFile*>& inputs, const StitchJob& job, Progress& progress) {
  if (inputs.size() < 2) throw ConfigError("stitch needs at least two clips, got " + std::to_string(inputs.size()));
  StitchedCrowds s;
  s.crowd.motion = inputs[0]->motion;
  s.crowd.scene = inputs[0]->scene;
  s.crowd.provenance.credits = inputs[0]->provenance.credits;
  const std::size_t joints = inputs.size() - 1;
  for (std::size_t k = 1; k < inputs.size(); ++k) {
    JointProgress joint(progress, k - 1, joints);
    stitch::Result r;
    const std::string which = "joint " + std::to_string(k) + " (inputs 1.." + std::to_string(k) + " then input " + std::to_string(k + 1) + "): ";
    try {
      r = stitch::stitch_clips(s.crowd.motion, inputs[k]->motion, job.options, &joint);
    } catch (const InputError& e) {
      throw InputError(which + e.what());
    } catch (const NumericalError& e) {
      throw NumericalError(which + e.what());
    }
    s.joint_frames.push_back(r.report.frames_first - 1);
    s.joint_ids.push_back(r.crowd.ids);
    s.crowd.motion = std::move(r.crowd);
    r.crowd = CrowdMotion{};
    s.joints.push_back(std::move(r));
    for (const std::string& c : inputs[k]->provenance.credits) {
      if (std::find(s.crowd.provenance.credits.begin(), s.crowd.provenance.credits.end(), c) == s.crowd.provenance.credits.end()) {
        s.crowd.provenance.credits.push_back(c);
      }
    }
  }
  return s;
}

void write_stitch_data(const h5::Group& throng_parameters, const StitchedCrowds& stitched) {
  const h5::Group g = throng_parameters.create_group("stitch");
  for (std::size_t k = 0; k < stitched.joints.size(); ++k) {
    const stitch::Result& r = stitched.joints[k];
    const h5::Group j = g.create_group("joint_" + std::to_string(k + 1));
    // The joint's agents are the clip-so-far's, with its ids (a later joint may leave some out).
    const std::vector<std::int64_t>& first_ids = stitched.joint_ids[k];
    j.write("first_ids", first_ids, {first_ids.size()});
    j.write("second_ids", r.second_ids, {r.second_ids.size()});
    j.set_attribute("frame", static_cast<std::int64_t>(stitched.joint_frames[k]));
    j.set_attribute("rotation", r.report.rotation);
    j.write("translation", std::vector<double>{r.report.translation.x(), r.report.translation.y()}, {2});
    j.set_attribute("gap_rms", r.report.gap_rms);
    j.set_attribute("gap_max", r.report.gap_max);
    j.write("window", std::vector<std::int64_t>{static_cast<std::int64_t>(r.report.window_first), static_cast<std::int64_t>(r.report.window_second)}, {2});
    j.write("window_seconds", std::vector<double>{r.report.window_first_s, r.report.window_second_s}, {2});
    j.set_attribute("window_limited", static_cast<std::int64_t>(r.report.window_limited ? 1 : 0));
    j.set_attribute("matching_distance", r.report.matching_distance);
  }
}

}  // namespace throng
