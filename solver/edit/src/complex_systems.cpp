#include "complex_systems.h"

#include <throng/core/parallel.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace throng::edit {
namespace {

using linalg::Complex;
using linalg::ComplexSparse;

// One feature list as a term of an objective: its rows are the feature's prediction (`esc` false) or its two
// ESC edges (`esc` true), weighted by the feature's weight times `weight`. `range[s]` .. `range[s + 1]` are the
// features whose predicted vertex lies at sample s.
struct Term {
  const std::vector<Feature>* features = nullptr;
  double weight = 0;
  bool esc = false;
  std::size_t before = 0, after = 0;  // the samples of features that reach a row at sample s: [s − before, s + after]
  std::vector<std::size_t> range;
};

std::vector<std::size_t> sample_ranges(const std::vector<Feature>& features, int agents, std::size_t samples) {
  std::vector<std::size_t> range(samples + 1, features.size());
  std::size_t k = 0;
  for (std::size_t s = 0; s <= samples; ++s) {
    while (k < features.size() && static_cast<std::size_t>(features[k].v / agents) < s) ++k;
    range[s] = k;
  }
  return range;
}

// The complex rows of feature f in a term: up to two rows of three (vertex, coefficient) pairs.
int rows_of(const Feature& f, bool esc, std::array<std::array<std::pair<int, Complex>, 3>, 2>& rows) {
  if (esc) {
    rows[0] = {{{f.v, 1.0}, {f.u, -1.0}, {f.u, 0.0}}};
    rows[1] = {{{f.v, 1.0}, {f.w, -1.0}, {f.w, 0.0}}};
    return 2;
  }
  rows[0] = {{{f.v, 1.0}, {f.u, -(1.0 - f.c)}, {f.w, -f.c}}};
  return 1;
}

// The rows of one sample's vertices being summed. Each row's entries are kept in the order first met (the
// order of summation), found through a small open-addressing table keyed by column: a row has ~25 entries; one
// with more than half the table's slots (a vertex of very high formation degree) is searched linearly.
class SampleRows {
 public:
  explicit SampleRows(int rows) : rows_(static_cast<std::size_t>(rows)), slot_(static_cast<std::size_t>(rows) * slots, -1) {}
  void clear() {
    for (std::size_t r = 0; r < rows_.size(); ++r) {
      std::fill(slot_.begin() + static_cast<std::ptrdiff_t>(r * slots), slot_.begin() + static_cast<std::ptrdiff_t>((r + 1) * slots), -1);
      rows_[r].clear();
    }
  }
  void add(int row, int column, Complex value) {
    auto& entries = rows_[static_cast<std::size_t>(row)];
    if (entries.size() >= slots / 2) {
      for (auto& e : entries) {
        if (e.first == column) {
          e.second += value;
          return;
        }
      }
      entries.emplace_back(column, value);
      return;
    }
    int* table = slot_.data() + static_cast<std::size_t>(row) * slots;
    for (std::size_t h = hash(column);; h = (h + 1) % slots) {
      const int at = table[h];
      if (at < 0) {
        table[h] = static_cast<int>(entries.size());
        entries.emplace_back(column, value);
        return;
      }
      if (entries[static_cast<std::size_t>(at)].first == column) {
        entries[static_cast<std::size_t>(at)].second += value;
        return;
      }
    }
  }
  std::vector<std::pair<int, Complex>>& row(int r) { return rows_[static_cast<std::size_t>(r)]; }

 private:
  static constexpr std::size_t slots = 64;  // > the most entries a row of these systems has (~45 with many edits)
  static std::size_t hash(int column) { return static_cast<std::size_t>(column) * 2654435761u % slots; }
  std::vector<std::vector<std::pair<int, Complex>>> rows_;
  std::vector<int> slot_;
};

}  // namespace

VertexSplit VertexSplit::of(std::size_t vertices, int agents, const std::vector<Eigen::Index>& handles) {
  VertexSplit s;
  s.agents = agents;
  s.free_index.assign(vertices, -1);
  s.pin_index.assign(vertices, -1);
  for (Eigen::Index h : handles) s.pin_index[static_cast<std::size_t>(h)] = 0;
  for (std::size_t v = 0; v < vertices; ++v) {
    if (s.pin_index[v] == 0) {
      s.pin_index[v] = static_cast<int>(s.pinned.size());
      s.pinned.push_back(static_cast<int>(v));
    }
  }
  const std::size_t samples = agents > 0 ? vertices / static_cast<std::size_t>(agents) : 0;
  for (int j = 0; j < agents; ++j) {
    for (std::size_t i = 0; i < samples; ++i) {
      const std::size_t v = i * static_cast<std::size_t>(agents) + static_cast<std::size_t>(j);
      if (s.pin_index[v] >= 0) continue;
      s.free_index[v] = static_cast<int>(s.free.size());
      s.free.push_back(static_cast<int>(v));
    }
  }
  return s;
}

ComplexSystem assemble_complex(const FeatureSet& features, StepKind step, double alpha, double beta, const VertexSplit& split) {
  const int n = split.agents;
  const std::size_t vertices = split.free_index.size();
  const std::size_t samples = n > 0 ? vertices / static_cast<std::size_t>(n) : 0;
  // Each term with the samples whose features reach a row at sample s: [s − before, s + after] (spatial: s;
  // temporal: s − 1 .. s + 1; spatiotemporal: s, s + 1).
  std::vector<Term> terms;
  terms.push_back({&features.spatial, 1.0, step == StepKind::scale_compensation, 0, 0, {}});
  terms.push_back({&features.temporal, alpha, false, 1, 1, {}});
  terms.push_back({&features.spatiotemporal, beta, false, 0, 1, {}});
  for (Term& t : terms) t.range = sample_ranges(*t.features, n, samples);

  // Per sample: the rows of its free vertices (CSR pieces, columns as vertices for now).
  struct Piece {
    std::vector<int> start;                          // per agent: its row's first entry (rows of pinned vertices are empty)
    std::vector<std::pair<int, Complex>> entries;    // (column vertex, value), rows one after the other, sorted
  };
  std::vector<Piece> pieces(samples);
  parallel_for(samples, 1, [&](std::size_t s0, std::size_t s1) {
    SampleRows rows(n);
    std::array<std::array<std::pair<int, Complex>, 3>, 2> feature_rows{};
    for (std::size_t s = s0; s < s1; ++s) {
      rows.clear();
      const int first = static_cast<int>(s) * n;
      for (const Term& t : terms) {
        if (t.weight <= 0) continue;
        const std::size_t from = s >= t.before ? s - t.before : 0;
        const std::size_t to = std::min(samples, s + t.after + 1);
        for (std::size_t k = t.range[from]; k < t.range[to]; ++k) {
          const Feature& f = (*t.features)[k];
          const double weight = f.weight * t.weight;
          const int count = rows_of(f, t.esc, feature_rows);
          for (int r = 0; r < count; ++r) {
            for (const auto& [p, ap] : feature_rows[static_cast<std::size_t>(r)]) {
              if (ap == Complex(0) || p < first || p >= first + n || split.free_index[static_cast<std::size_t>(p)] < 0) continue;
              const Complex left = weight * std::conj(ap);  // (real × complex: no library call)
              for (const auto& [q, aq] : feature_rows[static_cast<std::size_t>(r)]) {
                if (aq != Complex(0)) rows.add(p - first, q, linalg::times(left, aq));
              }
            }
          }
        }
      }
      Piece& piece = pieces[s];
      piece.start.assign(static_cast<std::size_t>(n) + 1, 0);
      for (int j = 0; j < n; ++j) {
        piece.start[static_cast<std::size_t>(j)] = static_cast<int>(piece.entries.size());
        if (split.free_index[static_cast<std::size_t>(first + j)] < 0) continue;
        auto& e = rows.row(j);
        std::sort(e.begin(), e.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        piece.entries.insert(piece.entries.end(), e.begin(), e.end());
      }
      piece.start[static_cast<std::size_t>(n)] = static_cast<int>(piece.entries.size());
    }
  });

  // The rows in the free vertices' order (agent by agent: split.free), columns split into free (by free index,
  // increasing) and pinned (by pin slot), written straight into the two matrices (sized first: no growth, no
  // copy), rows in parallel.
  const auto nf = static_cast<Eigen::Index>(split.free.size());
  const auto np = static_cast<Eigen::Index>(split.pinned.size());
  ComplexSystem system;
  system.FF.resize(nf, nf);
  system.FP.resize(nf, np);
  int* ff_outer = system.FF.outerIndexPtr();
  int* fp_outer = system.FP.outerIndexPtr();
  ff_outer[0] = fp_outer[0] = 0;
  for (Eigen::Index r = 0; r < nf; ++r) {
    const int vertex = split.free[static_cast<std::size_t>(r)];
    const Piece& piece = pieces[static_cast<std::size_t>(vertex / n)];
    const auto j = static_cast<std::size_t>(vertex % n);
    int free_count = 0;
    for (int e = piece.start[j]; e < piece.start[j + 1]; ++e) free_count += split.free_index[static_cast<std::size_t>(piece.entries[static_cast<std::size_t>(e)].first)] >= 0;
    ff_outer[r + 1] = ff_outer[r] + free_count;
    fp_outer[r + 1] = fp_outer[r] + (piece.start[j + 1] - piece.start[j] - free_count);
  }
  system.FF.resizeNonZeros(ff_outer[nf]);
  system.FP.resizeNonZeros(fp_outer[nf]);
  parallel_for(static_cast<std::size_t>(nf), 1024, [&](std::size_t r0, std::size_t r1) {
    std::vector<std::pair<int, Complex>> row;
    for (std::size_t r = r0; r < r1; ++r) {
      const int vertex = split.free[r];
      const Piece& piece = pieces[static_cast<std::size_t>(vertex / n)];
      const auto j = static_cast<std::size_t>(vertex % n);
      row.clear();
      int pinned_at = fp_outer[r];
      for (int e = piece.start[j]; e < piece.start[j + 1]; ++e) {
        const auto& [column, value] = piece.entries[static_cast<std::size_t>(e)];
        const int f = split.free_index[static_cast<std::size_t>(column)];
        if (f >= 0) {
          row.emplace_back(f, value);
        } else {  // vertex order is pin-slot order
          system.FP.innerIndexPtr()[pinned_at] = split.pin_index[static_cast<std::size_t>(column)];
          system.FP.valuePtr()[pinned_at++] = value;
        }
      }
      std::sort(row.begin(), row.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      int at = ff_outer[r];
      for (const auto& [f, value] : row) {
        system.FF.innerIndexPtr()[at] = f;
        system.FF.valuePtr()[at++] = value;
      }
    }
  });
  return system;
}

void esc_rhs(const FeatureSet& features, const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& original,
             const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& step1, const VertexSplit& split,
             const std::vector<std::size_t>& spatial_ranges, Eigen::VectorXcd& rhs) {
  const auto& range = spatial_ranges;
  const std::size_t samples = range.empty() ? 0 : range.size() - 1;
  rhs.setZero(static_cast<Eigen::Index>(split.free.size()));
  // A spatial feature touches its own sample only: samples in parallel, features in order within one. Spatial
  // features come in threes, one triangle each (FeatureSet), and a triangle never spans two samples.
  parallel_for(samples, 1, [&](std::size_t s0, std::size_t s1) {
    for (std::size_t t = range[s0]; t < range[s1]; t += 3) {
      const Feature& corner = features.spatial[t];
      const int vertex[3] = {corner.u, corner.v, corner.w};
      // turn = s / |s|, s = Σ conj(p_k − p̄)(q_k − q̄): the rotation of the best rigid fit (systems.h).
      double px = 0, py = 0, qx = 0, qy = 0;
      for (int v : vertex) {
        px += original(v, 0), py += original(v, 1);
        qx += step1(v, 0), qy += step1(v, 1);
      }
      px /= 3, py /= 3, qx /= 3, qy /= 3;
      double sr = 0, si = 0;
      for (int v : vertex) {
        const double ax = original(v, 0) - px, ay = original(v, 1) - py;
        const double bx = step1(v, 0) - qx, by = step1(v, 1) - qy;
        sr += ax * bx + ay * by;
        si += ax * by - ay * bx;
      }
      const double length = std::sqrt(sr * sr + si * si);
      const Complex turn_minus_one = length > 0 ? Complex(sr / length - 1.0, si / length) : Complex(0, 0);
      for (std::size_t k = t; k < t + 3; ++k) {
        const Feature& f = features.spatial[k];
        const Complex pv(original(f.v, 0), original(f.v, 1));
        const Complex vu = linalg::times(turn_minus_one, pv - Complex(original(f.u, 0), original(f.u, 1)));
        const Complex vw = linalg::times(turn_minus_one, pv - Complex(original(f.w, 0), original(f.w, 1)));
        // Rows (v − u) and (v − w): conj(a) is +1 at v, −1 at u or w.
        auto add = [&](int vertex_index, Complex value) {
          const int i = split.free_index[static_cast<std::size_t>(vertex_index)];
          if (i >= 0) rhs[i] += f.weight * value;
        };
        add(f.v, vu + vw);
        add(f.u, -vu);
        add(f.w, -vw);
      }
    }
  });
}

std::vector<std::size_t> spatial_sample_ranges(const FeatureSet& features, const VertexSplit& split) {
  const int n = split.agents;
  const std::size_t samples = n > 0 ? split.free_index.size() / static_cast<std::size_t>(n) : 0;
  return sample_ranges(features.spatial, n, samples);
}

}  // namespace throng::edit
