// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Geodesic curves on a parametric surface with features (Fig. 3 of Pottmann et al. 2004):
// each pair of points is joined by a Euclidean geodesic (w = 1, w' = 0, light) and an isophotic
// geodesic (w = 1, w' = 2, dark), which follows the smooth ridges of the surface.
// Writes parametric_geodesics.ply (per-vertex colours).
#include <CGAL/Isophotic_metric/Continuous/Parametric_surface_distance.h>

#include "continuous_output.h"

#include <cmath>
#include <iostream>

namespace IM = CGAL::Isophotic_metric;
using Eigen::Vector2d;
using Eigen::Vector3d;

//! [ridge_surface]
// A height field over [-1,1]^2 with two smooth ridges (blends): a sinuous one along u and a
// straight one along v.  Only point() is given: derivatives come from finite differences.
struct Ridged_surface
{
  static double crest(double u) { return 0.3 * std::sin(2.5 * u); }
  Vector3d point(double u, double v) const
  {
    const double a = v - crest(u), b = u - 0.45;
    return {u, v, 0.22 * std::exp(-a * a / 0.02) + 0.18 * std::exp(-b * b / 0.015)};
  }
};
//! [ridge_surface]

int main()
{
  const Ridged_surface surface;
  const IM::Grid_2 grid(-1., 1., -1., 1., 201, 201);

  //! [geodesics]
  // One solver per metric: the metric field is evaluated once, then reused for every pair.
  const IM::Parametric_surface_distance<Ridged_surface> euclidean(
    surface, grid, IM::parameters::euclidean_weight(1.).isophotic_weight(0.));
  const IM::Parametric_surface_distance<Ridged_surface> isophotic(
    surface, grid, IM::parameters::euclidean_weight(1.).isophotic_weight(2.));

  const std::vector<std::pair<Vector2d, Vector2d>> pairs = {
    {{-0.85, Ridged_surface::crest(-0.85)}, {0.25, Ridged_surface::crest(0.25)}},
    {{0.45, -0.85}, {0.45, 0.8}},
    {{-0.5, Ridged_surface::crest(-0.5)}, {0.45, -0.6}}};
  //! [geodesics]

  continuous_output::Coloured_mesh mesh;
  for(int j = 0; j < grid.nv(); ++j)
    for(int i = 0; i < grid.nu(); ++i)
      mesh.add_point(surface.point(grid.node(i, j).x(), grid.node(i, j).y()), {200, 200, 195});
  for(int j = 0; j + 1 < grid.nv(); ++j)
    for(int i = 0; i + 1 < grid.nu(); ++i)
    {
      const int a = int(grid.index(i, j)), b = int(grid.index(i + 1, j)), c = int(grid.index(i + 1, j + 1)),
                d = int(grid.index(i, j + 1));
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
    }

  for(const auto& [from, to] : pairs)
  {
    //! [trace]
    const IM::Parametric_geodesic e = euclidean.geodesic(from, to);
    const IM::Parametric_geodesic g = isophotic.geodesic(from, to);
    //! [trace]
    if(!e.reached_source || !g.reached_source)
    {
      std::cerr << "a geodesic did not reach its source: " << e.reached_source << g.reached_source << " "
                << (e.reached_source ? g : e).uv.back().transpose() << "\n";
      return 1;
    }
    std::cout << "pair (" << from.transpose() << ") -> (" << to.transpose() << "):\n"
              << "  Euclidean geodesic: distance " << e.distance << ", traced length " << e.length << "\n"
              << "  isophotic geodesic: distance " << g.distance << ", traced length " << g.length
              << ", Euclidean length " << IM::isophotic_length(surface, g.uv, 1., 0.) << "\n";
    mesh.add_tube(e.points, 0.008, {255, 200, 60});
    mesh.add_tube(g.points, 0.008, {150, 20, 20});
    mesh.add_marker(surface.point(from.x(), from.y()), 0.02, {20, 20, 20});
    mesh.add_marker(surface.point(to.x(), to.y()), 0.02, {20, 20, 20});
  }
  if(!mesh.write_ply("parametric_geodesics.ply")) return 1;
  std::cout << "wrote parametric_geodesics.ply\n";
  return 0;
}
