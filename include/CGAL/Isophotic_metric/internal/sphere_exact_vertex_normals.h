// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Default vertex normals of the lifted embedding (Max, "Weights for computing vertex normals from
// facet normals", J. Graphics Tools 4(2), 1999): the sum over the incident faces of
// (e2 x e1) / (|e1|^2 |e2|^2), e1 and e2 the two edges of the face leaving the vertex.
// The result is exact when the vertex and its neighbours lie on a common sphere, and second-order
// accurate on smooth surfaces. PMP::compute_vertex_normals (the "most visible" normal) does not
// converge under refinement: on a projected Loop-subdivided icosahedron its largest error grows from
// 0.0025 to 0.009 between 5k and 82k faces, the size of the normal change along an edge.
#ifndef CGAL_ISOPHOTIC_METRIC_INTERNAL_SPHERE_EXACT_VERTEX_NORMALS_H
#define CGAL_ISOPHOTIC_METRIC_INTERNAL_SPHERE_EXACT_VERTEX_NORMALS_H

#include <CGAL/boost/graph/iterator.h>

#include <boost/container/small_vector.hpp>
#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

inline std::array<double, 3> difference(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

template <typename Point>
std::array<double, 3> to_array(const Point& p)
{
  return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
}

// Unnormalized normal of `v`: a zero vector if every incident face is degenerate, and for an
// isolated vertex.
template <typename TriangleMesh, typename VertexPointMap>
std::array<double, 3>
sphere_exact_vertex_normal(typename boost::graph_traits<TriangleMesh>::vertex_descriptor v,
                           const TriangleMesh& tm, const VertexPointMap& vpm)
{
  std::array<double, 3> n = {0., 0., 0.};
  const auto h0 = halfedge(v, tm);
  if(h0 == boost::graph_traits<TriangleMesh>::null_halfedge())
    return n;
  const std::array<double, 3> p = to_array(get(vpm, v));
  // One walk around v: the edges to the neighbours in the order of the walk (the face of the k-th
  // incoming halfedge h runs source(h) -> v -> target(next(h)), the neighbour of edge k + 1), and
  // the largest coordinate difference.
  boost::container::small_vector<std::array<double, 3>, 16> edge;
  boost::container::small_vector<bool, 16> on_border;
  double unit = 0.;
  for(const auto h : CGAL::halfedges_around_target(h0, tm))
  {
    const std::array<double, 3> e = difference(to_array(get(vpm, source(h, tm))), p);
    unit = (std::max)({unit, std::abs(e[0]), std::abs(e[1]), std::abs(e[2])});
    edge.push_back(e);
    on_border.push_back(is_border(h, tm));
  }
  // The weights are homogeneous of degree -2 in the lengths: the edges are divided by that
  // difference, so that no product over- or underflows whatever the model's units (at 1e-100,
  // |e1|^2 |e2|^2 is 1e-400).
  if(!(unit > 0.) || !std::isfinite(unit))
    return n;
  for(std::array<double, 3>& e : edge)
    for(double& x : e)
      x /= unit;
  for(std::size_t k = 0; k < edge.size(); ++k)
  {
    if(on_border[k])
      continue;
    const std::array<double, 3>& e1 = edge[k];
    const std::array<double, 3>& e2 = edge[k + 1 == edge.size() ? 0 : k + 1];
    const double l1 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
    const double l2 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
    const std::array<double, 3> cross = {e2[1] * e1[2] - e2[2] * e1[1], e2[2] * e1[0] - e2[0] * e1[2],
                                         e2[0] * e1[1] - e2[1] * e1[0]};
    for(int i = 0; i < 3; ++i)
      n[i] += cross[i] / (l1 * l2);
  }
  return n;
}

} // namespace internal
} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_INTERNAL_SPHERE_EXACT_VERTEX_NORMALS_H
