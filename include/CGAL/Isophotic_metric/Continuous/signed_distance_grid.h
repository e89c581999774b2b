// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Signed distance grids (implicit surfaces) from a closed triangle mesh or an oriented point cloud,
// so that isophotic distances can be computed directly on measurement points.
#ifndef CGAL_ISOPHOTIC_METRIC_CONTINUOUS_SIGNED_DISTANCE_GRID_H
#define CGAL_ISOPHOTIC_METRIC_CONTINUOUS_SIGNED_DISTANCE_GRID_H

#include <CGAL/Isophotic_metric/Continuous/Implicit_surface_metric.h>
#include <CGAL/Isophotic_metric/exceptions.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/jet_estimate_normals.h>
#include <CGAL/mst_orient_normals.h>
#include <CGAL/property_map.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricContinuousRef
/// Signed distance from the nodes of `grid` to a closed triangle mesh: negative inside.
/// The unsigned distance comes from an AABB tree; the sign from `CGAL::Side_of_triangle_mesh`,
/// evaluated only where `|d| <= sign_band` (elsewhere the value is `+|d|`: far nodes are never in
/// the narrow band).
/// \throws Invalid_mesh_error if `tm` is not a closed triangle mesh
template <typename TriangleMesh, typename Kernel = typename Kernel_traits<
                                   typename boost::property_traits<typename boost::property_map<
                                     TriangleMesh, vertex_point_t>::const_type>::value_type>::Kernel>
Sampled_function_3 signed_distance_to_mesh(const TriangleMesh& tm, const Grid_3& grid,
                                           double sign_band = std::numeric_limits<double>::infinity())
{
  if(!CGAL::is_triangle_mesh(tm) || !CGAL::is_closed(tm))
    throw Invalid_mesh_error("signed_distance_to_mesh: the mesh must be a closed triangle mesh");
  using Primitive = CGAL::AABB_face_graph_triangle_primitive<TriangleMesh>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
  using Point = typename Kernel::Point_3;
  Tree tree(faces(tm).first, faces(tm).second, tm);
  tree.accelerate_distance_queries();
  CGAL::Side_of_triangle_mesh<TriangleMesh, Kernel> inside(tree);

  std::vector<double> values(grid.size());
  for(int k = 0; k < grid.nz(); ++k)
    for(int j = 0; j < grid.ny(); ++j)
      for(int i = 0; i < grid.nx(); ++i)
      {
        const Eigen::Vector3d x = grid.node(i, j, k);
        const Point p(x.x(), x.y(), x.z());
        const double d = std::sqrt(CGAL::to_double(tree.squared_distance(p)));
        const bool negative = d <= sign_band && inside(p) == CGAL::ON_BOUNDED_SIDE;
        values[grid.index(i, j, k)] = negative ? -d : d;
      }
  return Sampled_function_3(grid, std::move(values));
}

/// \ingroup PkgIsophoticMetricContinuousRef
/// Estimates oriented unit normals of a point cloud with CGAL's point-set processing:
/// `jet_estimate_normals` (local quadric fit over `k` neighbours) then `mst_orient_normals`
/// (propagation along a minimum spanning tree).  Points whose normal could not be oriented
/// are removed from `points_with_normals` (CGAL's convention).
template <typename Kernel>
void estimate_oriented_normals(std::vector<std::pair<typename Kernel::Point_3, typename Kernel::Vector_3>>& points_with_normals,
                               unsigned int k = 18)
{
  using Pair = std::pair<typename Kernel::Point_3, typename Kernel::Vector_3>;
  const auto point_map = CGAL::First_of_pair_property_map<Pair>();
  const auto normal_map = CGAL::Second_of_pair_property_map<Pair>();
  CGAL::jet_estimate_normals<CGAL::Sequential_tag>(points_with_normals, k,
    CGAL::parameters::point_map(point_map).normal_map(normal_map));
  const auto unoriented = CGAL::mst_orient_normals(points_with_normals, k,
    CGAL::parameters::point_map(point_map).normal_map(normal_map));
  points_with_normals.erase(unoriented, points_with_normals.end());
}

/// \ingroup PkgIsophoticMetricContinuousRef
/// Signed distance grid of an oriented point cloud: at every node, a Gaussian-weighted average of
/// the signed distances to the tangent planes of the `k` nearest points (Hoppe et al.'s distance
/// to the tangent plane of the nearest sample, smoothed), with `smoothing` the Gaussian radius
/// (default: twice the mean distance to the nearest neighbour).  Normals must point outwards.
/// \throws Invalid_parameter_error with fewer than `k` points, or a non-finite point or normal
///         (the message names it)
template <typename Kernel>
Sampled_function_3 signed_distance_to_oriented_points(
  const std::vector<std::pair<typename Kernel::Point_3, typename Kernel::Vector_3>>& points_with_normals,
  const Grid_3& grid, unsigned int k = 8, double smoothing = 0.)
{
  using Point = typename Kernel::Point_3;
  using Traits = CGAL::Search_traits_3<Kernel>;
  using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
  if(points_with_normals.size() < std::max(k, 2u))
    throw Invalid_parameter_error("signed_distance_to_oriented_points: " + std::to_string(points_with_normals.size())
                                  + " points, at least " + std::to_string(k) + " needed");
  std::vector<Point> points;
  std::vector<Eigen::Vector3d> normals;
  std::map<Point, std::size_t> index_of;
  for(std::size_t n = 0; n < points_with_normals.size(); ++n)
  {
    const Point& p = points_with_normals[n].first;
    const auto& v = points_with_normals[n].second;
    Eigen::Vector3d normal(CGAL::to_double(v.x()), CGAL::to_double(v.y()), CGAL::to_double(v.z()));
    if(!std::isfinite(CGAL::to_double(p.x())) || !std::isfinite(CGAL::to_double(p.y()))
       || !std::isfinite(CGAL::to_double(p.z())) || !normal.allFinite() || !(normal.norm() > 0.))
      throw Invalid_parameter_error("signed_distance_to_oriented_points: point " + std::to_string(n)
                                    + " has a non-finite coordinate or an invalid normal");
    if(index_of.emplace(p, points.size()).second)
    {
      points.push_back(p);
      normals.push_back(normal.normalized());
    }
  }
  typename Search::Tree tree(points.begin(), points.end());
  if(!(smoothing > 0.))
  {
    double sum = 0.;
    for(const Point& p : points)
    {
      Search search(tree, p, 2);
      auto it = search.begin();
      ++it; // the first neighbour is the point itself
      sum += std::sqrt(CGAL::to_double(it->second));
    }
    smoothing = 2. * sum / double(points.size());
  }
  std::vector<double> values(grid.size());
  for(int kk = 0; kk < grid.nz(); ++kk)
    for(int j = 0; j < grid.ny(); ++j)
      for(int i = 0; i < grid.nx(); ++i)
      {
        const Eigen::Vector3d x = grid.node(i, j, kk);
        Search search(tree, Point(x.x(), x.y(), x.z()), k);
        double sum = 0., weight = 0., nearest = std::numeric_limits<double>::infinity();
        for(const auto& neighbour : search)
        {
          const std::size_t n = index_of[neighbour.first];
          const Point& p = points[n];
          const Eigen::Vector3d px(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
          const double r2 = CGAL::to_double(neighbour.second);
          nearest = std::min(nearest, std::sqrt(r2));
          const double wgt = std::exp(-r2 / (smoothing * smoothing)) + 1e-300;
          sum += wgt * normals[n].dot(x - px);
          weight += wgt;
        }
        // Far from the cloud the plane average is meaningless: keep its sign, use the point distance.
        const double plane = sum / weight;
        values[grid.index(i, j, kk)] = nearest > 3. * smoothing ? std::copysign(nearest, plane) : plane;
      }
  return Sampled_function_3(grid, std::move(values));
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_CONTINUOUS_SIGNED_DISTANCE_GRID_H
