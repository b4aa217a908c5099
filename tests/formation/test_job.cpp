// The formation job file (io/formation): shape generators, edits, hierarchy forms, keyframes from a crowd,
// the effective job, and the errors with their exit-code types.
#include <throng/core/errors.h>
#include <throng/io/formation_job.h>
#include <throng/formation/runner.h>
#include <throng/io/formation_shapes.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace throng;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

ConfigNode yaml(const std::string& text) { return ConfigNode::parse(text, "job.yaml"); }

Eigen::MatrixXd shape(const std::string& text) { return generate_shapes(yaml("shapes: [" + text + "]").at("shapes")); }

double min_distance(const Eigen::MatrixXd& p) {
  double best = INFINITY;
  for (Eigen::Index i = 0; i < p.rows(); ++i)
    for (Eigen::Index j = i + 1; j < p.rows(); ++j) best = std::min(best, (p.row(i) - p.row(j)).norm());
  return best;
}

const std::string two_keyframes =
    "keyframes:\n"
    "  - time: 0\n"
    "    positions: [[0, 0], [2, 0], [0, 2], [2, 2.5]]\n"
    "  - time: 4\n"
    "    positions: [[10, 0], [12, 0], [10, 2], [12, 2]]\n";

}  // namespace

TEST_CASE("shape generators: circle, grid, polyline, star, strokes, text, nested, placement") {
  SECTION("circle: count points at the radius, evenly spaced, point 0 at angle 0") {
    const Eigen::MatrixXd p = shape("{circle: {count: 8, radius: 3, center: [1, 2]}}");
    REQUIRE(p.rows() == 8);
    REQUIRE(p.cols() == 2);
    for (Eigen::Index i = 0; i < 8; ++i) CHECK((p.row(i) - Eigen::RowVector2d(1, 2)).norm() == Approx(3));
    CHECK(p(0, 0) == Approx(4));
    CHECK(p(0, 1) == Approx(2));
    CHECK(min_distance(p) == Approx(2 * 3 * std::sin(std::numbers::pi / 8)));
  }
  SECTION("grid: row-major from the top-left, centred, spacing per axis") {
    const Eigen::MatrixXd p = shape("{grid: {rows: 2, columns: 3, spacing: [2, 1]}}");
    REQUIRE(p.rows() == 6);
    CHECK(p.row(0) == Eigen::RowVector2d(-2, 0.5));
    CHECK(p.row(5) == Eigen::RowVector2d(2, -0.5));
    CHECK(p.colwise().mean().norm() == Approx(0).margin(1e-12));
  }
  SECTION("polyline: open includes both ends; closed goes round") {
    const Eigen::MatrixXd open = shape("{polyline: {points: [[0, 0], [4, 0], [4, 4]], count: 5}}");
    CHECK(open.row(0) == Eigen::RowVector2d(0, 0));
    CHECK(open.row(2).isApprox(Eigen::RowVector2d(4, 0)));
    CHECK(open.row(4).isApprox(Eigen::RowVector2d(4, 4)));
    const Eigen::MatrixXd closed = shape("{polyline: {points: [[0, 0], [4, 0], [4, 4], [0, 4]], count: 8, closed: true}}");
    CHECK(closed.row(7).isApprox(Eigen::RowVector2d(0, 2)));
    CHECK(min_distance(closed) == Approx(2));
  }
  SECTION("star: a tip at the top, every point between the inner and outer radius") {
    const Eigen::MatrixXd p = shape("{star: {count: 20, outer_radius: 6, inner_radius: 2, tips: 5}}");
    REQUIRE(p.rows() == 20);
    CHECK(p.row(0).isApprox(Eigen::RowVector2d(0, 6)));
    for (Eigen::Index i = 0; i < 20; ++i) {
      CHECK(p.row(i).norm() <= 6 + 1e-9);
      CHECK(p.row(i).norm() >= 2 * std::cos(std::numbers::pi / 5) - 1e-9);  // no closer than an edge's foot
    }
    CHECK(min_distance(p) > 1.0);
  }
  SECTION("strokes: evenly along the lines taken end to end, half a spacing from the ends") {
    const Eigen::MatrixXd p = shape("{strokes: {lines: [[[0, 0], [3, 0]], [[0, 5], [3, 5]]], count: 4}}");
    CHECK(p.row(0).isApprox(Eigen::RowVector2d(0.75, 0)));
    CHECK(p.row(1).isApprox(Eigen::RowVector2d(2.25, 0)));
    CHECK(p.row(2).isApprox(Eigen::RowVector2d(0.75, 5)));
    CHECK(p.row(3).isApprox(Eigen::RowVector2d(2.25, 5)));
  }
  SECTION("text: the letter T has a bar at the top and a stem, centred, height as asked") {
    const Eigen::MatrixXd p = shape("{text: {text: T, count: 10, height: 100}}");
    REQUIRE(p.rows() == 10);
    CHECK(p.col(1).maxCoeff() == Approx(50));   // bar points at the top
    CHECK(p.col(1).minCoeff() > -50);           // stem points above the baseline (half a spacing)
    int on_bar = 0;
    for (Eigen::Index i = 0; i < 10; ++i) on_bar += std::abs(p(i, 1) - 50) < 1e-9 ? 1 : 0;
    CHECK(on_bar == 4);  // 0.6 of 1.6 of the strokes' length
    CHECK(min_distance(p) > 5);
    CHECK_THROWS_AS(shape("{text: {text: 'T4', count: 10, height: 1}}"), ConfigError);
    CHECK_THROWS_WITH(shape("{text: {text: 'T4', count: 10, height: 1}}"), Contains("font has no '4'"));
  }
  SECTION("nested: every combination, first index slowest, rows add up") {
    const Eigen::MatrixXd p = shape("{nested: [{circle: {count: 3, radius: 10}}, {circle: {count: 2, radius: 1}}]}");
    REQUIRE(p.rows() == 6);
    CHECK(p.row(0).isApprox(Eigen::RowVector2d(11, 0)));
    CHECK(p.row(1).isApprox(Eigen::RowVector2d(9, 0)));
    CHECK((p.row(2) - p.row(3)).norm() == Approx(2));
  }
  SECTION("placement: rotation in degrees, 3-D through center and axes") {
    const Eigen::MatrixXd r = shape("{circle: {count: 4, radius: 1, rotation: 90}}");
    CHECK(r.row(0).isApprox(Eigen::RowVector2d(0, 1)));
    const Eigen::MatrixXd s = shape("{circle: {count: 4, radius: 2, center: [0, 5, 100], axes: [[1, 0, 0], [0, 0, 1]]}}");
    REQUIRE(s.cols() == 3);
    CHECK(s.row(1).isApprox(Eigen::RowVector3d(0, 5, 102)));
    CHECK(s.col(1).isApproxToConstant(5));
  }
  SECTION("several entries are concatenated; 2-D beside 3-D gets z = 0") {
    const Eigen::MatrixXd p = shape("{points: [[1, 1]]}, {points: [[2, 2, 2]]}");
    REQUIRE(p.rows() == 2);
    REQUIRE(p.cols() == 3);
    CHECK(p.row(0) == Eigen::RowVector3d(1, 1, 0));
  }
  SECTION("malformed shapes are ConfigErrors naming the line") {
    CHECK_THROWS_WITH(shape("{hexagon: {count: 3}}"), Contains("unknown shape 'hexagon'"));
    CHECK_THROWS_WITH(shape("{circle: {count: 0, radius: 1}}"), Contains("count must be"));
    CHECK_THROWS_WITH(shape("{polyline: {points: [[1, 1], [1, 1]], count: 3}}"), Contains("zero length"));
    CHECK_THROWS_AS(shape("{circle: {count: 3, radius: 1}, grid: {rows: 1, columns: 1, spacing: 1}}"), ConfigError);
  }
}

TEST_CASE("a job reads keyframes, edits, ids and options, and writes them back as its effective job") {
  const FormationJob job = read_job<FormationJob>(yaml(
      two_keyframes +
      "ids: [10, 11, 12, 13]\n"
      "tension: 0.8\n"
      "reordering: max_min\n"
      "edits:\n"
      "  remove: [[0, 3]]\n"
      "  add: [[1, 2]]\n"
      "  scale: [{pairs: [[0, 1]], factor: 2}, {members: [0, 1, 2], factor: 3}]\n"
      "collision: {enabled: true, min_distance: 0.5}\n"));
  REQUIRE(job.problem.keyframes.size() == 2);
  CHECK(job.problem.keyframes[1].time_s == 4);
  CHECK(job.problem.keyframes[1].positions(1, 0) == 12);
  CHECK(job.problem.ids == std::vector<std::int64_t>{10, 11, 12, 13});
  CHECK(job.options.tension == 0.8);
  CHECK(job.options.reordering == formation::Reordering::max_min);
  CHECK(job.options.collision.enabled);
  CHECK(job.problem.edits.remove == std::vector<formation::Pair>{{0, 3}});
  REQUIRE(job.problem.edits.scale.size() == 2);
  CHECK(job.problem.edits.scale[1].members == std::vector<int>{0, 1, 2});

  const YAML::Node effective = effective_job(job);
  CHECK(effective["orientation"].as<std::string>() == "pca");
  CHECK(effective["collision"]["min_distance"].as<double>() == 0.5);
  // The effective job reads back to the same problem.
  const FormationJob again = read_job<FormationJob>(ConfigNode(effective, "effective"));
  CHECK(again.problem.keyframes[0].positions == job.problem.keyframes[0].positions);
  CHECK(again.options.tension == 0.8);
  CHECK(again.problem.edits.scale.size() == 2);
}

TEST_CASE("hierarchy forms: a tree, sizes, nested and auto and scale edits by group name") {
  SECTION("nested: levels of consecutive individuals") {
    const FormationJob job = read_job<FormationJob>(yaml(
        "hierarchy: {nested: [2, 2]}\n" + two_keyframes));
    REQUIRE(job.problem.hierarchy);
    REQUIRE(job.problem.hierarchy->subgroups.size() == 2);
    CHECK(job.problem.hierarchy->subgroups[1].name == "g1");
    CHECK(job.problem.hierarchy->subgroups[1].members == std::vector<int>{2, 3});
  }
  SECTION("sizes: one level") {
    const FormationJob job = read_job<FormationJob>(yaml("hierarchy: {sizes: [1, 3]}\n" + two_keyframes));
    CHECK(job.problem.hierarchy->subgroups[1].members == std::vector<int>{1, 2, 3});
  }
  SECTION("a tree, and a scale edit naming one of its groups") {
    const FormationJob job = read_job<FormationJob>(yaml(
        "hierarchy: {name: all, members: [3], groups: [{name: front, members: [0, 1, 2]}]}\n"
        "edits: {scale: [{groups: [front], factor: 2}]}\n" + two_keyframes));
    CHECK(job.problem.hierarchy->members == std::vector<int>{3});
    REQUIRE(job.problem.edits.scale.size() == 1);
    CHECK(job.problem.edits.scale[0].members == std::vector<int>{0, 1, 2});
    CHECK_THROWS_WITH(read_job<FormationJob>(yaml("hierarchy: {name: all, members: [0, 1, 2, 3]}\n"
                                              "edits: {scale: [{groups: [back], factor: 2}]}\n" + two_keyframes)),
                      Contains("no hierarchy group is named 'back'"));
  }
  SECTION("auto: spectral clustering with a largest group") {
    const FormationJob job = read_job<FormationJob>(yaml("hierarchy: {auto: 3}\n" + two_keyframes));
    CHECK_FALSE(job.problem.hierarchy);
    CHECK(job.options.auto_group_size == 3);
    CHECK(effective_job(job)["hierarchy"]["auto"].as<int>() == 3);
  }
  SECTION("none given: automatic beyond 2,000 individuals; flat: never") {
    const FormationJob automatic = read_job<FormationJob>(yaml(two_keyframes));
    CHECK_FALSE(automatic.problem.hierarchy);
    CHECK(automatic.options.auto_group_size == 2000);
    CHECK(effective_job(automatic)["hierarchy"]["auto"].as<int>() == 2000);
    const FormationJob flat = read_job<FormationJob>(yaml("hierarchy: flat\n" + two_keyframes));
    CHECK_FALSE(flat.problem.hierarchy);
    CHECK(flat.options.auto_group_size == 0);
    const YAML::Node effective = effective_job(flat);
    CHECK(effective["hierarchy"].as<std::string>() == "flat");
    CHECK(read_job<FormationJob>(ConfigNode(effective, "effective")).options.auto_group_size == 0);  // round trip
    CHECK_THROWS_AS(read_job<FormationJob>(yaml("hierarchy: flatter\n" + two_keyframes)), ConfigError);
  }
}

TEST_CASE("keyframes from a crowd at given frames, counting back from the end") {
  FormationJob job = read_job<FormationJob>(yaml("from_crowd: {frames: [0, -1]}\n"));
  REQUIRE(job.from_crowd);
  CrowdFile crowd;
  crowd.motion = CrowdMotion::with_shape(5, 3);
  for (std::size_t f = 0; f < 5; ++f) {
    crowd.motion.times[f] = 0.5 * static_cast<double>(f);
    for (std::size_t i = 0; i < 3; ++i) crowd.motion.position(f, i) = Eigen::Vector3d(static_cast<double>(f + 2 * i), static_cast<double>(i * i), 0);
  }
  crowd.motion.ids = {7, 8, 9};
  resolve_formation_keyframes(job, &crowd);
  REQUIRE(job.problem.keyframes.size() == 2);
  CHECK(job.problem.keyframes[1].time_s == 2.0);
  CHECK(job.problem.keyframes[1].positions(2, 0) == 8.0);
  CHECK(job.problem.ids == std::vector<std::int64_t>{7, 8, 9});
  FormationJob bad = read_job<FormationJob>(yaml("from_crowd: {frames: [0, 5]}\n"));
  CHECK_THROWS_AS(resolve_formation_keyframes(bad, &crowd), InputError);
  CHECK_THROWS_AS(resolve_formation_keyframes(bad, nullptr), ConfigError);
}

TEST_CASE("job errors: data problems are InputErrors with the line, syntax and options ConfigErrors") {
  SECTION("a keyframe with a different count") {
    CHECK_THROWS_AS(read_job<FormationJob>(yaml("keyframes:\n  - {time: 0, positions: [[0, 0], [1, 0], [0, 1]]}\n"
                                            "  - {time: 1, positions: [[0, 0], [1, 0]]}\n")),
                    InputError);
    CHECK_THROWS_WITH(read_job<FormationJob>(yaml("keyframes:\n  - {time: 0, positions: [[0, 0], [1, 0], [0, 1]]}\n"
                                              "  - {time: 1, positions: [[0, 0], [1, 0]]}\n")),
                      Contains("job.yaml:3") && Contains("keyframe 1 has 2 individuals, keyframe 0 has 3"));
  }
  SECTION("duplicate positions") {
    CHECK_THROWS_WITH(read_job<FormationJob>(yaml("keyframes:\n  - {time: 0, positions: [[0, 0], [1, 0], [0, 1]]}\n"
                                              "  - {time: 1, positions: [[5, 5], [1, 0], [5, 5]]}\n")),
                      Contains("individuals 0 and 2 are both at (5, 5)"));
  }
  SECTION("times not increasing") {
    CHECK_THROWS_AS(read_job<FormationJob>(yaml("keyframes:\n  - {time: 2, positions: [[0, 0], [1, 0]]}\n"
                                            "  - {time: 2, positions: [[0, 1], [1, 1]]}\n")),
                    InputError);
  }
  SECTION("2-D beside 3-D") {
    CHECK_THROWS_AS(read_job<FormationJob>(yaml("keyframes:\n  - {time: 0, positions: [[0, 0], [1, 0]]}\n"
                                            "  - {time: 1, positions: [[0, 1, 0], [1, 1, 0]]}\n")),
                    InputError);
  }
  SECTION("syntax and options") {
    CHECK_THROWS_AS(read_job<FormationJob>(yaml(two_keyframes + "tension: 2\n")), ConfigError);
    CHECK_THROWS_WITH(read_job<FormationJob>(yaml(two_keyframes + "tensoin: 0.5\n")), Contains("tensoin"));
    CHECK_THROWS_AS(read_job<FormationJob>(yaml(two_keyframes + "reordering: best\n")), ConfigError);
    CHECK_THROWS_AS(read_job<FormationJob>(yaml("keyframes: [{time: 0, positions: [[0, 0]]}]\n")), ConfigError);
    CHECK_THROWS_AS(read_job<FormationJob>(yaml(two_keyframes + "from_crowd: {frames: [0, 1]}\n")), ConfigError);
    CHECK_THROWS_AS(read_job<FormationJob>(yaml(two_keyframes + "edits: {add: [[0, 1, 2]]}\n")), ConfigError);
    CHECK_THROWS_AS(read_job<FormationJob>(yaml(two_keyframes + "edits: {scale: [{pairs: [[0, 1]], factor: 0}]}\n")), ConfigError);
    CHECK_THROWS_AS(read_job<FormationJob>(yaml(two_keyframes + "ids: [1, 1, 2, 3]\n")), ConfigError);
  }
  SECTION("a disconnected graph after edits reaches the solver as an InputError naming the cut-off individuals") {
    const FormationJob job = read_job<FormationJob>(yaml(
        "keyframes:\n  - {time: 0, positions: [[0, 0], [1, 0]]}\n  - {time: 1, positions: [[0, 1], [1, 1]]}\n"
        "edits: {remove: [[0, 1]]}\n"));
    CHECK_THROWS_AS(formation::animate_formation(job.problem, job.options), InputError);
  }
}

TEST_CASE("errors the solver finds name the place in the job: a disconnected graph, an edit, the hierarchy") {
  // The job's keyframes, edits and hierarchy carry their file:line into the problem; the solver's messages
  // about them start with it.
  auto solve = [](const std::string& text) {
    const FormationJob job = read_job<FormationJob>(yaml(text));
    (void)formation::animate_formation(job.problem, job.options);
  };
  SECTION("a keyframe whose graph the edits disconnect: the keyframe's line") {
    const std::string text =
        "keyframes:\n  - {time: 0, positions: [[0, 0], [1, 0]]}\n"
        "  - time: 1\n    positions: [[0, 1], [1, 1]]\n    edits: {remove: [[0, 1]]}\n";
    CHECK_THROWS_AS(solve(text), InputError);
    CHECK_THROWS_WITH(solve(text), StartsWith("job.yaml:3:") && Contains("formation keyframe 1") &&
                                       Contains("disconnected") && Contains("individual 1 not connected"));
  }
  SECTION("an edit naming an individual that does not exist, or a pair that is not an edge: the edits' line") {
    CHECK_THROWS_AS(solve(two_keyframes + "edits: {remove: [[0, 5]]}\n"), ConfigError);
    CHECK_THROWS_WITH(solve(two_keyframes + "edits: {remove: [[0, 5]]}\n"),
                      StartsWith("job.yaml:6:") && Contains("edits.remove[0]: individual 5 does not exist"));
    // Square 0, 1, 3, 2 (2.5 m high on one side): its diagonal 0–3 is no edge of keyframe 0.
    CHECK_THROWS_WITH(solve(two_keyframes + "edits: {scale: [{pairs: [[0, 3]], factor: 2}]}\n"),
                      StartsWith("job.yaml:6:") && Contains("are not adjacent"));
  }
  SECTION("a hierarchy that misses an individual: the hierarchy's line") {
    const std::string text = two_keyframes + "hierarchy: {name: all, groups: [{name: a, members: [0, 1]}, {name: b, members: [2]}]}\n";
    CHECK_THROWS_AS(solve(text), ConfigError);
    CHECK_THROWS_WITH(solve(text), StartsWith("job.yaml:6:") && Contains("individual 3 is in no group"));
  }
}

TEST_CASE("the result lists each keyframe's frame and graph and the crowd's formation edges are those kept throughout") {
  // A square with a centre, then the same turned by 45° and spread: Delaunay joins the centre to every corner
  // and the corners around; the job removes one rim edge in keyframe 1 only and adds a diagonal everywhere.
  const FormationJob job = read_job<FormationJob>(yaml(
      "keyframes:\n"
      "  - {time: 0, positions: [[0, 0], [2, 0], [2, 2], [0, 2], [1, 1]]}\n"
      "  - {time: 1, positions: [[10, 0], [13, 3], [10, 6], [7, 3], [10, 3]], edits: {remove: [[0, 1]]}}\n"
      "edits: {add: [[0, 2]]}\n"));
  const formation::Result r = formation::animate_formation(job.problem, job.options);
  CHECK(r.keyframe_frames == std::vector<std::size_t>{0, 30});
  using P = formation::Pair;
  const std::vector<P> rim_and_spokes{{0, 1}, {0, 2}, {0, 3}, {0, 4}, {1, 2}, {1, 4}, {2, 3}, {2, 4}, {3, 4}};
  CHECK(r.keyframe_edges[0] == rim_and_spokes);
  const std::vector<P> without_01{{0, 2}, {0, 3}, {0, 4}, {1, 2}, {1, 4}, {2, 3}, {2, 4}, {3, 4}};
  CHECK(r.keyframe_edges[1] == without_01);
  const Crowd crowd{r.motion, {}, formation::kept_edges(r)};
  REQUIRE(crowd.formation_edges.size() == without_01.size());
  for (std::size_t e = 0; e < without_01.size(); ++e) {
    CHECK(crowd.formation_edges[e][0] == without_01[e][0]);
    CHECK(crowd.formation_edges[e][1] == without_01[e][1]);
  }
}

TEST_CASE("a keyframe's facing: degrees for everyone, one per individual, or toward a point, and the facing options") {
  auto yaw_deg = [](const Eigen::Quaterniond& q) {
    const Eigen::Vector3d forward = q * Eigen::Vector3d::UnitX();
    return std::atan2(forward.y(), forward.x()) * 180.0 / std::numbers::pi;
  };
  const FormationJob job = read_job<FormationJob>(yaml(
      "keyframes:\n"
      "  - {time: 0, positions: [[0, 0], [2, 0], [0, 2], [2, 2.5]], facing: 90}\n"
      "  - {time: 4, positions: [[10, 0], [12, 0], [10, 2], [12, 2]], facing: [0, 45, -90, 180]}\n"
      "  - {time: 8, positions: [[20, 0], [22, 0], [20, 2], [22, 2]], facing: {toward: [21, 10]}}\n"
      "facing: {max_turn_rate: 1.5, smoothing: 0.2, standing_speed: 0.2, running_speed: 3, bank: false}\n"));
  const auto& k = job.problem.keyframes;
  REQUIRE(k[0].facings.size() == 4);
  for (const auto& q : k[0].facings) CHECK(yaw_deg(q) == Approx(90));
  REQUIRE(k[1].facings.size() == 4);
  CHECK(yaw_deg(k[1].facings[1]) == Approx(45));
  CHECK(yaw_deg(k[1].facings[2]) == Approx(-90));
  CHECK(std::abs(yaw_deg(k[1].facings[3])) == Approx(180));
  REQUIRE(k[2].facings.size() == 4);
  // Individual 0 at (20, 0) faces (21, 10): atan2(10, 1).
  CHECK(yaw_deg(k[2].facings[0]) == Approx(std::atan2(10.0, 1.0) * 180.0 / std::numbers::pi));
  CHECK(yaw_deg(k[2].facings[3]) == Approx(std::atan2(8.0, -1.0) * 180.0 / std::numbers::pi));
  CHECK(job.options.facing.max_turn_rate_rad_s == 1.5);
  CHECK(job.options.facing.smoothing_s == 0.2);
  CHECK(job.options.facing.rule.standing_speed == 0.2);
  CHECK(job.options.facing.rule.running_speed == 3);
  CHECK_FALSE(job.options.facing.bank);

  SECTION("errors name the keyframe's line") {
    CHECK_THROWS_WITH(read_job<FormationJob>(yaml(two_keyframes + "    facing: [0, 90]\n")),
                      Contains("job.yaml:6") && Contains("keyframes[1].facing") && Contains("2 facings for 4 individuals"));
    CHECK_THROWS_AS(read_job<FormationJob>(yaml(two_keyframes + "    facing: .nan\n")), ConfigError);
    CHECK_THROWS_WITH(read_job<FormationJob>(yaml(two_keyframes + "    facing: {towards: [0, 1]}\n")), Contains("toward"));
    CHECK_THROWS_AS(read_job<FormationJob>(yaml(two_keyframes + "    facing: {toward: [0, 1, 2, 3]}\n")), ConfigError);
    CHECK_THROWS_AS(read_job<FormationJob>(yaml(two_keyframes + "facing: {max_turn_rate: 0}\n")), ConfigError);
  }
}
