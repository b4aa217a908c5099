// The edit job file: every key read, effective options round-trip, malformed entries are ConfigErrors with the line.
#include <throng/core/errors.h>
#include <throng/io/edit_job.h>

#include <catch2/catch.hpp>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

const char* full_job = R"(
clip_only: true
guard: {enabled: false, max_speed_ratio: 1.5, max_acceleration: 4, ramp_time: 2, smoothing_time: 0.25, max_window_time: 1}
clip: {first_frame: 5, last_frame: end, agents: [100, 101, 102], sample_step: 3}
formation:
  max_edge_length: 4.5
  edits:
    - {add: [100, 102], frames: [5, 20]}
    - {remove: [100, 101]}
weights: {alpha: 2, beta: 0.5, alpha_prime: 3, beta_prime: 0.25}
scale_compensation: false
features: {min_length: 0.1, degenerate_ratio: 0.01}
solver: {backend: petsc, relative_tolerance: 1e-10, petsc_options: "-pc_type hypre"}
pins:
  - {agent: 100, frame: 10}
  - {agent: 101, frame: -1, position: [3, 4]}
drags:
  - {agents: [100], frames: [5, 8], offset: [1, 2], rotation: 0.5, pivot: [0, 0]}
  - {frames: [-10, end]}
constraints:
  - {type: relative_position, agent: 100, other: 101, frames: [6, 9], offset: [1, 0]}
  - {type: velocity, agent: 102, frame: 12, velocity: [1.5, 0]}
  - {type: on_line, agent: 100, point: [0, 1], direction: [1, 1]}
)";

edit::Job parse(const std::string& text) { return read_job<edit::Job>(ConfigNode::parse(text, "edit.yaml")); }

}  // namespace

TEST_CASE("every key of a full job is read") {
  const edit::Job job = parse(full_job);
  CHECK(job.clip_only);
  CHECK_FALSE(parse("{}").clip_only);  // default: the whole crowd with the clip put back
  CHECK_FALSE(job.guard.enabled);
  CHECK(parse("{}").guard.enabled);  // default: the guard on
  CHECK((job.guard.max_speed_ratio == 1.5 && job.guard.max_acceleration == 4 && job.guard.ramp_time == 2 &&
         job.guard.smoothing_time == 0.25 && job.guard.max_window_time == 1));
  const edit::Options& o = job.options;
  CHECK(o.clip.first_frame == 5);
  CHECK(o.clip.last_frame == std::numeric_limits<std::size_t>::max());
  CHECK(o.clip.agents == std::vector<std::int64_t>{100, 101, 102});
  CHECK(o.clip.sample_step == 3);
  CHECK(o.formation.max_edge_length == 4.5);
  REQUIRE(o.formation.edits.size() == 2);
  CHECK(o.formation.edits[0].add);
  CHECK(o.formation.edits[0].last_frame == 20);
  CHECK_FALSE(o.formation.edits[1].add);
  CHECK((o.alpha == 2 && o.beta == 0.5 && o.alpha_prime == 3 && o.beta_prime == 0.25));
  CHECK_FALSE(o.scale_compensation);
  CHECK(o.features.min_length == 0.1);
  CHECK(o.solver.backend == "petsc");
  CHECK(o.solver.relative_tolerance == 1e-10);
  CHECK(o.solver.petsc_options == "-pc_type hypre");
  const edit::Request& r = job.request;
  REQUIRE(r.pins.size() == 2);
  CHECK(r.pins[1].frame == -1);
  CHECK(*r.pins[1].position == Eigen::Vector2d(3, 4));
  REQUIRE(r.drags.size() == 2);
  CHECK(r.drags[0].rotation == 0.5);
  CHECK(r.drags[1].selection.first_frame == -10);
  CHECK(r.drags[1].selection.last_frame == -1);
  REQUIRE(r.constraints.size() == 3);
  CHECK(std::get<edit::Velocity>(r.constraints[1]).velocity == Eigen::Vector2d(1.5, 0));
  CHECK(std::get<edit::OnLine>(r.constraints[2]).direction == Eigen::Vector2d(1, 1));
}

TEST_CASE("the effective job reads back to the same job") {
  const edit::Job job = parse(full_job);
  const std::string text = to_yaml_text(effective_job(job));
  const edit::Job again = parse(text);
  CHECK(to_yaml_text(effective_job(again)) == text);
  CHECK_THAT(text, Contains("alpha: 2") && Contains("petsc_options: -pc_type hypre") && Contains("frame: -1"));
  CHECK(again.request.constraints.size() == 3);
  CHECK(again.options.formation.edits.size() == 2);
  // Defaults are written out in full.
  const std::string defaults = to_yaml_text(effective_job(parse("{}")));
  CHECK_THAT(defaults, Contains("sample_step: 1") && Contains("backend: eigen") && Contains("last_frame: end") &&
                          Contains("max_speed_ratio: 1.25"));
}

TEST_CASE("malformed entries are configuration errors naming the line") {
  CHECK_THROWS_WITH(parse("weights: {alpha: 1, gamma: 2}\n"), Contains("gamma"));
  CHECK_THROWS_WITH(parse("guard: {max_speed_ratio: 0}\n"), Contains("guard.max_speed_ratio"));
  CHECK_THROWS_WITH(parse("constraints:\n  - {type: speed, agent: 1}\n"), Contains("edit.yaml:2") && Contains("unknown constraint type 'speed'"));
  CHECK_THROWS_WITH(parse("drags:\n  - {frames: [1, 2, 3]}\n"), Contains("expected [first, last]"));
  CHECK_THROWS_WITH(parse("pins:\n  - {agent: 1}\n"), Contains("frame"));
  CHECK_THROWS_WITH(parse("clip: {first_frame: -2}\n"), Contains("negative"));
  CHECK_THROWS_WITH(parse("clip: {first_frame: 5, last_frame: 5}\n"), Contains("must be after first_frame"));
  CHECK_THROWS_WITH(parse("formation:\n  edits:\n    - {add: [1, 2], remove: [1, 2]}\n"), Contains("exactly one of add"));
  CHECK_THROWS_WITH(parse("formation:\n  edits:\n    - {add: [3, 3]}\n"), Contains("edit.yaml:3") && Contains("two different agents"));
  CHECK_THROWS_WITH(parse("formation:\n  edits:\n    - {add: [1, 2], frames: [-1, 4]}\n"), Contains("indices into the input"));
  CHECK_THROWS_WITH(parse("formation:\n  edits:\n    - {remove: [1, 2], frames: [9, 4]}\n"), Contains("after the last"));
  CHECK_THROWS_WITH(parse("solver: {backend: cuda}\n"), Contains("cuda"));
  CHECK_THROWS_WITH(parse("weights: {beta: -1}\n"), Contains("out of range"));
  CHECK_THROWS_AS(parse("drags:\n  - {offset: [1]}\n"), ConfigError);
}

TEST_CASE("the local block: parts as a count or auto, vertices_per_part, and bad values naming the key") {
  const edit::Job by_size = parse("local: {parts: auto, vertices_per_part: 2000, halo: 2}\n");
  CHECK(by_size.options.local.parts == edit::LocalOptions::by_size);
  CHECK(by_size.options.local.vertices_per_part == 2000);
  CHECK(by_size.options.local.halo == 2);
  const std::string text = to_yaml_text(effective_job(by_size));
  CHECK_THAT(text, Contains("parts: auto") && Contains("vertices_per_part: 2000") && Contains("halo: 2"));
  CHECK(parse(text).options.local.parts == edit::LocalOptions::by_size);  // reads back
  const edit::Job counted = parse("local: {parts: 12}\n");
  CHECK(counted.options.local.parts == 12);
  CHECK(counted.options.local.vertices_per_part == edit::LocalOptions{}.vertices_per_part);
  CHECK_THAT(to_yaml_text(effective_job(counted)), Contains("parts: 12"));
  CHECK(parse("{}").options.local.parts == 0);  // global solves by default
  CHECK_THAT(to_yaml_text(effective_job(parse("{}"))), Contains("parts: 0") && Contains("vertices_per_part: "));

  CHECK_THROWS_WITH(parse("local:\n  vertices_per_part: 0\n"), Contains("edit.yaml:2") && Contains("local.vertices_per_part") && Contains("out of range"));
  CHECK_THROWS_WITH(parse("local: {vertices_per_part: 2.5}\n"), Contains("local.vertices_per_part"));
  CHECK_THROWS_WITH(parse("local: {parts: -1}\n"), Contains("local.parts") && Contains("out of range"));
  CHECK_THROWS_WITH(parse("local: {parts: 2000000000}\n"), Contains("local.parts") && Contains("out of range"));
  CHECK_THROWS_WITH(parse("local: {parts: many}\n"), Contains("local.parts") && Contains("'many'"));
  CHECK_THROWS_WITH(parse("local: {parts: [1, 2]}\n"), Contains("local.parts") && Contains("a part count or auto"));
  CHECK_THROWS_AS(parse("local: {parts: auto, vertices_per_part: -5}\n"), ConfigError);
}

namespace {

const char* kinds_job = R"(
formation:
  splits:
    - {agents: [100, 101], frames: [10, end]}
    - {agents: [102]}
constraints:
  - {type: acceleration, agent: 100, frame: 12, acceleration: [0.5, -1]}
  - {type: acceleration, agent: 101, frame: -1}
  - {type: sum, agents: [100, 101, 102], weights: [0.5, 0.25, 0.25], frames: [3, 8], value: [1, 2]}
  - {type: sum, agents: [100, 101]}
  - type: row
    terms:
      - {agent: 100, frame: 10, axis: x, coefficient: 2}
      - {agent: 101, frame: -3, axis: y}
    value: 1.5
)";

}  // namespace

TEST_CASE("acceleration, sum, row and formation splits: every key read, and read back from the effective job") {
  const edit::Job job = parse(kinds_job);
  const auto& splits = job.options.formation.splits;
  REQUIRE(splits.size() == 2);
  CHECK(splits[0].agents == std::vector<std::int64_t>{100, 101});
  CHECK((splits[0].first_frame == 10 && splits[0].last_frame == std::numeric_limits<std::size_t>::max()));
  CHECK((splits[1].first_frame == 0 && splits[1].last_frame == std::numeric_limits<std::size_t>::max()));
  const auto& c = job.request.constraints;
  REQUIRE(c.size() == 5);
  const auto& a = std::get<edit::Acceleration>(c[0]);
  CHECK((a.agent == 100 && a.frame == 12 && a.acceleration == Eigen::Vector2d(0.5, -1)));
  CHECK(std::get<edit::Acceleration>(c[1]).frame == -1);
  CHECK(std::get<edit::Acceleration>(c[1]).acceleration == Eigen::Vector2d::Zero());  // default: zero acceleration
  const auto& s = std::get<edit::Sum>(c[2]);
  CHECK(s.agents == std::vector<std::int64_t>{100, 101, 102});
  CHECK(s.weights == std::vector<double>{0.5, 0.25, 0.25});
  CHECK((s.first_frame == 3 && s.last_frame == 8 && *s.value == Eigen::Vector2d(1, 2)));
  const auto& centroid = std::get<edit::Sum>(c[3]);
  CHECK((centroid.weights.empty() && !centroid.value && centroid.first_frame == 0 && centroid.last_frame == -1));
  const auto& row = std::get<edit::Row>(c[4]);
  REQUIRE(row.terms.size() == 2);
  CHECK((row.terms[0].agent == 100 && row.terms[0].frame == 10 && row.terms[0].axis == 0 && row.terms[0].coefficient == 2));
  CHECK((row.terms[1].frame == -3 && row.terms[1].axis == 1 && row.terms[1].coefficient == 1));  // default coefficient 1
  CHECK(row.value == 1.5);

  const std::string text = to_yaml_text(effective_job(job));
  const edit::Job again = parse(text);
  CHECK(to_yaml_text(effective_job(again)) == text);
  CHECK_THAT(text, Contains("type: acceleration") && Contains("type: sum") && Contains("type: row") && Contains("axis: y") &&
                       Contains("splits:") && Contains("[10, end]"));
  REQUIRE(again.request.constraints.size() == 5);
  CHECK(std::get<edit::Row>(again.request.constraints[4]).terms[1].frame == -3);
  CHECK(std::get<edit::Sum>(again.request.constraints[2]).weights == s.weights);
  CHECK(again.options.formation.splits.size() == 2);
}

TEST_CASE("malformed acceleration, sum, row and split entries are configuration errors naming the line") {
  auto c = [](const std::string& entry) { return parse("constraints:\n  - " + entry + "\n"); };
  CHECK_THROWS_WITH(c("{type: acceleration, frame: 3}"), Contains("edit.yaml:2") && Contains("agent"));
  CHECK_THROWS_WITH(c("{type: acceleration, agent: 1}"), Contains("frame"));
  CHECK_THROWS_WITH(c("{type: acceleration, agent: 1, frame: 3, acceleration: [1]}"), Contains("acceleration"));
  CHECK_THROWS_WITH(c("{type: acceleration, agent: 1, frame: 3, acceleration: [.nan, 0]}"), Contains("finite"));
  CHECK_THROWS_WITH(c("{type: acceleration, agent: 1, frame: 3, speed: 2}"), Contains("speed"));
  CHECK_THROWS_WITH(c("{type: sum, frames: [0, 3]}"), Contains("agents"));
  CHECK_THROWS_WITH(c("{type: sum, agents: []}"), Contains("a sum needs at least one agent"));
  CHECK_THROWS_WITH(c("{type: sum, agents: [1, 2, 1]}"), Contains("agent 1 is named twice"));
  CHECK_THROWS_WITH(c("{type: sum, agents: [1, 2], weights: [1]}"), Contains("1 weights for 2 agents"));
  CHECK_THROWS_WITH(c("{type: sum, agents: [1, 2], weights: [0, 0]}"), Contains("every weight is 0"));
  CHECK_THROWS_WITH(c("{type: sum, agents: [1, 2], weights: [1, .inf]}"), Contains("finite"));
  CHECK_THROWS_WITH(c("{type: sum, agents: [1, 2], value: [1, 2, 3]}"), Contains("value"));
  CHECK_THROWS_WITH(c("{type: sum, agents: [1, 2], frames: [1]}"), Contains("expected [first, last]"));
  CHECK_THROWS_WITH(c("{type: row, value: 1}"), Contains("terms"));
  CHECK_THROWS_WITH(c("{type: row, terms: [], value: 1}"), Contains("a row needs at least one term"));
  CHECK_THROWS_WITH(c("{type: row, terms: [{agent: 1, frame: 2, axis: x}]}"), Contains("value"));
  CHECK_THROWS_WITH(c("{type: row, terms: [{agent: 1, frame: 2, axis: z}], value: 1}"), Contains("unknown axis 'z': expected x or y"));
  CHECK_THROWS_WITH(c("{type: row, terms: [{agent: 1, frame: 2}], value: 1}"), Contains("axis"));
  CHECK_THROWS_WITH(c("{type: row, terms: [{frame: 2, axis: x}], value: 1}"), Contains("agent"));
  CHECK_THROWS_WITH(c("{type: row, terms: [{agent: 1, frame: 2, axis: x, coefficient: .nan}], value: 1}"), Contains("finite"));
  CHECK_THROWS_WITH(c("{type: row, terms: [{agent: 1, frame: 2, axis: x}], value: .inf}"), Contains("finite"));
  CHECK_THROWS_WITH(c("{type: row, terms: [{agent: 1, frame: 2, axis: x, coefficient: 0}], value: 1}"),
                    Contains("every coefficient is 0"));
  CHECK_THROWS_WITH(c("{type: row, terms: [{agent: 1, frame: 2, axis: x}, {agent: 1, frame: 2, axis: x, coefficient: 3}], value: 1}"),
                    Contains("the same coordinate as terms[0] (agent 1, frame 2, x)"));
  CHECK_THROWS_WITH(c("{type: row, terms: [{agent: 1, frame: 2, axis: x, weight: 3}], value: 1}"), Contains("weight"));
  auto split = [](const std::string& entry) { return parse("formation:\n  splits:\n    - " + entry + "\n"); };
  CHECK_THROWS_WITH(split("{frames: [0, 4]}"), Contains("edit.yaml:3") && Contains("agents"));
  CHECK_THROWS_WITH(split("{agents: []}"), Contains("a split needs the agents of one side"));
  CHECK_THROWS_WITH(split("{agents: [4, 4]}"), Contains("agent 4 is named twice"));
  CHECK_THROWS_WITH(split("{agents: [4], frames: [-1, 4]}"), Contains("negative: frames are indices into the input"));
  CHECK_THROWS_WITH(split("{agents: [4], frames: [9, 4]}"), Contains("first frame 9 is after the last 4"));
  CHECK_THROWS_WITH(split("{agents: [4], frames: [9]}"), Contains("expected [first, last]"));
  CHECK_THROWS_WITH(split("{agents: [4], side: left}"), Contains("side"));
  CHECK_THROWS_WITH(c("{type: jerk, agent: 1}"), Contains("expected relative_position, velocity, on_line, acceleration, sum or row"));
}
