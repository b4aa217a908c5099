#include "resample.h"

#include <throng/core/parallel.h>
#include <throng/timewarp/spline.h>

#include <cassert>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

namespace throng::edit {

Eigen::MatrixXd natural_cubic_spline(const std::vector<double>& knots, const Eigen::Ref<const Eigen::MatrixXd>& y,
                                     const std::vector<double>& at) {
  assert(knots.size() >= 2 && y.rows() == static_cast<Eigen::Index>(knots.size()));
  const timewarp::CubicSpline spline(knots, timewarp::RowMatrix(y), timewarp::SplineEnd::natural);
  return spline.evaluate(at);
}

CrowdMotion slice_clip(const CrowdMotion& crowd, const Clip& clip) {
  const std::size_t frames = clip.last_frame - clip.first_frame + 1;
  const std::size_t agents = clip.agent_count();
  CrowdMotion out = CrowdMotion::with_shape(frames, agents);
  for (std::size_t f = 0; f < frames; ++f) {
    out.times[f] = crowd.times[clip.first_frame + f];
    for (std::size_t j = 0; j < agents; ++j) out.position(f, j) = crowd.position(clip.first_frame + f, clip.agents[j]);
  }
  for (std::size_t j = 0; j < agents; ++j) {
    out.ids[j] = crowd.ids[clip.agents[j]];
    out.radii[j] = crowd.radii[clip.agents[j]];
    out.species[j] = crowd.species[clip.agents[j]];
  }
  return out;
}

namespace {

using Complex = std::complex<double>;

Complex at(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& p, Eigen::Index row) {
  return {p(row, 0), p(row, 1)};
}

// The rotation Σ conj(o_k − ō)(q_k − q̄) of one sample's formation (original o, edited q), or 0 when the
// formation is a point. A rigid map of the sample gives its rotation times a positive number.
Complex formation_turn(const Clip& clip, const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& edited,
                       std::size_t sample) {
  const std::size_t n = clip.agent_count();
  Complex o_mean = 0, q_mean = 0;
  for (std::size_t j = 0; j < n; ++j) {
    o_mean += at(clip.positions, clip.vertex(sample, j));
    q_mean += at(edited, clip.vertex(sample, j));
  }
  o_mean /= static_cast<double>(n);
  q_mean /= static_cast<double>(n);
  Complex turn = 0;
  for (std::size_t j = 0; j < n; ++j) {
    turn += std::conj(at(clip.positions, clip.vertex(sample, j)) - o_mean) * (at(edited, clip.vertex(sample, j)) - q_mean);
  }
  return turn;
}

}  // namespace

CrowdMotion resample_clip(const CrowdMotion& slice, const Clip& clip,
                          const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& edited) {
  CrowdMotion out = slice;
  const std::size_t frames = slice.frame_count();
  const std::size_t samples = clip.sample_count();
  // Below this squared arm length (m²) a trajectory's turn at a sample is not measurable: the agent stands still.
  const double scale = 1.0 + clip.positions.cwiseAbs().maxCoeff();
  const double still = 1e-18 * scale * scale;
  std::vector<Complex> formation(samples);
  parallel_for(samples, 64, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) formation[i] = formation_turn(clip, edited, i);
  });
  parallel_for(slice.agent_count(), 16, [&](std::size_t begin, std::size_t end) {
    // Columns: original x, y; edited x, y; unwrapped turn angle (radians).
    Eigen::MatrixXd knots(static_cast<Eigen::Index>(samples), 5);
    for (std::size_t j = begin; j < end; ++j) {
      double previous_angle = 0;
      for (std::size_t i = 0; i < samples; ++i) {
        const Eigen::Index v = clip.vertex(i, j);
        const auto row = static_cast<Eigen::Index>(i);
        knots.row(row) << clip.positions(v, 0), clip.positions(v, 1), edited(v, 0), edited(v, 1), 0.0;
        // The trajectory's turn at the sample: the rotation that best maps its motion edges (to the samples
        // before and after), or the formation's when the agent stands still, or none.
        Complex turn = 0;
        double arms = 0;
        for (std::size_t k : {i - 1, i + 1}) {
          if (k >= samples) continue;  // i − 1 wraps around at i = 0
          const Eigen::Index u = clip.vertex(k, j);
          const Complex o = at(clip.positions, u) - at(clip.positions, v);
          turn += std::conj(o) * (at(edited, u) - at(edited, v));
          arms += std::norm(o);
        }
        if (!(arms > still) || turn == Complex(0)) turn = formation[i];
        double angle = turn == Complex(0) ? previous_angle : std::arg(turn);
        // Unwrap: the angle closest to the previous sample's.
        if (i > 0) angle = previous_angle + std::remainder(angle - previous_angle, 2.0 * std::numbers::pi);
        knots(row, 4) = previous_angle = angle;
      }
      const Eigen::MatrixXd s = natural_cubic_spline(clip.times, knots, slice.times);
      std::size_t next_sample = 0;
      for (std::size_t f = 0; f < frames; ++f) {
        auto p = out.position(f, j);
        if (next_sample < samples && clip.frames[next_sample] == clip.first_frame + f) {
          // A sample: its edited position exactly.
          const Eigen::Index v = clip.vertex(next_sample++, j);
          p.x() = edited(v, 0);
          p.y() = edited(v, 1);
          continue;
        }
        // Between samples: the edited path, plus the original's detail off its own path turned with the agent.
        const auto r = static_cast<Eigen::Index>(f);
        const Complex detail = Complex(p.x(), p.y()) - Complex(s(r, 0), s(r, 1));
        const Complex moved = Complex(s(r, 2), s(r, 3)) + std::polar(1.0, s(r, 4)) * detail;
        p.x() = moved.real();
        p.y() = moved.imag();
      }
    }
  });
  return out;
}

}  // namespace throng::edit
