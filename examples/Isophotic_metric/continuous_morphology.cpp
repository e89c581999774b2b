// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Continuous morphology on a parametric surface with a feature (Fig. 4 and 5 of Pottmann et al. 2004).
//  - continuous_level_sets.ply: level sets of the distance to a region, Euclidean (left copy) and
//    isophotic (right copy): the isophotic ones accumulate at the ridge.
//  - continuous_closing.ply: a broken thin region along the ridge (left), closed by a Euclidean
//    dilation followed by an erosion with a high isophotic part (right).
#include <CGAL/Isophotic_metric/Continuous/Parametric_surface_distance.h>
#include <CGAL/Isophotic_metric/Continuous/level_set_morphology.h>

#include "continuous_output.h"

#include <cmath>
#include <iostream>

namespace IM = CGAL::Isophotic_metric;
using Eigen::Vector2d;
using Eigen::Vector3d;

struct Ridge
{
  static double crest(double u) { return 0.3 * std::sin(2.5 * u); }
  Vector3d point(double u, double v) const
  {
    const double a = v - crest(u);
    return {u, v, 0.22 * std::exp(-a * a / 0.02)};
  }
};

// The grid as a triangle mesh, shifted by `offset`, coloured per node.
void add_surface(continuous_output::Coloured_mesh& mesh, const Ridge& surface, const IM::Grid_2& grid,
                 const Vector3d& offset, const std::vector<continuous_output::Colour>& colours)
{
  const int base = int(mesh.points.size());
  for(int j = 0; j < grid.nv(); ++j)
    for(int i = 0; i < grid.nu(); ++i)
      mesh.add_point(surface.point(grid.node(i, j).x(), grid.node(i, j).y()) + offset, colours[grid.index(i, j)]);
  for(int j = 0; j + 1 < grid.nv(); ++j)
    for(int i = 0; i + 1 < grid.nu(); ++i)
    {
      const int a = base + int(grid.index(i, j)), b = base + int(grid.index(i + 1, j)),
                c = base + int(grid.index(i + 1, j + 1)), d = base + int(grid.index(i, j + 1));
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
    }
}

int main()
{
  const Ridge surface;
  const IM::Grid_2 grid(-1., 1., -1., 1., 161, 161);

  //! [level_sets]
  // Region: a disc in the parameter plane just below the ridge.
  std::vector<char> region(grid.size(), 0);
  for(int j = 0; j < grid.nv(); ++j)
    for(int i = 0; i < grid.nu(); ++i)
      region[grid.index(i, j)] = (grid.node(i, j) - Vector2d(-0.3, -0.55)).norm() < 0.15;

  const IM::Parametric_surface_distance<Ridge> euclidean(surface, grid,
    IM::parameters::euclidean_weight(1.).isophotic_weight(0.));
  const IM::Parametric_surface_distance<Ridge> isophotic(surface, grid,
    IM::parameters::euclidean_weight(1.).isophotic_weight(0.5));
  const IM::Distance_field_2 d_euclidean = euclidean.distance_field({}, region);
  const IM::Distance_field_2 d_isophotic = isophotic.distance_field({}, region);
  // The boundary of the dilation by r is the level set d = r:
  const auto boundary = IM::level_set_segments(d_isophotic, 0.4);
  //! [level_sets]
  std::cout << "level set d = 0.4 (isophotic): " << boundary.size() << " segments\n";

  continuous_output::Coloured_mesh level_sets;
  auto colour_field = [&](const IM::Distance_field_2& f) {
    std::vector<continuous_output::Colour> c(grid.size());
    for(std::size_t n = 0; n < grid.size(); ++n)
      c[n] = region[n] ? continuous_output::Colour{20, 20, 20} : continuous_output::distance_colour(f.distance[n], 1.6, 0.1);
    return c;
  };
  add_surface(level_sets, surface, grid, Vector3d(-1.1, 0., 0.), colour_field(d_euclidean));
  add_surface(level_sets, surface, grid, Vector3d(1.1, 0., 0.), colour_field(d_isophotic));
  if(!level_sets.write_ply("continuous_level_sets.ply")) return 1;

  //! [closing]
  // A thin, interrupted region along the crest of the ridge.
  std::vector<char> broken(grid.size(), 0);
  for(int j = 0; j < grid.nv(); ++j)
    for(int i = 0; i < grid.nu(); ++i)
    {
      const Vector2d p = grid.node(i, j);
      const bool on_crest = std::abs(p.y() - Ridge::crest(p.x())) < 0.04 && std::abs(p.x()) < 0.8;
      const bool in_gap = std::abs(std::fmod(p.x() + 2., 0.4) - 0.2) < 0.06;
      broken[grid.index(i, j)] = on_crest && !in_gap;
    }
  // Euclidean dilation fills the gaps (and widens the region across the ridge) ...
  const IM::Parametric_surface_distance<Ridge> mostly_isophotic(surface, grid,
    IM::parameters::euclidean_weight(0.05).isophotic_weight(1.));
  // ... the erosion with a high isophotic part removes what crossed the feature, not the gaps' fill.
  const std::vector<char> closed = IM::close_grid_mask(euclidean, mostly_isophotic, broken, 0.12, 0.12);
  //! [closing]
  std::size_t before = 0, after = 0;
  for(std::size_t n = 0; n < grid.size(); ++n) { before += broken[n]; after += closed[n]; }
  std::cout << "closing: " << before << " -> " << after << " nodes\n";
  if(after < before) return 1; // a closing never shrinks a region

  continuous_output::Coloured_mesh closing;
  std::vector<continuous_output::Colour> c_before(grid.size()), c_after(grid.size());
  for(std::size_t n = 0; n < grid.size(); ++n)
  {
    c_before[n] = broken[n] ? continuous_output::Colour{20, 20, 20} : continuous_output::Colour{235, 235, 225};
    c_after[n] = closed[n] ? continuous_output::Colour{20, 20, 20} : continuous_output::Colour{235, 235, 225};
  }
  add_surface(closing, surface, grid, Vector3d(-1.1, 0., 0.), c_before);
  add_surface(closing, surface, grid, Vector3d(1.1, 0., 0.), c_after);
  if(!closing.write_ply("continuous_closing.ply")) return 1;
  std::cout << "wrote continuous_level_sets.ply and continuous_closing.ply\n";
  return 0;
}
