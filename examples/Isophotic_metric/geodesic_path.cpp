// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Shortest paths between the same two points of a CAD part in the Euclidean metric and in the
// isophotic metric (w = w' = 0.5, length scale = bounding-box diagonal). The Euclidean path cuts
// diagonally across a fillet; the isophotic one crosses it as briefly as it can and otherwise runs
// along it (Fig. 3 of Pottmann et al., here on a mesh). Prints the length of each path in both metrics and checks that
// each path is the shorter one in its own metric and that its length is the computed distance.
// Writes <name>_paths.ply: the surface in grey, the Euclidean path in blue, the isophotic one in
// orange, the end points in red (per-vertex colours).
//
// Usage: geodesic_path [mesh.off]   (default: CGAL's fandisk)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Isophotic_metric.h>

#include "example_output.h" // PLY files, colours, picking

#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
typedef boost::graph_traits<Mesh>::face_descriptor face_descriptor;
namespace IM = CGAL::Isophotic_metric;
using namespace example_output;
typedef IM::Geodesic_solver<Mesh> Solver;

int main(int argc, char* argv[])
{
  const std::string filename = (argc > 1) ? argv[1] : CGAL::data_file_path("meshes/fandisk.off");
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(filename, mesh) || is_empty(mesh))
  {
    std::cerr << "Cannot read " << filename << std::endl;
    return 1;
  }
  // On fandisk, two points on either side of the fillet below its upper curved band.
  const vertex_descriptor a = vertex_near(mesh, {0.6, 0.5, 0.75}), b = vertex_near(mesh, {1, 0.5, 0.75});
  const double L = IM::suggested_weight_length_scale(mesh);

  try
  {
    const auto euclidean = IM::parameters::euclidean_weight(1).isophotic_weight(0);
    const auto isophotic = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);

    /// [path]
    // Propagate from `a` (windows are stored by default), then trace back from `b`:
    // the path comes as surface points (face + barycentric coordinates), `b` first.
    Solver solver(mesh, isophotic);
    solver.add_source(a);
    solver.propagate();
    std::vector<Solver::Face_location> isophotic_path;
    solver.trace_path(solver.location(b), std::back_inserter(isophotic_path));
    const double isophotic_distance = solver.distance(b);
    /// [path]

    /// [one-shot path]
    // The same as one call, returning 3D points from `a` to `b` and the length.
    std::vector<Point> euclidean_points;
    const double euclidean_distance = IM::compute_geodesic_path(a, b, mesh, std::back_inserter(euclidean_points),
                                                                euclidean);
    /// [one-shot path]

    // Face locations of the Euclidean path too, to measure it in the isophotic metric.
    Solver euclidean_solver(mesh, euclidean);
    euclidean_solver.add_source(a);
    euclidean_solver.propagate();
    std::vector<Solver::Face_location> euclidean_path;
    euclidean_solver.trace_path(euclidean_solver.location(b), std::back_inserter(euclidean_path));
    std::vector<Point> isophotic_points;
    solver.trace_path_points(solver.location(b), std::back_inserter(isophotic_points));

    /// [lengths]
    // Lengths of polylines on the surface, in either metric, through the lifted embeddings.
    auto lifted_euclidean = get(CGAL::dynamic_vertex_property_t<IM::Lifted_point>(), mesh);
    auto lifted_isophotic = get(CGAL::dynamic_vertex_property_t<IM::Lifted_point>(), mesh);
    IM::compute_lifted_embedding(mesh, lifted_euclidean, euclidean);
    IM::compute_lifted_embedding(mesh, lifted_isophotic, isophotic);
    const double e_of_e = IM::polyline_isophotic_length(euclidean_path, mesh, lifted_euclidean);
    const double i_of_e = IM::polyline_isophotic_length(euclidean_path, mesh, lifted_isophotic);
    const double e_of_i = IM::polyline_isophotic_length(isophotic_path, mesh, lifted_euclidean);
    const double i_of_i = IM::polyline_isophotic_length(isophotic_path, mesh, lifted_isophotic);
    /// [lengths]

    std::cout << "                 Euclidean length   isophotic length\n"
              << "Euclidean path   " << e_of_e << "           " << i_of_e << "\n"
              << "isophotic path   " << e_of_i << "           " << i_of_i << std::endl;

    // Each path has the computed distance as length, and is the shorter one in its own metric.
    const double tolerance = 1e-9;
    if(std::abs(e_of_e - euclidean_distance) > tolerance * euclidean_distance ||
       std::abs(i_of_i - isophotic_distance) > tolerance * isophotic_distance)
    {
      std::cerr << "a path length differs from the distance" << std::endl;
      return 1;
    }
    if(e_of_e > e_of_i * (1 + tolerance) || i_of_i > i_of_e * (1 + tolerance))
    {
      std::cerr << "a path is longer than the other one in its own metric" << std::endl;
      return 1;
    }
    if(euclidean_points.front() != mesh.point(a) || euclidean_points.back() != mesh.point(b))
    {
      std::cerr << "the one-shot path does not join the end points" << std::endl;
      return 1;
    }

    Coloured_soup soup;
    soup.add_mesh(mesh, Vector(0, 0, 0), [](vertex_descriptor) { return Colour{215, 217, 222}; },
                  [](face_descriptor) { return Colour{0, 0, 0}; });
    const double r = 0.003 * L;
    soup.add_tube(euclidean_points, r, Colour{40, 110, 220});
    soup.add_tube(isophotic_points, r, Colour{245, 140, 20});
    soup.add_marker(mesh.point(a), 3 * r, Colour{200, 20, 30});
    soup.add_marker(mesh.point(b), 3 * r, Colour{200, 20, 30});
    const std::string output = stem(filename) + "_paths.ply";
    if(!soup.write_ply(output, Colours_on::vertices))
    {
      std::cerr << "Cannot write " << output << std::endl;
      return 1;
    }
    std::cout << "wrote " << output << std::endl;
  }
  catch(const IM::Error& e)
  {
    std::cerr << e.what() << std::endl;
    return 1;
  }
  return 0;
}
