#include <throng/core/errors.h>
#include <throng/io/config.h>

#include <catch2/catch.hpp>
#include "check_throws.h"

using namespace throng;
using Catch::Matchers::Contains;

namespace {

enum class Mode { stop, remove };

struct Options {
  double time_step = 0.1;
  int agents = 50;
  std::size_t steps = 10;
  bool avoid = true;
  std::string name = "crowd";
  std::vector<double> weights{1, 2, 2};
  Mode mode = Mode::stop;
  double inner_radius = 0.5;
  std::size_t count = 5;
};

void bind(OptionBinder& b, Options& o) {
  b.field("time_step", o.time_step, Range::positive());
  b.field("agents", o.agents, Range{1, 1e6});
  b.field("steps", o.steps);
  b.field("avoid", o.avoid);
  b.field("name", o.name);
  b.field("weights", o.weights);
  b.choice("end_of_path", o.mode, {{"stop", Mode::stop}, {"remove", Mode::remove}});
  b.section("inner", [&](OptionBinder& s) { s.field("radius", o.inner_radius, Range::closed(0, 2)); });
  b.field("count", o.count, Range::closed(1, 100));
}

Options read(const std::string& text, const std::vector<std::string>& overrides = {}) {
  const ConfigNode job = ConfigNode::parse(text, "job.yaml").with_overrides(overrides);
  Options o;
  OptionReader r(job);
  bind(r, o);
  job.finish();
  return o;
}

}  // namespace

TEST_CASE("absent keys keep defaults and present keys are read") {
  const Options o = read("time_step: 0.05\nagents: 7\nend_of_path: remove\ninner: {radius: 1.5}\nweights: [1, 3, 4]\n");
  CHECK(o.time_step == 0.05);
  CHECK(o.agents == 7);
  CHECK(o.steps == 10);
  CHECK(o.mode == Mode::remove);
  CHECK(o.inner_radius == 1.5);
  CHECK(o.weights == std::vector<double>{1, 3, 4});
}

TEST_CASE("an unknown key is an error naming it, its line and the known keys") {
  CHECK_THROWS_AS_WITH(read("time_step: 0.05\nagnets: 7\n"), ConfigError,
                       Contains("job.yaml:2:1: unknown key 'agnets'") && Contains("known here:") && Contains("agents"));
  CHECK_THROWS_AS_WITH(read("inner: {radius: 1, radios: 2}\n"), ConfigError, Contains("unknown key 'radios' in inner"));
}

TEST_CASE("out-of-range, wrong-type and non-finite values name the key and line") {
  CHECK_THROWS_AS_WITH(read("time_step: -1\n"), ConfigError, Contains("job.yaml:1:12 (time_step): value -1 is out of range, expected > 0"));
  CHECK_THROWS_AS_WITH(read("agents: many\n"), ConfigError, Contains("(agents): expected an integer, found 'many'"));
  CHECK_THROWS_AS_WITH(read("time_step: .nan\n"), ConfigError, Contains("expected a finite number"));
  CHECK_THROWS_AS_WITH(read("end_of_path: vanish\n"), ConfigError, Contains("expected one of: stop, remove"));
  CHECK_THROWS_AS_WITH(read("inner: {radius: 3}\n"), ConfigError, Contains("expected in [0, 2]"));
  CHECK_THROWS_AS_WITH(read("steps: -4\n"), ConfigError, Contains("value -4 is out of range, expected ≥ 0"));
  // A negative count is out of the count's own range, not merely "≥ 0".
  CHECK_THROWS_AS_WITH(read("count: -5\n"), ConfigError, Contains("value -5 is out of range, expected in [1, 100]"));
  CHECK_THROWS_AS_WITH(read("count: 0\n"), ConfigError, Contains("expected in [1, 100]"));
  CHECK_THROWS_AS_WITH(read("time_step: [1\n"), ConfigError, Contains("not valid YAML"));
}

TEST_CASE("writing the effective options and reading them back gives the same options") {
  Options o;
  o.time_step = 0.1 + 0.2;  // not representable exactly: the writer must round-trip it
  o.mode = Mode::remove;
  YAML::Node node(YAML::NodeType::Map);
  OptionWriter w(node);
  bind(w, o);
  const Options back = read(to_yaml_text(node));
  CHECK(back.time_step == o.time_step);
  CHECK(back.mode == Mode::remove);
  CHECK(back.weights == o.weights);
  CHECK(back.inner_radius == o.inner_radius);
}

TEST_CASE("set overrides (--set) reach nested keys and create missing ones") {
  YAML::Node root = YAML::Load("agents: 5\ninner: {radius: 1}\n");
  apply_overrides(root, {"agents=9", "inner.radius=0.25", "weights=[3, 2, 1]", "name=big crowd"});
  const Options o = read(to_yaml_text(root));
  CHECK(o.agents == 9);
  CHECK(o.inner_radius == 0.25);
  CHECK(o.weights == std::vector<double>{3, 2, 1});
  CHECK(o.name == "big crowd");
  CHECK_THROWS_AS(apply_overrides(root, {"agents"}), ConfigError);
  CHECK_THROWS_AS(apply_overrides(root, {"agents.x=1"}), ConfigError);
}

TEST_CASE("errors in --set values name the override, not a place in the job file") {
  const std::string job = "time_step: 0.05\ninner: {radius: 1}\n";
  CHECK(read(job, {"count=7", "inner.radius=0.25"}).count == 7);
  CHECK_THROWS_AS_WITH(read(job, {"count=-5"}), ConfigError,
                       Contains("--set count=-5: value -5 is out of range, expected in [1, 100]"));
  CHECK_THROWS_AS_WITH(read(job, {"inner.radius=9"}), ConfigError, Contains("--set inner.radius=9: value 9 is out"));
  CHECK_THROWS_AS_WITH(read(job, {"weights=[1, x]"}), ConfigError,
                       Contains("--set weights=[1, x] (weights[1]): expected a number, found 'x'"));
  CHECK_THROWS_AS_WITH(read(job, {"inner.radios=1"}), ConfigError,
                       Contains("--set inner.radios=1: unknown key 'radios' in inner"));
  CHECK_THROWS_AS_WITH(read(job, {"inner={radius: 1, radios: 2}"}), ConfigError,
                       Contains("--set inner={radius: 1, radios: 2}: unknown key 'radios' in inner"));
  // Values still in the file keep their line, also with overrides applied elsewhere.
  CHECK_THROWS_AS_WITH(read("time_step: -1\n", {"count=7"}), ConfigError, Contains("job.yaml:1:12 (time_step)"));
  // Without the override list (apply_overrides alone), a value from --set never points at line 1 of the file.
  YAML::Node root = YAML::Load("time_step: 0.05\n");
  apply_overrides(root, {"count=-5"});
  const ConfigNode plain(root, "job.yaml");
  Options o;
  OptionReader r(plain);
  CHECK_THROWS_AS_WITH(bind(r, o), ConfigError, Contains("job.yaml (count): value -5"));
}

TEST_CASE("lists and missing keys report their place") {
  const ConfigNode job = ConfigNode::parse("points: [[0, 0], [1, 2, 3]]\n", "j.yaml");
  const auto points = job.at("points").elements();
  CHECK(points[0].as_doubles({2}) == std::vector<double>{0, 0});
  CHECK_THROWS_AS_WITH(points[1].as_doubles({2}), ConfigError, Contains("(points[1]): expected 2 numbers, found 3"));
  CHECK_THROWS_AS_WITH(job.at("strokes"), ConfigError, Contains("missing key 'strokes'"));
}

TEST_CASE("a key written twice in one mapping is an error naming both lines, at any depth") {
  // yaml-cpp would keep the first value and drop the second without a word.
  CHECK_THROWS_AS_WITH(read("agents: 7\ntime_step: 0.05\nagents: 9\n"), ConfigError,
                       Contains("job.yaml:3:1: the key 'agents' is written twice") && Contains("first at line 1, again at line 3"));
  CHECK_THROWS_AS_WITH(read("inner:\n  radius: 1\n  radius: 2\n"), ConfigError,
                       Contains("'radius' is written twice") && Contains("first at line 2, again at line 3"));
  CHECK_THROWS_AS_WITH(ConfigNode::parse("steps:\n  - {step: sketch, step: edit}\n", "p.yaml"), ConfigError,
                       Contains("p.yaml:2:") && Contains("'step' is written twice"));
  // The same key in two different mappings is fine.
  CHECK(read("inner: {radius: 1}\nagents: 3\n").agents == 3);
}
