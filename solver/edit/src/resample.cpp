#include "resample.h"

#include <throng/core/parallel.h>

#include <cassert>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

namespace throng::edit {

Eigen::MatrixXd natural_cubic_spline(const std::vector<double>& knots, const Eigen::Ref<const Eigen::MatrixXd>& y,
                                     const std::vector<double>& at) {
  const auto n = static_cast<Eigen::Index>(knots.size());
  assert(n >= 2 && y.rows() == n);
  // Second derivatives M (M_0 = M_{n−1} = 0): h_{i−1} M_{i−1} + 2 (h_{i−1} + h_i) M_i + h_i M_{i+1}
  //   = 6 ((y_{i+1} − y_i)/h_i − (y_i − y_{i−1})/h_{i−1}), solved by the Thomas algorithm.
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, y.cols());
  if (n > 2) {
    std::vector<double> h(static_cast<std::size_t>(n - 1));
    for (Eigen::Index i = 0; i + 1 < n; ++i) h[static_cast<std::size_t>(i)] = knots[static_cast<std::size_t>(i + 1)] - knots[static_cast<std::size_t>(i)];
    std::vector<double> diagonal(static_cast<std::size_t>(n), 1.0), upper(static_cast<std::size_t>(n), 0.0);
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, y.cols());
    for (Eigen::Index i = 1; i + 1 < n; ++i) {
      const double h0 = h[static_cast<std::size_t>(i - 1)], h1 = h[static_cast<std::size_t>(i)];
      const double lower = h0;
      double diag = 2.0 * (h0 + h1);
      Eigen::RowVectorXd r = 6.0 * ((y.row(i + 1) - y.row(i)) / h1 - (y.row(i) - y.row(i - 1)) / h0);
      // Eliminate the sub-diagonal entry against the previous row.
      const double factor = lower / diagonal[static_cast<std::size_t>(i - 1)];
      diag -= factor * upper[static_cast<std::size_t>(i - 1)];
      r -= factor * rhs.row(i - 1);
      diagonal[static_cast<std::size_t>(i)] = diag;
      upper[static_cast<std::size_t>(i)] = h1;
      rhs.row(i) = r;
    }
    for (Eigen::Index i = n - 2; i >= 1; --i) {
      M.row(i) = (rhs.row(i) - upper[static_cast<std::size_t>(i)] * M.row(i + 1)) / diagonal[static_cast<std::size_t>(i)];
    }
  }
  Eigen::MatrixXd out(static_cast<Eigen::Index>(at.size()), y.cols());
  Eigen::Index i = 0;
  for (std::size_t p = 0; p < at.size(); ++p) {
    const double t = at[p];
    while (i + 2 < n && t > knots[static_cast<std::size_t>(i + 1)]) ++i;
    const double t0 = knots[static_cast<std::size_t>(i)], t1 = knots[static_cast<std::size_t>(i + 1)];
    if (t == t0) {
      out.row(static_cast<Eigen::Index>(p)) = y.row(i);
    } else if (t == t1) {
      out.row(static_cast<Eigen::Index>(p)) = y.row(i + 1);
    } else {
      const double h = t1 - t0, a = t1 - t, b = t - t0;
      out.row(static_cast<Eigen::Index>(p)) = M.row(i) * (a * a * a / (6 * h)) + M.row(i + 1) * (b * b * b / (6 * h)) +
                                              (y.row(i) / h - M.row(i) * (h / 6)) * a +
                                              (y.row(i + 1) / h - M.row(i + 1) * (h / 6)) * b;
    }
  }
  return out;
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
