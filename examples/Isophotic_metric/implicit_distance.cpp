// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Isophotic distance fields on implicit surfaces (Sect. 2.2 of Pottmann et al. 2004):
//  - implicit_torus.ply: an analytic torus, distance from a point on its outer equator,
//    Euclidean (left, w = 1, w' = 0) and isophotic (right, w = 1, w' = 0.5);
//  - implicit_kitten.ply: CGAL's kitten point cloud, surface = zero set of the signed distance to
//    the oriented points, Euclidean (left) and isophotic (right) distance from one point.
// Each surface is the zero level set of the function, meshed by marching tetrahedra and coloured by
// distance with dark bands at regular distances: the bands are the level sets (geodesic circles).
#include <CGAL/Isophotic_metric/Continuous/Implicit_surface_distance.h>
#include <CGAL/Isophotic_metric/Continuous/signed_distance_grid.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/read_points.h>
#include <CGAL/property_map.h>

#include "continuous_output.h"

#include <cmath>
#include <iostream>
#include <utility>
#include <vector>

namespace IM = CGAL::Isophotic_metric;
using Eigen::Vector3d;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

//! [torus]
// Signed distance to a torus around the z axis (radii R and r): a model of ImplicitFunction
// (only the value: gradient and Hessian come from finite differences).
struct Torus
{
  double R = 1., r = 0.4;
  double operator()(const Vector3d& x) const { return std::hypot(std::hypot(x.x(), x.y()) - R, x.z()) - r; }
};
//! [torus]

// Both distance fields on the zero set of `values`, side by side (the isophotic copy shifted by `shift`).
void write_pair(const std::string& file, const IM::Grid_3& grid, const std::vector<double>& values,
                const IM::Distance_field_3& euclidean, const IM::Distance_field_3& isophotic, const Vector3d& shift,
                int bands, const Vector3d& source, double marker)
{
  continuous_output::Coloured_mesh mesh;
  for(const auto* field : {&euclidean, &isophotic})
  {
    double d_max = 0.;
    for(double d : field->distance)
      if(std::isfinite(d)) d_max = std::max(d_max, d);
    const Vector3d offset = field == &euclidean ? Vector3d::Zero() : shift;
    const std::size_t first = mesh.points.size();
    continuous_output::add_zero_level_set(mesh, values, grid.origin(), grid.h(), grid.nx(), grid.ny(), grid.nz(),
      [&](const Vector3d& p) { return continuous_output::banded_colour(field->interpolate(p), d_max, d_max / bands); });
    for(std::size_t v = first; v < mesh.points.size(); ++v) mesh.points[v] += offset;
    mesh.add_marker(source + offset, marker, {20, 20, 20});
  }
  if(!mesh.write_ply(file)) throw std::runtime_error("cannot write " + file);
  std::cout << "wrote " << file << " (" << mesh.triangles.size() << " triangles)\n";
}

int main()
{
  // ---- Analytic implicit surface ------------------------------------------------------------
  //! [torus_distance]
  const Torus torus;
  const IM::Grid_3 grid = IM::Grid_3::covering(Vector3d(-1.5, -1.5, -0.5), Vector3d(1.5, 1.5, 0.5), 0.04);
  const IM::Implicit_surface_distance euclidean(torus, grid, IM::parameters::euclidean_weight(1.).isophotic_weight(0.));
  const IM::Implicit_surface_distance isophotic(torus, grid, IM::parameters::euclidean_weight(1.).isophotic_weight(0.5));
  const Vector3d source(1.4, 0., 0.); // on the outer equator
  const IM::Distance_field_3 d_euclidean = euclidean.distance_field({source});
  const IM::Distance_field_3 d_isophotic = isophotic.distance_field({source});
  //! [torus_distance]
  std::cout << "torus: " << isophotic.band_size() << " band nodes of " << grid.size() << "\n";

  std::vector<double> torus_values(grid.size());
  for(int k = 0; k < grid.nz(); ++k)
    for(int j = 0; j < grid.ny(); ++j)
      for(int i = 0; i < grid.nx(); ++i) torus_values[grid.index(i, j, k)] = torus(grid.node(i, j, k));
  write_pair("implicit_torus.ply", grid, torus_values, d_euclidean, d_isophotic, Vector3d(3.3, 0., 0.), 12, source, 0.06);

  // ---- Point cloud ----------------------------------------------------------------------------
  //! [point_cloud]
  using Point_with_normal = std::pair<K::Point_3, K::Vector_3>;
  std::vector<Point_with_normal> points;
  if(!CGAL::IO::read_points(CGAL::data_file_path("points_3/kitten.xyz"), std::back_inserter(points),
                            CGAL::parameters::point_map(CGAL::First_of_pair_property_map<Point_with_normal>())
                              .normal_map(CGAL::Second_of_pair_property_map<Point_with_normal>())))
  {
    std::cerr << "cannot read kitten.xyz\n";
    return 1;
  }
  // The file's normals are consistently oriented; make them point outwards (away from the centroid on average).
  Vector3d centroid = Vector3d::Zero();
  for(const auto& [p, n] : points) centroid += Vector3d(p.x(), p.y(), p.z()) / double(points.size());
  double outward = 0.;
  for(const auto& [p, n] : points) outward += (Vector3d(p.x(), p.y(), p.z()) - centroid).dot(Vector3d(n.x(), n.y(), n.z()));
  if(outward < 0.)
    for(auto& pn : points) pn.second = -pn.second;

  // A grid of ~70 cells along the longest side of the bounding box, with a margin.
  const CGAL::Bbox_3 box = CGAL::bbox_3(CGAL::make_transform_iterator_from_property_map(points.begin(),
                                          CGAL::First_of_pair_property_map<Point_with_normal>()),
                                        CGAL::make_transform_iterator_from_property_map(points.end(),
                                          CGAL::First_of_pair_property_map<Point_with_normal>()));
  const Vector3d lo(box.xmin(), box.ymin(), box.zmin()), hi(box.xmax(), box.ymax(), box.zmax());
  const double size = (hi - lo).maxCoeff(), h = size / 70.;
  const IM::Grid_3 cloud_grid = IM::Grid_3::covering(lo - Vector3d::Constant(4 * h), hi + Vector3d::Constant(4 * h), h);
  const IM::Sampled_function_3 sdf = IM::signed_distance_to_oriented_points<K>(points, cloud_grid, 16);

  // Weights independent of the model's scale: w' is a squared length, the size of the model.
  const double w_prime = 0.02 * size * size;
  const IM::Implicit_surface_distance cloud_euclidean(sdf, IM::parameters::euclidean_weight(1.).isophotic_weight(0.));
  const IM::Implicit_surface_distance cloud_isophotic(sdf, IM::parameters::euclidean_weight(1.).isophotic_weight(w_prime));
  const K::Point_3& s = points.front().first;
  const Vector3d cloud_source(s.x(), s.y(), s.z());
  const IM::Distance_field_3 c_euclidean = cloud_euclidean.distance_field({cloud_source});
  const IM::Distance_field_3 c_isophotic = cloud_isophotic.distance_field({cloud_source});
  //! [point_cloud]
  std::cout << "kitten: " << points.size() << " points, grid " << cloud_grid.nx() << " x " << cloud_grid.ny() << " x "
            << cloud_grid.nz() << ", " << cloud_isophotic.band_size() << " band nodes\n";
  write_pair("implicit_kitten.ply", cloud_grid, sdf.values(), c_euclidean, c_isophotic,
             Vector3d(1.15 * (hi - lo).x(), 0., 0.), 12, cloud_source, 0.02 * size);
  return 0;
}
