// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Cross-check of the two sides of the package on one surface: the fast-sweeping distance field of a
// parametric surface against the exact polyhedral geodesics (R^6-lifted mesh) of a tessellation of
// it with exact normals.  Both converge to the same smooth distance, so their difference must
// shrink as both resolutions grow.
#include <CGAL/Isophotic_metric/Geodesics/Geodesic_solver.h>
#include <CGAL/Isophotic_metric/Continuous/Parametric_surface_distance.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

namespace IM = CGAL::Isophotic_metric;
using Eigen::Vector2d;
using Eigen::Vector3d;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;

namespace {

// A smooth bump: curvature of both signs, so the isophotic part matters everywhere but at the rim.
struct Bump
{
  Vector3d point(double u, double v) const { return {u, v, 0.35 * std::exp(-(u * u + v * v) / 0.25)}; }
};

// Normalised max difference over the mesh vertices between the mesh engine's distances and the
// fast-sweeping field of an n_fs x n_fs grid, for an n x n tessellation of [-1,1]^2.
double difference(int n, int n_fs, double w, double w_prime)
{
  const Bump bump;
  Mesh mesh;
  std::vector<vertex_descriptor> node(n * n);
  std::vector<Vector2d> uv(n * n);
  auto normals = mesh.add_property_map<vertex_descriptor, K::Vector_3>("v:exact_normal").first;
  for(int j = 0; j < n; ++j)
    for(int i = 0; i < n; ++i)
    {
      uv[i + n * j] = Vector2d(-1. + 2. * i / (n - 1), -1. + 2. * j / (n - 1));
      const IM::Surface_differentials sd = IM::surface_differentials(bump, uv[i + n * j].x(), uv[i + n * j].y());
      node[i + n * j] = mesh.add_vertex(K::Point_3(sd.point.x(), sd.point.y(), sd.point.z()));
      normals[node[i + n * j]] = K::Vector_3(sd.normal.x(), sd.normal.y(), sd.normal.z());
    }
  for(int j = 0; j + 1 < n; ++j)
    for(int i = 0; i + 1 < n; ++i)
    {
      const vertex_descriptor a = node[i + n * j], b = node[i + 1 + n * j], c = node[i + 1 + n * (j + 1)],
                              d = node[i + n * (j + 1)];
      // Alternate the diagonals so the tessellation has no preferred direction.
      if((i + j) % 2 == 0) { mesh.add_face(a, b, c); mesh.add_face(a, c, d); }
      else { mesh.add_face(a, b, d); mesh.add_face(b, c, d); }
    }
  // Source at parameter (-0.6, -0.4): a vertex of every tessellation used below.
  const Vector2d source(-0.6, -0.4);
  const int si = int(std::lround((source.x() + 1.) * (n - 1) / 2.)), sj = int(std::lround((source.y() + 1.) * (n - 1) / 2.));
  IM::Geodesic_solver<Mesh> exact(mesh, IM::parameters::euclidean_weight(w).isophotic_weight(w_prime).weight_length_scale(1).vertex_normal_map(normals));
  exact.add_source(node[si + n * sj]);
  exact.propagate();

  const IM::Grid_2 grid(-1., 1., -1., 1., n_fs, n_fs);
  const IM::Distance_field_2 field = IM::parametric_distance_field(
    bump, grid, {source}, IM::parameters::euclidean_weight(w).isophotic_weight(w_prime));
  double max_difference = 0., max_distance = 0.;
  for(int k = 0; k < n * n; ++k)
  {
    const double d = exact.distance(node[k]);
    max_difference = std::max(max_difference, std::abs(d - field.interpolate(uv[k])));
    max_distance = std::max(max_distance, d);
  }
  return max_difference / max_distance;
}

} // namespace

TEST(ContinuousVsMesh, FastSweepingAndExactMeshGeodesicsConverge)
{
  for(const double w_prime : {0., 0.2})
  {
    std::vector<double> differences;
    for(const auto& [n, n_fs] : {std::pair<int, int>(11, 81), {21, 161}, {41, 321}})
    {
      differences.push_back(difference(n, n_fs, 1., w_prime));
      std::cout << "w' = " << w_prime << ", mesh " << n << "^2, grid " << n_fs << "^2: max difference "
                << 100. * differences.back() << " % of the max distance\n";
    }
    // Both errors are first order: the difference must shrink clearly at every refinement.
    for(std::size_t k = 1; k < differences.size(); ++k)
      EXPECT_LT(differences[k], 0.75 * differences[k - 1]) << "w' = " << w_prime << ", refinement " << k;
    EXPECT_LT(differences.back(), 0.01) << "w' = " << w_prime;
  }
}
