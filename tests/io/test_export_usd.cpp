// The .usda read back by a strict reader of the USD text grammar (test_export_usda_reader): the stage metadata,
// the PointInstancer's schema attributes and every value round-trip — positions as float, orientations as half,
// ids, protoIndices, scales, invisibleIds per frame, actions per frame and the action table.
#include "test_export_fixtures.h"
#include "test_export_usda_reader.h"
#include "test_paths.h"

#include <throng/io/export/usd.h>

#include <catch2/catch.hpp>

#include <fstream>
#include <map>

using namespace throng;

namespace {

void check_round_trip(const CrowdFile& crowd, const test::usda::Layer& layer) {
  const CrowdMotion& m = crowd.motion;
  const std::size_t T = m.frame_count(), N = m.agent_count();
  CHECK(layer.metadata.at("upAxis") == "Z");
  CHECK(layer.metadata.at("metersPerUnit") == "1");
  CHECK(layer.metadata.at("defaultPrim") == "Crowd");
  CHECK(std::stod(layer.metadata.at("timeCodesPerSecond")) == 25.0);
  CHECK(std::stod(layer.metadata.at("startTimeCode")) == 0.0);
  CHECK(std::stod(layer.metadata.at("endTimeCode")) == static_cast<double>(T - 1));
  CHECK(layer.custom_layer_data.at("throng:startTime").second.numbers == std::vector<double>{m.times.front()});
  CHECK(layer.custom_layer_data.at("throng:credits").second.strings == std::vector<std::string>{"test crowd"});

  const test::usda::Prim* agents = layer.find("/Crowd/Agents");
  REQUIRE(agents);
  CHECK(agents->type == "PointInstancer");
  const auto& a = agents->attributes;
  // Constant per-agent values.
  CHECK(a.at("ids").type == "int64[]");
  CHECK(a.at("ids").value->numbers == std::vector<double>(m.ids.begin(), m.ids.end()));
  std::map<std::int32_t, double> prototype_of;  // species → prototype index, in increasing species order
  for (const auto s : m.species) prototype_of[s] = 0;
  double index = 0;
  for (auto& [s, i] : prototype_of) i = index++;
  const auto& prototypes = agents->relationships.at("prototypes");
  REQUIRE(prototypes.size() == prototype_of.size());
  for (const auto& path : prototypes) {
    const test::usda::Prim* proto = layer.find(path);
    REQUIRE(proto);
    CHECK(proto->type == "Mesh");
    CHECK(proto->attributes.at("points").value->elements == 8);
    CHECK(proto->attributes.at("faceVertexIndices").value->elements == 3 * proto->attributes.at("faceVertexCounts").value->elements);
  }
  CHECK(a.at("primvars:throng:species").metadata.at("interpolation") == "vertex");
  for (std::size_t n = 0; n < N; ++n) {
    CHECK(a.at("protoIndices").value->numbers[n] == prototype_of.at(m.species[n]));
    CHECK(a.at("primvars:throng:species").value->numbers[n] == m.species[n]);
    for (int k = 0; k < 3; ++k) CHECK(a.at("scales").value->numbers[3 * n + k] == static_cast<float>(m.radii[n]));
  }
  // Per-frame values: one sample per frame at time code k, one element per agent.
  for (const char* name : {"positions", "orientations", "invisibleIds", "primvars:throng:action"}) {
    INFO(name);
    REQUIRE(a.at(name).samples.size() == T);
    CHECK(a.at(name).samples.begin()->first == 0.0);
    CHECK(a.at(name).samples.rbegin()->first == static_cast<double>(T - 1));
  }
  CHECK(a.at("positions").type == "point3f[]");
  CHECK(a.at("orientations").type == "quath[]");
  CHECK(a.at("primvars:throng:action").metadata.at("interpolation") == "vertex");
  std::vector<std::string> names, props;
  for (const ActionKind& k : m.actions.empty() ? standard_actions() : m.action_table) {
    names.push_back(k.name);
    props.push_back(k.prop);
  }
  CHECK(a.at("throng:actionNames").value->strings == names);
  CHECK(a.at("throng:actionProps").value->strings == props);
  CHECK(a.at("throng:actionNames").custom);
  CHECK(a.at("throng:actionNames").uniform);
  PathFacing derived(m);
  for (std::size_t t = 0; t < T; ++t) {
    INFO("frame " << t);
    const auto& positions = a.at("positions").samples.at(static_cast<double>(t));
    const auto& orientations = a.at("orientations").samples.at(static_cast<double>(t));
    const auto& actions = a.at("primvars:throng:action").samples.at(static_cast<double>(t));
    REQUIRE(positions.elements == N);
    REQUIRE(orientations.elements == N);
    REQUIRE(actions.elements == N);
    std::vector<double> invisible;
    for (std::size_t n = 0; n < N; ++n) {
      if (!m.present(t, n)) {
        invisible.push_back(static_cast<double>(m.ids[n]));
        continue;
      }
      for (int k = 0; k < 3; ++k) CHECK(positions.numbers[3 * n + k] == static_cast<float>(m.position(t, n)[k]));
      const Eigen::Quaterniond q = m.orientations.empty() ? derived.at(t, n) : Eigen::Quaterniond(m.orientation(t, n));
      const std::vector<double> wxyz{q.w(), q.x(), q.y(), q.z()};
      for (std::size_t k = 0; k < 4; ++k) CHECK(orientations.numbers[4 * n + k] == test::usda::to_half(wxyz[k]));
      CHECK(actions.numbers[n] == (m.actions.empty() ? path_action(m, t, n) : m.action(t, n)));
    }
    CHECK(a.at("invisibleIds").samples.at(static_cast<double>(t)).numbers == invisible);
  }
}

}  // namespace

TEST_CASE("the usda export reads back through the USD grammar with every value") {
  const auto dir = test::scratch_dir("export_usd");
  for (const bool posed : {true, false}) {
    INFO((posed ? "stored facing and actions" : "derived facing and actions"));
    const CrowdFile crowd = posed ? test::posed_export_crowd() : test::export_crowd();
    export_usd(crowd, dir / "crowd.usda");
    check_round_trip(crowd, test::usda::read(dir / "crowd.usda"));
  }
}

TEST_CASE("the strict usda reader refuses what the grammar does not allow") {
  const auto dir = test::scratch_dir("export_usd_reader");
  const std::vector<std::pair<std::string, std::string>> cases{
      {"#usda 1.0\ndef Xform \"A\" {\n  point3f[] p = [(1, 2)]\n}\n", "line 3: expected ','"},
      {"#usda 1.0\ndef Xform \"A\" {\n  int[] p = [1.5]\n}\n", "expected an integer"},
      {"#usda 1.0\ndef Xform \"A\" {\n  vector7 p = 1\n}\n", "expected a value type"},
      {"#usda 1.0\ndef Xform \"A\" {\n  int p.timeSamples = {\n 1: 2,\n 0: 3,\n }\n}\n", "time codes in increasing order"},
      {"#usda 1.0\ndef Xform \"A\" {\n  int p = 1\n  int p = 2\n}\n", "one default value"},
      {"#usda 1.0\ndef Xform \"A\" {\n  int p = 1\n", "expected a name"},
      {"usda 1.0\n", "expected the header"},
  };
  for (const auto& [text, message] : cases) {
    INFO(text);
    std::ofstream(dir / "bad.usda") << text;
    CHECK_THROWS_WITH(test::usda::read(dir / "bad.usda"), Catch::Contains(message));
  }
}
