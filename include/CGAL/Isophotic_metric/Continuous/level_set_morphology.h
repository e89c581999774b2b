// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Continuous morphology on surfaces (Pottmann et al. 2004, Sect. 4.1): dilation, erosion, opening and
// closing of a region as sub/super-level sets of distance fields, and level-set curves of a field.
#ifndef CGAL_ISOPHOTIC_METRIC_CONTINUOUS_LEVEL_SET_MORPHOLOGY_H
#define CGAL_ISOPHOTIC_METRIC_CONTINUOUS_LEVEL_SET_MORPHOLOGY_H

#include <CGAL/Isophotic_metric/Continuous/Fast_sweeping_2.h>
#include <CGAL/Isophotic_metric/exceptions.h>

#include <Eigen/Dense>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

namespace internal {

template <typename Solver>
void check_region(const Solver& solver, const std::vector<char>& region, double radius, const char* operation)
{
  if(region.size() != solver.grid().size())
    throw Invalid_parameter_error(std::string(operation) + ": region mask of size " + std::to_string(region.size())
                                  + " for a grid of " + std::to_string(solver.grid().size()) + " nodes");
  if(!std::isfinite(radius) || radius < 0.)
    throw Invalid_parameter_error(std::string(operation) + ": radius " + std::to_string(radius)
                                  + " must be finite and >= 0");
}

} // namespace internal

/// \ingroup PkgIsophoticMetricContinuousRef
/// Dilation of `region` (mask over the grid nodes) by a geodesic disc of radius `radius` in the
/// solver's metric: the nodes whose distance to the region is at most `radius`.
/// (The `_grid_mask` operators work on node masks of a grid; the `_face_selection` ones on meshes.)
/// \tparam GridDistanceSolver a model of `GridDistanceSolver`
/// \throws Invalid_parameter_error on a mask of the wrong size or a negative radius
template <typename GridDistanceSolver>
std::vector<char> dilate_grid_mask(const GridDistanceSolver& solver, const std::vector<char>& region, double radius)
{
  internal::check_region(solver, region, radius, "dilate_grid_mask");
  const std::vector<char> domain = solver.domain();
  bool empty = true;
  for(std::size_t n = 0; n < region.size(); ++n) empty = empty && !(region[n] && domain[n]);
  if(empty) return std::vector<char>(region.size(), 0);
  const auto field = solver.distance_field({}, region);
  std::vector<char> result(region.size(), 0);
  for(std::size_t n = 0; n < region.size(); ++n) result[n] = domain[n] && field.distance[n] <= radius;
  return result;
}

/// \ingroup PkgIsophoticMetricContinuousRef
/// Erosion: the dilation of the background, complemented (within the solver's domain).
template <typename GridDistanceSolver>
std::vector<char> erode_grid_mask(const GridDistanceSolver& solver, const std::vector<char>& region, double radius)
{
  internal::check_region(solver, region, radius, "erode_grid_mask");
  const std::vector<char> domain = solver.domain();
  std::vector<char> background(region.size(), 0);
  for(std::size_t n = 0; n < region.size(); ++n) background[n] = domain[n] && !region[n];
  const std::vector<char> grown = dilate_grid_mask(solver, background, radius);
  std::vector<char> result(region.size(), 0);
  for(std::size_t n = 0; n < region.size(); ++n) result[n] = domain[n] && region[n] && !grown[n];
  return result;
}

/// \ingroup PkgIsophoticMetricContinuousRef
/// Closing: dilation with `dilation_solver`, then erosion with `erosion_solver` (the two may use
/// different metrics, e.g. a Euclidean dilation followed by an isophotic erosion, Fig. 5 of the paper).
template <typename DilationSolver, typename ErosionSolver>
std::vector<char> close_grid_mask(const DilationSolver& dilation_solver, const ErosionSolver& erosion_solver,
                        const std::vector<char>& region, double dilation_radius, double erosion_radius)
{
  return erode_grid_mask(erosion_solver, dilate_grid_mask(dilation_solver, region, dilation_radius), erosion_radius);
}

/// \ingroup PkgIsophoticMetricContinuousRef
/// Opening: erosion with `erosion_solver`, then dilation with `dilation_solver`.
template <typename ErosionSolver, typename DilationSolver>
std::vector<char> open_grid_mask(const ErosionSolver& erosion_solver, const DilationSolver& dilation_solver,
                       const std::vector<char>& region, double erosion_radius, double dilation_radius)
{
  return dilate_grid_mask(dilation_solver, erode_grid_mask(erosion_solver, region, erosion_radius), dilation_radius);
}

/// \ingroup PkgIsophoticMetricContinuousRef
/// The level set `d = value` of a 2D distance field as segments in the parameter domain
/// (marching squares; each cell is split into two triangles so that the pieces are unambiguous).
inline std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>
level_set_segments(const Distance_field_2& field, double value)
{
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> segments;
  const Grid_2& g = field.grid;
  auto crossing = [&](int i0, int j0, int i1, int j1) {
    const double a = field.at(i0, j0) - value, b = field.at(i1, j1) - value;
    const double t = a / (a - b);
    return Eigen::Vector2d((1 - t) * g.node(i0, j0) + t * g.node(i1, j1));
  };
  for(int j = 0; j + 1 < g.nv(); ++j)
    for(int i = 0; i + 1 < g.nu(); ++i)
    {
      const int triangles[2][3][2] = {{{i, j}, {i + 1, j}, {i + 1, j + 1}}, {{i, j}, {i + 1, j + 1}, {i, j + 1}}};
      for(const auto& t : triangles)
      {
        std::vector<Eigen::Vector2d> points;
        for(int e = 0; e < 3; ++e)
        {
          const int* p = t[e];
          const int* q = t[(e + 1) % 3];
          const double a = field.at(p[0], p[1]), b = field.at(q[0], q[1]);
          if(!std::isfinite(a) || !std::isfinite(b)) continue;
          if((a < value) != (b < value)) points.push_back(crossing(p[0], p[1], q[0], q[1]));
        }
        if(points.size() == 2) segments.emplace_back(points[0], points[1]);
      }
    }
  return segments;
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_CONTINUOUS_LEVEL_SET_MORPHOLOGY_H
