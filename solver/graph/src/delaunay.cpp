#include <throng/graph/delaunay.h>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <numeric>

namespace throng {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, DataStructure>;

// Rotate a CCW triple so its smallest index comes first (keeps orientation, gives a canonical form).
std::array<int, 3> canonical(std::array<int, 3> t) {
  while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
  return t;
}

}  // namespace

bool Triangulation::has_duplicates() const noexcept {
  return std::any_of(duplicate_of.begin(), duplicate_of.end(), [](int d) { return d >= 0; });
}

Triangulation delaunay_2d(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& points) {
  const int n = static_cast<int>(points.rows());
  Triangulation out;
  out.duplicate_of.assign(static_cast<std::size_t>(n), -1);

  // Insert in index order (not CGAL's spatial sort) so that, among coincident points, the lowest index is the
  // vertex; the triangulation itself does not depend on insertion order for points in general position.
  Delaunay dt;
  Delaunay::Vertex_handle hint;
  for (int i = 0; i < n; ++i) {
    const Kernel::Point_2 p(points(i, 0), points(i, 1));
    const std::size_t before = dt.number_of_vertices();
    Delaunay::Vertex_handle v = dt.insert(p, hint == Delaunay::Vertex_handle() ? Delaunay::Face_handle() : hint->face());
    if (dt.number_of_vertices() == before) {
      out.duplicate_of[static_cast<std::size_t>(i)] = v->info();
    } else {
      v->info() = i;
    }
    hint = v;
  }

  if (dt.dimension() == 2) {
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
      out.triangles.push_back(canonical({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}));
    }
    std::sort(out.triangles.begin(), out.triangles.end());
  }
  if (dt.dimension() >= 1) {
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
      int a = e->first->vertex(Delaunay::cw(e->second))->info();
      int b = e->first->vertex(Delaunay::ccw(e->second))->info();
      if (a > b) std::swap(a, b);
      out.edges.push_back({a, b});
    }
    std::sort(out.edges.begin(), out.edges.end());
  }
  return out;
}

}  // namespace throng
