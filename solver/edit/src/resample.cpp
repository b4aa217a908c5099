#include "resample.h"

#include <throng/core/parallel.h>

#include <cassert>

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

CrowdMotion resample_clip(const CrowdMotion& slice, const Clip& clip,
                          const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& edited) {
  CrowdMotion out = slice;
  const std::size_t frames = slice.frame_count();
  parallel_for(slice.agent_count(), 16, [&](std::size_t begin, std::size_t end) {
    Eigen::MatrixXd displacement(static_cast<Eigen::Index>(clip.sample_count()), 2);
    for (std::size_t j = begin; j < end; ++j) {
      for (std::size_t i = 0; i < clip.sample_count(); ++i) {
        const Eigen::Index v = clip.vertex(i, j);
        displacement.row(static_cast<Eigen::Index>(i)) = edited.row(v) - clip.positions.row(v);
      }
      const Eigen::MatrixXd d = natural_cubic_spline(clip.times, displacement, slice.times);
      std::size_t next_sample = 0;
      for (std::size_t f = 0; f < frames; ++f) {
        auto p = out.position(f, j);
        if (next_sample < clip.sample_count() && clip.frames[next_sample] == clip.first_frame + f) {
          // A sample: its edited position exactly (original + (edited − original) may differ in the last bit).
          const Eigen::Index v = clip.vertex(next_sample++, j);
          p.x() = edited(v, 0);
          p.y() = edited(v, 1);
        } else {
          p.x() += d(static_cast<Eigen::Index>(f), 0);
          p.y() += d(static_cast<Eigen::Index>(f), 1);
        }
      }
    }
  });
  return out;
}

}  // namespace throng::edit
