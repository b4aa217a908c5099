#include "adjacency.h"

#include <throng/core/union_find.h>
#include <throng/core/errors.h>
#include <throng/graph/delaunay.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace throng::formation {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase3 = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel>;
using DataStructure3 = CGAL::Triangulation_data_structure_3<VertexBase3>;
using Delaunay3 = CGAL::Delaunay_triangulation_3<Kernel, DataStructure3>;

struct EdgesAndDuplicates {
  std::vector<std::array<int, 2>> edges;
  std::vector<int> duplicate_of;
};

// 3-D Delaunay edges over point indices, inserted in index order so that among coincident points the lowest
// index is the vertex (as delaunay_2d does).
EdgesAndDuplicates delaunay_3d(const Eigen::Ref<const Eigen::MatrixXd>& points) {
  const int n = static_cast<int>(points.rows());
  EdgesAndDuplicates out;
  out.duplicate_of.assign(static_cast<std::size_t>(n), -1);
  Delaunay3 dt;
  Delaunay3::Vertex_handle hint;
  for (int i = 0; i < n; ++i) {
    const Kernel::Point_3 p(points(i, 0), points(i, 1), points(i, 2));
    const std::size_t before = dt.number_of_vertices();
    Delaunay3::Vertex_handle v =
        dt.insert(p, hint == Delaunay3::Vertex_handle() ? Delaunay3::Cell_handle() : hint->cell());
    if (dt.number_of_vertices() == before) {
      out.duplicate_of[static_cast<std::size_t>(i)] = v->info();
    } else {
      v->info() = i;
    }
    hint = v;
  }
  if (dt.dimension() >= 1) {
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
      int a = e->first->vertex(e->second)->info();
      int b = e->first->vertex(e->third)->info();
      if (a > b) std::swap(a, b);
      out.edges.push_back({a, b});
    }
    std::sort(out.edges.begin(), out.edges.end());
  }
  return out;
}

// Where four or more points lie on one empty circle — rings, grids, the regular formations of mass performances —
// the triangulation's diagonals are an arbitrary choice that changes when the formation turns, and a turned
// formation would get a different graph and deform on the way. The Delaunay graph (every pair of points on a
// common empty circle) is unique: triangles sharing an edge whose four points are cocircular (incircle
// determinant within 1e-9 of its scale: designed shapes, whose rounding is ~1e-16) are merged into clusters and
// every pair of points of a cluster is connected.
std::vector<std::array<int, 2>> cocircular_chords(const Eigen::Ref<const Eigen::MatrixXd>& points,
                                                  const std::vector<std::array<int, 3>>& triangles) {
  std::map<std::pair<int, int>, std::vector<int>> faces_of_edge;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = triangles[t][static_cast<std::size_t>(e)], b = triangles[t][static_cast<std::size_t>((e + 1) % 3)];
      faces_of_edge[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(t));
    }
  UnionFind sets(triangles.size());
  bool any = false;
  for (const auto& [edge, faces] : faces_of_edge) {
    if (faces.size() != 2) continue;
    const auto& t = triangles[static_cast<std::size_t>(faces[0])];
    int opposite = -1;
    for (int v : triangles[static_cast<std::size_t>(faces[1])])
      if (v != edge.first && v != edge.second) opposite = v;
    const Eigen::Vector2d d = points.row(opposite).transpose();
    Eigen::Matrix3d m;
    double scale = 0.0, lengths = 1.0;
    for (int r = 0; r < 3; ++r) {
      const Eigen::Vector2d v = points.row(t[static_cast<std::size_t>(r)]).transpose() - d;
      m.row(r) << v.x(), v.y(), v.squaredNorm();
      lengths *= v.norm();
      scale += v.norm();
    }
    if (std::abs(m.determinant()) <= 1e-9 * lengths * scale) {
      sets.join(static_cast<std::size_t>(faces[0]), static_cast<std::size_t>(faces[1]));
      any = true;
    }
  }
  std::vector<std::array<int, 2>> chords;
  if (!any) return chords;
  std::map<int, std::vector<int>> cluster_vertices;
  std::map<int, int> cluster_size;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const int r = static_cast<int>(sets.root(t));
    ++cluster_size[r];
    for (int v : triangles[t]) cluster_vertices[r].push_back(v);
  }
  for (auto& [r, vertices] : cluster_vertices) {
    if (cluster_size[r] < 2) continue;
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    for (std::size_t i = 0; i < vertices.size(); ++i)
      for (std::size_t j = i + 1; j < vertices.size(); ++j) chords.push_back({vertices[i], vertices[j]});
  }
  return chords;
}

std::string point_text(const Eigen::Ref<const Eigen::MatrixXd>& points, int i) {
  std::ostringstream s;
  s << "(";
  for (Eigen::Index c = 0; c < points.cols(); ++c) s << (c ? ", " : "") << points(i, c);
  s << ")";
  return s.str();
}

double distance(const Eigen::Ref<const Eigen::MatrixXd>& points, int a, int b) {
  return (points.row(a) - points.row(b)).norm();
}

}  // namespace

Adjacency delaunay_adjacency(const Eigen::Ref<const Eigen::MatrixXd>& points, const std::string& what,
                             const std::vector<std::string>& item_names) {
  Adjacency graph;
  graph.count = static_cast<int>(points.rows());
  EdgesAndDuplicates found;
  if (points.cols() == 2) {
    Triangulation t = delaunay_2d(points);
    found.edges = std::move(t.edges);
    found.duplicate_of = std::move(t.duplicate_of);
    if (!t.has_duplicates())
      for (const auto& chord : cocircular_chords(points, t.triangles)) found.edges.push_back(chord);
  } else {
    found = delaunay_3d(points);
  }
  for (std::size_t i = 0; i < found.duplicate_of.size(); ++i) {
    const int first = found.duplicate_of[i];
    if (first >= 0) {
      throw InputError(what + ": " + item_names[static_cast<std::size_t>(first)] + " and " + item_names[i] +
                       " are at the same position " + point_text(points, first) +
                       "; every individual of a keyframe needs its own position");
    }
  }
  for (const auto& e : found.edges) graph.weights[{e[0], e[1]}] = 1.0 / distance(points, e[0], e[1]);
  return graph;
}

void apply_edits(Adjacency& graph, const Eigen::Ref<const Eigen::MatrixXd>& points, const std::vector<EdgeEdit>& edits,
                 const std::string& what, const std::vector<std::string>& item_names) {
  auto key = [](const EdgeEdit& e) { return std::make_pair(std::min(e.a, e.b), std::max(e.a, e.b)); };
  auto placed = [](const EdgeEdit& e) { return e.place.empty() ? std::string() : e.place + ": "; };
  auto pair_text = [&](const EdgeEdit& e) {
    return item_names[static_cast<std::size_t>(e.a)] + " and " + item_names[static_cast<std::size_t>(e.b)];
  };
  for (const EdgeEdit::Kind pass : {EdgeEdit::Kind::remove, EdgeEdit::Kind::add, EdgeEdit::Kind::scale}) {
    for (const EdgeEdit& e : edits) {
      const bool scaling = e.kind == EdgeEdit::Kind::scale || e.kind == EdgeEdit::Kind::scale_if_edge;
      if (pass == EdgeEdit::Kind::scale ? !scaling : e.kind != pass) continue;
      auto it = graph.weights.find(key(e));
      switch (e.kind) {
        case EdgeEdit::Kind::remove:
          if (it == graph.weights.end())
            throw ConfigError(placed(e) + what + " " + e.where + ": " + pair_text(e) + " are not adjacent, nothing to remove");
          graph.weights.erase(it);
          break;
        case EdgeEdit::Kind::add:
          if (it == graph.weights.end()) graph.weights[key(e)] = 1.0 / distance(points, e.a, e.b);
          break;
        case EdgeEdit::Kind::scale:
        case EdgeEdit::Kind::scale_if_edge:
          if (!(e.factor > 0.0) || !std::isfinite(e.factor))
            throw ConfigError(placed(e) + what + " " + e.where + ": factor " + std::to_string(e.factor) +
                              " must be finite and > 0 (use remove to cut an edge)");
          if (it != graph.weights.end()) {
            it->second *= e.factor;
          } else if (e.kind == EdgeEdit::Kind::scale) {
            throw ConfigError(placed(e) + what + " " + e.where + ": " + pair_text(e) +
                              " are not adjacent, so their weight cannot be scaled (add the edge first)");
          }
          break;
      }
    }
  }
}

void require_connected(const Adjacency& graph, const std::string& what, const std::vector<std::string>& item_names) {
  std::vector<int> parent(static_cast<std::size_t>(graph.count));
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  };
  for (const auto& [edge, weight] : graph.weights) {
    const int a = root(edge.first), b = root(edge.second);
    if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
  std::vector<std::string> cut;
  std::vector<int> roots;
  for (int i = 0; i < graph.count; ++i) {
    const int r = root(i);
    if (r != root(0)) cut.push_back(item_names[static_cast<std::size_t>(i)]);
    if (std::find(roots.begin(), roots.end(), r) == roots.end()) roots.push_back(r);
  }
  if (!cut.empty()) {
    std::string list;
    for (std::size_t i = 0; i < cut.size() && i < 8; ++i) list += (i ? ", " : "") + cut[i];
    if (cut.size() > 8) list += ", ... (" + std::to_string(cut.size()) + " in all)";
    throw InputError(what + ": the adjacency graph is disconnected (" + std::to_string(roots.size()) +
                     " components): " + list + " not connected to " + item_names[0] +
                     "; the spectral method needs one connected graph per group: add edges, or make the parts "
                     "subgroups of a hierarchy");
  }
}

Eigen::MatrixXd laplacian(const Adjacency& graph) {
  Eigen::MatrixXd l = Eigen::MatrixXd::Zero(graph.count, graph.count);
  for (const auto& [edge, weight] : graph.weights) {
    l(edge.first, edge.second) -= weight;
    l(edge.second, edge.first) -= weight;
    l(edge.first, edge.first) += weight;
    l(edge.second, edge.second) += weight;
  }
  return l;
}

}  // namespace throng::formation
