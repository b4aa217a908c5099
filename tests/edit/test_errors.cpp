// Bad requests end in the documented error types (and so exit codes), naming the entry at fault.
#include "../graph/synthetic_crowd.h"

#include <throng/core/errors.h>
#include <throng/edit/edit.h>

#include <catch2/catch.hpp>

using namespace throng;
using namespace throng::edit;
using Catch::Matchers::Contains;

namespace {

CrowdMotion crowd_with_leaver() {
  CrowdMotion crowd = test::marching_grid(3, 3, 21, 1.0, 1.2, 0.1, 0.2, 0.2);
  for (std::size_t f = 15; f < 21; ++f) crowd.position(f, 4).setConstant(absent);  // id 104 leaves at frame 15
  return crowd;
}

Request held_ends() {
  Request r;
  Drag first, last;
  first.selection.last_frame = 0;
  last.selection.first_frame = 20;
  r.drags = {first, last};
  return r;
}

template <typename Error>
void expect(const Request& request, const std::string& text, const Options& options = {}) {
  try {
    (void)edit_group_motion(crowd_with_leaver(), options, request);
    FAIL("expected an error containing: " << text);
  } catch (const Error& e) {
    CHECK_THAT(e.what(), Contains(text));
  }
}

}  // namespace

TEST_CASE("a pin on an agent absent from part of the clip is a configuration error") {
  Request r = held_ends();
  r.pins.push_back({104, 5, std::nullopt});
  expect<ConfigError>(r, "pins[0].agent: agent 104 is absent at some frames of the clip [0, 20]");
  r.pins[0].agent = 777;
  expect<ConfigError>(r, "pins[0].agent: no agent with id 777");
  // Over a clip where the agent is present, it can be pinned.
  Options early;
  early.clip.last_frame = 14;
  Request ok;
  Drag first, last;
  first.selection.last_frame = 0;
  last.selection.first_frame = 14;
  ok.drags = {first, last};
  ok.pins.push_back({104, 5, Eigen::Vector2d(3, 3)});
  CHECK_NOTHROW(edit_group_motion(crowd_with_leaver(), early, ok));
}

TEST_CASE("frames outside the clip are configuration errors") {
  Request r = held_ends();
  r.pins.push_back({100, 25, std::nullopt});
  expect<ConfigError>(r, "pins[0].frame 25 is outside the clip [0, 20]");
  r = held_ends();
  r.drags[0].selection.first_frame = 30;
  r.drags[0].selection.last_frame = 40;
  expect<ConfigError>(r, "drags[0]: frames [30, 40] are outside the clip");
  r = held_ends();
  r.constraints.push_back(Velocity{100, 99, Eigen::Vector2d(1, 0)});
  expect<ConfigError>(r, "constraints[0].frame 99 is outside");
  Options options;
  options.clip.last_frame = 50;
  expect<ConfigError>(held_ends(), "clip.last_frame 50", options);
}

TEST_CASE("contradictory constraints are a numerical error naming them") {
  Request r = held_ends();
  r.constraints.push_back(RelativePosition{100, 101, 10, 10, Eigen::Vector2d(1, 0)});
  r.constraints.push_back(RelativePosition{101, 100, 10, 10, Eigen::Vector2d(1, 0)});  // the opposite offset
  expect<NumericalError>(r, "constraints[0] (position of agent 100 relative to agent 101) and constraints[1]");
  // A constraint that the pins already decide otherwise.
  r = held_ends();
  r.constraints.push_back(OnLine{100, 0, 0, Eigen::Vector2d(100, 100), Eigen::Vector2d(1, 0)});
  expect<NumericalError>(r, "constraints[0] (agent 100 on a line) cannot be met together with the pins and drags");
  // Two handles placing one vertex differently.
  r = held_ends();
  r.pins.push_back({100, 0, Eigen::Vector2d(50, 50)});
  expect<NumericalError>(r, "contradictory handles: pins[0] and drags[0] both place agent 100 at frame 0");
  // Several contradictions: the first one in request order is named (the drag places agent 100 before 101).
  r = held_ends();
  r.pins.push_back({101, 0, Eigen::Vector2d(50, 50)});
  r.pins.push_back({100, 0, Eigen::Vector2d(60, 60)});
  expect<NumericalError>(r, "contradictory handles: pins[1] and drags[0] both place agent 100 at frame 0");
}

TEST_CASE("a system the handles do not determine is a singular-system error") {
  Request one_pin;
  one_pin.pins.push_back({100, 0, std::nullopt});
  expect<NumericalError>(one_pin, "the system is singular: the clip holds handles at one place only");
  // Cutting the formation apart leaves a group without handles.
  Options cut;
  cut.formation.max_edge_length = 0.5;  // shorter than every spacing: each agent is alone
  Request r;
  Drag one_agent;
  one_agent.selection.agents = {100};
  r.drags = {one_agent};
  expect<NumericalError>(r, "agent 101 over frames 0..20 forms a group joined to the rest by no feature", cut);
}

TEST_CASE("zero time weights in either step are named as the cause of a singular system") {
  // Without ET and EST nothing ties one sample to the next: with handles at the ends only, the samples between
  // float. Step 1 checks α, β; step 2 (scale compensation) checks α′, β′ with its own weights.
  Options step1;
  step1.alpha = step1.beta = 0;
  expect<NumericalError>(held_ends(), "the system of step 1 is singular: weights.alpha and weights.beta are 0", step1);
  Options step2;
  step2.alpha_prime = step2.beta_prime = 0;
  expect<NumericalError>(held_ends(), "the system of step 2 (scale compensation) is singular: weights.alpha_prime and "
                                      "weights.beta_prime are 0",
                         step2);
  // Without step 2 its weights do not matter; with every sample held, zero weights are fine.
  step2.scale_compensation = false;
  CHECK_NOTHROW(edit_group_motion(crowd_with_leaver(), step2, held_ends()));
  Request all;
  all.drags.resize(1);
  all.drags[0].selection.last_frame = 20;
  step1.clip.agents = {100, 101, 102};
  CHECK_NOTHROW(edit_group_motion(crowd_with_leaver(), step1, all));
  // One of the two is enough to join the samples.
  step1 = {};
  step1.alpha = 0;
  CHECK_NOTHROW(edit_group_motion(crowd_with_leaver(), step1, held_ends()));
}

TEST_CASE("bad option values are configuration errors") {
  Options options;
  options.alpha = -1;
  expect<ConfigError>(held_ends(), "alpha -1", options);
  options = {};
  options.solver.backend = "magic";
  expect<ConfigError>(held_ends(), "unknown solver backend 'magic'", options);
  options = {};
  options.formation.edits.push_back({100, 555, 0, 5, true});
  expect<ConfigError>(held_ends(), "formation.edits[0]: agent 555", options);
}
