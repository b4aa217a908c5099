#include <throng/core/parallel.h>
#include <throng/graph/features.h>

#include <algorithm>

namespace throng {
namespace {

using Complex = std::complex<double>;

Complex as_complex(const Eigen::Vector2d& p) { return {p.x(), p.y()}; }

// Concatenates per-sample feature lists in sample order.
std::vector<Feature> concatenate(std::vector<std::vector<Feature>>& parts) {
  std::size_t total = 0;
  for (const auto& p : parts) total += p.size();
  std::vector<Feature> out;
  out.reserve(total);
  for (auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

}  // namespace

Feature make_feature(int u, int v, int w, const Eigen::Vector2d& pu, const Eigen::Vector2d& pv, const Eigen::Vector2d& pw,
                     const FeatureOptions& options) {
  Feature f;
  f.u = u;
  f.v = v;
  f.w = w;
  const Complex cu = as_complex(pu), cv = as_complex(pv), cw = as_complex(pw);
  const double arm_u = std::abs(cv - cu);
  const double arm_w = std::abs(cv - cw);
  const double base = std::abs(cw - cu);
  if (base <= options.degenerate_ratio * (arm_u + arm_w)) {
    // Degenerate frame: keep v at the midpoint of u and w plus its original offset.
    f.c = 0.5;
    f.offset = cv - 0.5 * (cu + cw);
  } else {
    f.c = (cv - cu) / (cw - cu);  // Eq. 1: v − u = c (w − u)
  }
  const double floor = options.min_length * options.min_length;
  f.weight = 1.0 / std::max(arm_u * arm_u + arm_w * arm_w, floor);
  return f;
}

FeatureSet compute_features(const MotionGraph& graph, const FeatureOptions& options) {
  const Clip& clip = graph.clip;
  const std::size_t samples = graph.sample_count();
  const std::size_t agents = graph.agent_count();
  std::vector<std::vector<Feature>> spatial(samples), temporal(samples), spatiotemporal(samples);
  auto at = [&](std::size_t i, std::size_t j) { return Eigen::Vector2d(clip.positions.row(clip.vertex(i, j))); };
  auto id = [&](std::size_t i, std::size_t j) { return static_cast<int>(clip.vertex(i, j)); };

  parallel_for(samples, 4, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      for (const auto& t : graph.triangles[i]) {
        for (int k = 0; k < 3; ++k) {
          const auto a = static_cast<std::size_t>(t[static_cast<std::size_t>(k)]);
          const auto b = static_cast<std::size_t>(t[static_cast<std::size_t>((k + 1) % 3)]);
          const auto c = static_cast<std::size_t>(t[static_cast<std::size_t>((k + 2) % 3)]);
          spatial[i].push_back(make_feature(id(i, a), id(i, b), id(i, c), at(i, a), at(i, b), at(i, c), options));
        }
      }
      if (i > 0 && i + 1 < samples) {
        for (std::size_t j = 0; j < agents; ++j) {
          temporal[i].push_back(
              make_feature(id(i - 1, j), id(i, j), id(i + 1, j), at(i - 1, j), at(i, j), at(i + 1, j), options));
        }
      }
      if (i > 0) {
        for (const auto& e : graph.edges[i]) {
          for (int side = 0; side < 2; ++side) {
            const auto j = static_cast<std::size_t>(e[static_cast<std::size_t>(side)]);
            const auto k = static_cast<std::size_t>(e[static_cast<std::size_t>(1 - side)]);
            spatiotemporal[i].push_back(
                make_feature(id(i - 1, j), id(i, j), id(i, k), at(i - 1, j), at(i, j), at(i, k), options));
          }
        }
      }
    }
  });
  return {concatenate(spatial), concatenate(temporal), concatenate(spatiotemporal)};
}

}  // namespace throng
