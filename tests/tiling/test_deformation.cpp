// Patch deformation (solver/tiling/src/deformation.h): the Schur-complement joint solve against the single
// concatenated system the paper describes, rigid placement when nothing pulls, interpersonal constraints and
// stitching (Eq. 1–3) met, and the per-frame limits (stretch 3 cm, bend 7°, time shift 0.018 s) enforced.
#include <catch2/catch.hpp>

#include <throng/tiling/check.h>
#include <throng/tiling/library.h>

#include "deformation.h"
#include "geometry.h"
#include "within_limits.h"

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <numbers>

using namespace throng;
using namespace throng::tiling;

namespace {

// Deformation.h's objective and constraints of one channel of one type, built here from the formulas in its
// comment (not from the precomputed G): rows of L with targets l, rows of C with values d, for angle φ.
struct Dense {
  Eigen::MatrixXd L, C;
  Eigen::VectorXd l, d;
};

Dense dense_channel(const PatchType& type, const PatchSystem& sys, bool space, double phi) {
  const Eigen::Index n = sys.samples(), width = space ? 2 : 1;
  std::vector<Eigen::RowVectorXd> rows, crows;
  std::vector<double> targets, values;
  for (std::size_t f = 0; f < type.fragments.size(); ++f) {
    const Fragment& fr = type.fragments[f];
    for (std::size_t i = 1; i + 1 < fr.sample_count(); ++i) {
      const Eigen::Index p = sys.sample(f, i - 1), c = sys.sample(f, i), q = sys.sample(f, i + 1);
      if (!space) {
        Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
        r[c] = 1;
        r[p] = r[q] = -0.5;
        rows.push_back(r);
        targets.push_back(fr.times[i] - 0.5 * (fr.times[i - 1] + fr.times[i + 1]));
        continue;
      }
      const Eigen::Vector2d chord = fr.positions[i + 1] - fr.positions[i - 1];
      const Eigen::Vector2d delta = fr.positions[i] - 0.5 * (fr.positions[i - 1] + fr.positions[i + 1]);
      REQUIRE(chord.norm() > 1e-6);  // the fixtures walk: no degenerate rows
      const double a = delta.dot(chord) / chord.squaredNorm();
      const double b = delta.dot(Eigen::Vector2d(-chord.y(), chord.x())) / chord.squaredNorm();
      // L_i(p) = p_i − (p_{i−1} + p_{i+1})/2 − a c − b J c, c = p_{i+1} − p_{i−1}, J c = (−c_y, c_x).
      for (int k = 0; k < 2; ++k) {
        Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(2 * n);
        r[2 * c + k] = 1;
        r[2 * p + k] = -0.5 + a;
        r[2 * q + k] = -0.5 - a;
        const int other = 1 - k;
        const double sign = k == 0 ? 1.0 : -1.0;  // (J c)_x = −c_y, (J c)_y = c_x
        r[2 * q + other] += sign * b;
        r[2 * p + other] -= sign * b;
        rows.push_back(r);
        targets.push_back(0.0);
      }
    }
  }
  for (const InterpersonalConstraint& ic : type.constraints) {
    const Eigen::Index a = sys.sample(ic.fragment_a, ic.sample_a), b = sys.sample(ic.fragment_b, ic.sample_b);
    if (space) {
      const Eigen::Vector2d want =
          rotate(type.fragments[ic.fragment_b].positions[ic.sample_b] - type.fragments[ic.fragment_a].positions[ic.sample_a], phi);
      for (int k = 0; k < 2; ++k) {
        Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(2 * n);
        r[2 * b + k] = 1;
        r[2 * a + k] = -1;
        crows.push_back(r);
        values.push_back(want[k]);
      }
    } else {
      Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
      r[b] = 1;
      r[a] = -1;
      crows.push_back(r);
      values.push_back(type.fragments[ic.fragment_b].times[ic.sample_b] - type.fragments[ic.fragment_a].times[ic.sample_a]);
    }
  }
  Dense out;
  out.L.resize(static_cast<Eigen::Index>(rows.size()), width * n);
  out.l.resize(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    out.L.row(static_cast<Eigen::Index>(r)) = rows[r];
    out.l[static_cast<Eigen::Index>(r)] = targets[r];
  }
  out.C.resize(static_cast<Eigen::Index>(crows.size()), width * n);
  out.d.resize(static_cast<Eigen::Index>(crows.size()));
  for (std::size_t r = 0; r < crows.size(); ++r) {
    out.C.row(static_cast<Eigen::Index>(r)) = crows[r];
    out.d[static_cast<Eigen::Index>(r)] = values[r];
  }
  return out;
}

// The concatenated system of all members and the coupling rows, solved through its KKT matrix:
//   minimise Σ_k |L_k x_k − l_k|² + w_a |x_k − anchor_k|²  subject to  C_k x_k = d_k,  E x = e.
Eigen::VectorXd concatenated(const std::vector<const PatchType*>& types, const JointProblem& jp, bool space, double w_a) {
  std::vector<Dense> parts;
  std::vector<Eigen::Index> offset{0};
  for (std::size_t k = 0; k < jp.members.size(); ++k) {
    parts.push_back(dense_channel(*types[k], *jp.members[k].system, space, jp.members[k].angle));
    offset.push_back(offset.back() + parts.back().L.cols());
  }
  const Eigen::Index N = offset.back();
  const std::vector<Row>& coupling = space ? jp.space_rows : jp.time_rows;
  Eigen::Index M = static_cast<Eigen::Index>(coupling.size());
  for (const Dense& p : parts) M += p.C.rows();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N + M, N + M);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(N + M);
  Eigen::Index m = N;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const Dense& p = parts[k];
    const Eigen::Index o = offset[k], w = p.L.cols();
    const Eigen::VectorXd& anchor = space ? jp.members[k].space_anchor : jp.members[k].time_anchor;
    K.block(o, o, w, w) = 2 * (p.L.transpose() * p.L) + 2 * w_a * Eigen::MatrixXd::Identity(w, w);
    rhs.segment(o, w) = 2 * (p.L.transpose() * p.l) + 2 * w_a * anchor;
    K.block(m, o, p.C.rows(), w) = p.C;
    K.block(o, m, w, p.C.rows()) = p.C.transpose();
    rhs.segment(m, p.C.rows()) = p.d;
    m += p.C.rows();
  }
  for (const Row& r : coupling) {
    for (int i = 0; i < r.size; ++i) {
      const Term& t = r.terms[static_cast<std::size_t>(i)];
      K(m, offset[t.member] + t.unknown) += t.coefficient;
      K(offset[t.member] + t.unknown, m) += t.coefficient;
    }
    rhs[m] = r.value;
    ++m;
  }
  const Eigen::VectorXd x = K.fullPivLu().solve(rhs);
  return x.head(N);
}

// A member placed undeformed at `transform`.
Member member_at(const PatchType& type, const PatchSystem& sys, const Transform& transform) {
  const std::vector<Path> paths = place(type, transform);
  return {&sys, sys.space_anchor(paths), sys.time_anchor(paths), transform.angle};
}

// Eq. 1–3 rows between the exit of fragment fa of member a and the entry of fragment fb of member b.
void join(JointProblem& jp, const PatchType& ta, std::uint32_t a, std::size_t fa, std::uint32_t b, std::size_t fb) {
  const PatchSystem& sa = *jp.members[a].system;
  const PatchSystem& sb = *jp.members[b].system;
  const std::size_t n = ta.fragments[fa].sample_count() - 1;
  for (int c = 0; c < 2; ++c) {
    Row r;
    r.add(a, 2 * sa.sample(fa, n) + c, 1.0);
    r.add(b, 2 * sb.sample(fb, 0) + c, -1.0);
    jp.space_rows.push_back(r);
    Row tangent;
    tangent.add(a, 2 * sa.sample(fa, n) + c, 1.0);
    tangent.add(a, 2 * sa.sample(fa, n - 1) + c, -1.0);
    tangent.add(b, 2 * sb.sample(fb, 1) + c, -1.0);
    tangent.add(b, 2 * sb.sample(fb, 0) + c, 1.0);
    jp.space_rows.push_back(tangent);
  }
  Row t;
  t.add(a, sa.sample(fa, n), 1.0);
  t.add(b, sb.sample(fb, 0), -1.0);
  jp.time_rows.push_back(t);
}

// True when check-tiling finds no deformation failure in one undeformed-placed instance of lib's first type
// whose first path is `path` (in a 40 m box wide enough for it).
bool checker_accepts_path(const PatchLibrary& lib, const Path& path, const CheckOptions& check) {
  Tiling t;
  t.instances.push_back({0, Transform{}, false, {path}});
  Environment env;
  env.scene.region = Region{{-20, -20}, {20, 20}, -20, 20, {false, false, false}};
  return check_tiling(lib, t, env, check).count(FailureKind::deformation) == 0;
}

}  // namespace

TEST_CASE("the Schur-complement joint solve equals the single concatenated system, and meets Eq. 1-3") {
  const PatchLibrary lib = builtin_library({"turn_left", "walk"});
  const DeformationOptions options;
  const PatchType& turn = lib.types[0];
  const PatchType& walk = lib.types[1];
  const PatchSystem st(turn, options), sw(walk, options);
  // A turn and a walk whose entry lies 0.3 m, 0.2 m and 0.1 s off the turn's exit: stitching pulls both.
  Transform a;
  a.translation = {2, 3};
  a.angle = 0.4;
  a.time_shift = 5;
  const Path turned = place(turn, a)[0];
  Transform b;
  b.angle = wrap_angle(turned.headings.back() - walk.fragments[0].headings.front() + 0.05);
  b.translation = turned.positions.back() - rotate(walk.fragments[0].positions.front(), b.angle) + Eigen::Vector2d(0.3, 0.2);
  b.time_shift = turned.times.back() - walk.fragments[0].times.front() + 0.1;
  JointProblem jp;
  jp.members = {member_at(turn, st, a), member_at(walk, sw, b)};
  join(jp, turn, 0, 0, 1, 0);
  const JointSolution s = solve_joint(jp);
  CHECK(s.max_residual < 1e-9);

  const std::vector<const PatchType*> types{&turn, &walk};
  for (const bool space : {true, false}) {
    INFO((space ? "space" : "time") << " channel");
    const Eigen::VectorXd x = concatenated(types, jp, space, options.anchor_weight);
    const Eigen::VectorXd mine = space ? (Eigen::VectorXd(x.size()) << s.space[0], s.space[1]).finished()
                                       : (Eigen::VectorXd(x.size()) << s.time[0], s.time[1]).finished();
    // Both solve the same well-posed problem in double precision (the pull moves samples by up to 0.16 m and
    // 0.05 s); the KKT matrix's condition (about 1 / w_a = 10³ along the Laplacian's near-null directions)
    // times the unit roundoff times the coordinates' size (≤ 12) bounds the difference near 1e-11.
    CHECK((x - mine).cwiseAbs().maxCoeff() < 1e-10);
  }

  // Eq. 1–3 on the paths: the same position, tangent and time at the join.
  const Path p = paths_from(turn, st, a.angle, s.space[0], s.time[0])[0];
  const Path q = paths_from(walk, sw, b.angle, s.space[1], s.time[1])[0];
  const std::size_t n = p.times.size() - 1;
  CHECK((p.positions[n] - q.positions[0]).norm() < 1e-9);
  CHECK(((p.positions[n] - p.positions[n - 1]) - (q.positions[1] - q.positions[0])).norm() < 1e-9);
  CHECK(std::abs(p.times[n] - q.times[0]) < 1e-9);
}

TEST_CASE("with the handles where the placement puts them, a deformed patch is its rigid placement") {
  const PatchLibrary lib = builtin_library({"meet"});
  const PatchType& meet = lib.types[0];
  const PatchSystem sys(meet, DeformationOptions{});
  Transform t;
  t.translation = {4, -1};
  t.angle = 0.7;
  t.time_shift = 3;
  const std::vector<Path> placed = place(meet, t);
  // No coupling: the free solution.
  JointProblem free;
  free.members = {member_at(meet, sys, t)};
  const JointSolution a = solve_joint(free);
  // Every end pinned where it already is (position, tangent, time): the same.
  JointProblem pinned = free;
  for (std::size_t f = 0; f < 2; ++f) {
    for (const bool exit : {false, true}) {
      const Path& p = placed[f];
      const std::size_t e = exit ? p.times.size() - 1 : 0, inner = exit ? e - 1 : 1;
      for (int c = 0; c < 2; ++c) {
        Row r;
        r.add(0, 2 * sys.sample(f, e) + c, 1.0);
        r.value = p.positions[e][c];
        pinned.space_rows.push_back(r);
        Row tr;
        tr.add(0, 2 * sys.sample(f, exit ? e : inner) + c, 1.0);
        tr.add(0, 2 * sys.sample(f, exit ? inner : e) + c, -1.0);
        tr.value = exit ? (p.positions[e] - p.positions[inner])[c] : (p.positions[inner] - p.positions[e])[c];
        pinned.space_rows.push_back(tr);
      }
      Row tt;
      tt.add(0, sys.sample(f, e), 1.0);
      tt.value = p.times[e];
      pinned.time_rows.push_back(tt);
    }
  }
  const JointSolution b = solve_joint(pinned);
  for (const JointSolution* s : {&a, &b}) {
    const std::vector<Path> paths = paths_from(meet, sys, t.angle, s->space[0], s->time[0]);
    double worst = 0, worst_t = 0, worst_h = 0;
    for (std::size_t f = 0; f < 2; ++f) {
      for (std::size_t k = 0; k < placed[f].times.size(); ++k) {
        worst = std::max(worst, (paths[f].positions[k] - placed[f].positions[k]).norm());
        worst_t = std::max(worst_t, std::abs(paths[f].times[k] - placed[f].times[k]));
        worst_h = std::max(worst_h, std::abs(wrap_angle(paths[f].headings[k] - placed[f].headings[k])));
      }
    }
    // The rigid placement zeroes the rotation-invariant Laplacian and the anchor terms: it is the minimiser.
    CHECK(worst < 1e-9);
    CHECK(worst_t < 1e-9);
    CHECK(worst_h < 1e-9);
  }
}

TEST_CASE("a pulled two-character patch keeps its interpersonal constraints and its limits decide validity") {
  const PatchLibrary lib = builtin_library({"meet"});
  const PatchType& meet = lib.types[0];
  const PatchSystem sys(meet, DeformationOptions{});
  Transform t;
  t.angle = -0.3;
  t.time_shift = 10;
  const std::vector<Path> placed = place(meet, t);
  const auto pulled = [&](const Eigen::Vector2d& offset, double dt) {
    // The entry of character 0 pinned `offset` and `dt` away from where the placement puts it.
    JointProblem jp;
    jp.members = {member_at(meet, sys, t)};
    const Path& p = placed[0];
    for (int c = 0; c < 2; ++c) {
      Row r;
      r.add(0, 2 * sys.sample(0, 0) + c, 1.0);
      r.value = p.positions[0][c] + offset[c];
      jp.space_rows.push_back(r);
    }
    Row tt;
    tt.add(0, sys.sample(0, 0), 1.0);
    tt.value = p.times[0] + dt;
    jp.time_rows.push_back(tt);
    const JointSolution s = solve_joint(jp);
    CHECK(s.max_residual < 1e-9);
    return paths_from(meet, sys, t.angle, s.space[0], s.time[0]);
  };
  const std::vector<Path> paths = pulled({0.25, -0.15}, 0.08);
  CHECK((paths[0].positions[0] - placed[0].positions[0] - Eigen::Vector2d(0.25, -0.15)).norm() < 1e-9);
  for (const InterpersonalConstraint& ic : meet.constraints) {
    const Eigen::Vector2d want = rotate(meet.fragments[ic.fragment_b].positions[ic.sample_b] - meet.fragments[ic.fragment_a].positions[ic.sample_a], t.angle);
    const Eigen::Vector2d got = paths[ic.fragment_b].positions[ic.sample_b] - paths[ic.fragment_a].positions[ic.sample_a];
    CHECK((want - got).norm() < 1e-9);
    const double dt_want = meet.fragments[ic.fragment_b].times[ic.sample_b] - meet.fragments[ic.fragment_a].times[ic.sample_a];
    CHECK(std::abs(paths[ic.fragment_b].times[ic.sample_b] - paths[ic.fragment_a].times[ic.sample_a] - dt_want) < 1e-9);
  }
  // A small pull stays within the per-frame limits; a 1.5 m, 1 s pull cannot (at most 9 cm and 0.054 s per
  // 0.1 s sample, and the elastic string spreads the pull over the first seconds only).
  const DeformationLimits limits;
  const double top_speed = speed_limit(builtin_library({"meet"}), limits.speed_ratio);
  CHECK(within_limits(meet.fragments[0], paths[0], limits, top_speed));
  const std::vector<Path> far = pulled({1.5, 0.0}, 1.0);
  CHECK_FALSE(within_limits(meet.fragments[0], far[0], limits, top_speed));
}

TEST_CASE("the deformation limits are per frame of 30 Hz motion: stretch 3 cm, bend 7°, time shift 0.018 s") {
  const PatchLibrary lib = builtin_library({"walk"});
  const Fragment& walk = lib.types[0].fragments[0];  // 0.1 s samples: 3 frames each
  DeformationLimits limits;
  limits.speed_ratio = 0;  // the paper's limits alone (the speed limit has its own test below)
  const double no_limit = std::numeric_limits<double>::infinity();
  const Path rigid = place(lib.types[0], Transform{})[0];
  REQUIRE(within_limits(walk, rigid, limits, no_limit));
  // Each test changes one sample by just under and just over its limit; the checker agrees with the tiler.
  CheckOptions check;
  check.limits = limits;
  const auto checker_accepts = [&](const Path& p) { return checker_accepts_path(lib, p, check); };
  for (const double scale : {0.99, 1.01}) {
    INFO("scale " << scale);
    const bool within = scale < 1;
    // Stretch: samples 11.. moved along the path, segment 10 longer by scale × 9 cm.
    Path stretched = rigid;
    for (std::size_t s = 11; s < stretched.positions.size(); ++s) stretched.positions[s].x() += scale * 3 * limits.stretch_m;
    CHECK(within_limits(walk, stretched, limits, no_limit) == within);
    CHECK(checker_accepts(stretched) == within);
    // Time shift: samples 11.. later by scale × 0.054 s.
    Path shifted = rigid;
    for (std::size_t s = 11; s < shifted.times.size(); ++s) shifted.times[s] += scale * 3 * limits.time_shift_s;
    CHECK(within_limits(walk, shifted, limits, no_limit) == within);
    CHECK(checker_accepts(shifted) == within);
    // Bend: the path turns at sample 10 by scale × 21°, its later segments rotated about it.
    Path bent = rigid;
    const double turn = scale * 3 * limits.bend_rad;
    for (std::size_t s = 11; s < bent.positions.size(); ++s) {
      bent.positions[s] = bent.positions[10] + rotate(rigid.positions[s] - rigid.positions[10], turn);
    }
    CHECK(within_limits(walk, bent, limits, no_limit) == within);
    CHECK(checker_accepts(bent) == within);
  }
}

TEST_CASE("beyond the paper, no deformed segment is faster than speed_ratio times the library's fastest") {
  // walk moves 0.13 m per 0.1 s sample (1.3 m/s): the limit is 1.25 × 1.3 = 1.625 m/s, a segment of 0.1625 m,
  // well inside the paper's stretch limit (0.09 m more per sample), which alone would allow 2.2 m/s.
  const PatchLibrary lib = builtin_library({"walk"});
  const Fragment& walk = lib.types[0].fragments[0];
  const DeformationLimits limits;
  REQUIRE(limits.speed_ratio == 1.25);
  const double top_speed = speed_limit(lib, limits.speed_ratio);
  CHECK_THAT(top_speed, Catch::Matchers::WithinRel(1.625, 1e-9));
  CHECK(speed_limit(lib, 0) == std::numeric_limits<double>::infinity());
  // A library of standing patches has no speed to keep to: no limit rather than a limit of 0.
  CHECK(speed_limit(builtin_library({"wait"}), limits.speed_ratio) == std::numeric_limits<double>::infinity());
  const Path rigid = place(lib.types[0], Transform{})[0];
  CheckOptions check;
  const auto checker_accepts = [&](const Path& p) { return checker_accepts_path(lib, p, check); };
  for (const double scale : {0.99, 1.01}) {
    INFO("scale " << scale);
    const bool within = scale < 1;
    // Segment 10 made scale × (1.625 − 1.3) m/s faster: samples 11.. moved along the path.
    Path faster = rigid;
    for (std::size_t s = 11; s < faster.positions.size(); ++s) faster.positions[s].x() += scale * (top_speed - 1.3) * 0.1;
    CHECK(within_limits(walk, faster, limits, top_speed) == within);
    CHECK(checker_accepts(faster) == within);
    // Without the speed limit the paper's limits allow it.
    CHECK(within_limits(walk, faster, limits, std::numeric_limits<double>::infinity()));
  }
}
