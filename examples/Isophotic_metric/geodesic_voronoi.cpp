// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Geodesic Voronoi partition of a CAD part from a few seed vertices, in the Euclidean metric and in
// the isophotic metric (w = w' = 0.5, length scale = bounding-box diagonal). Isophotic cells stop at
// fillets and sharp edges, which are expensive to cross, and spread along the patches of the part.
// The labels are checked against the single-seed distance fields, computed in parallel.
// Writes <name>_voronoi.ply: Euclidean partition left, isophotic right, one colour per cell
// (per-face colours), seeds in black.
//
// Usage: geodesic_voronoi [mesh.off]   (default: CGAL's fandisk)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Isophotic_metric.h>

#include "example_output.h" // PLY files, colours, picking

#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
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

// The label of every face (nearest seed of its centroid) and checks the vertex labels against
// the seeds' own distance fields. Returns false if a label is not the nearest seed.
template <class NamedParameters>
bool voronoi_labels(const Mesh& mesh, const std::vector<vertex_descriptor>& seeds, const NamedParameters& metric,
                    std::vector<std::size_t>& face_label)
{
  /// [voronoi]
  // All seeds in one propagation: every vertex and surface point gets its distance to the
  // nearest seed and that seed's label (0, 1, ... in the order the seeds were added).
  Solver solver(mesh, metric);
  for(vertex_descriptor s : seeds)
    solver.add_source(s);
  solver.propagate();
  face_label.assign(num_faces(mesh), Solver::no_source);
  for(face_descriptor f : faces(mesh))
    face_label[f] = solver.nearest_source(Solver::Face_location(f, {{1. / 3, 1. / 3, 1. / 3}}));
  /// [voronoi]

  /// [batch]
  // One distance field per seed, in parallel when TBB is available; the callback of field i
  // writes to column i only.
  std::vector<std::vector<double>> d(seeds.size(), std::vector<double>(num_vertices(mesh)));
  IM::for_each_geodesic_distance_field(seeds, mesh, [&](std::size_t i, const Solver& field) {
    for(vertex_descriptor v : vertices(mesh))
      d[i][v] = field.distance(v);
  }, metric);
  /// [batch]

  for(vertex_descriptor v : vertices(mesh))
  {
    double nearest = std::numeric_limits<double>::infinity();
    for(std::size_t i = 0; i < seeds.size(); ++i)
      nearest = std::min(nearest, d[i][v]);
    const std::size_t label = solver.nearest_source(v);
    if(label == Solver::no_source || d[label][v] > nearest * (1 + 1e-9) ||
       std::abs(solver.distance(v) - nearest) > 1e-9 * nearest)
    {
      std::cerr << "vertex " << v << ": label " << label << " is not its nearest seed" << std::endl;
      return false;
    }
  }
  return true;
}

int main(int argc, char* argv[])
{
  const std::string filename = (argc > 1) ? argv[1] : CGAL::data_file_path("meshes/fandisk.off");
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(filename, mesh) || is_empty(mesh))
  {
    std::cerr << "Cannot read " << filename << std::endl;
    return 1;
  }
  if(mesh.has_garbage())
    mesh.collect_garbage(); // the labels are indexed by face and vertex index
  // Seeds at fixed places of the bounding box (their nearest vertices).
  std::vector<vertex_descriptor> seeds;
  for(const std::array<double, 3>& where : std::vector<std::array<double, 3>>{
        {0.7, 0.5, 0.15}, {0.9, 0.5, 0.55}, {0.6, 0.5, 0.8}, {0.2, 1, 0.6}, {0.3, 0.5, 1}, {0.5, 0, 0.5}, {0.1, 0.5, 0.7}})
  {
    const vertex_descriptor v = vertex_near(mesh, where);
    if(std::find(seeds.begin(), seeds.end(), v) == seeds.end())
      seeds.push_back(v);
  }

  try
  {
    const double L = IM::suggested_weight_length_scale(mesh);
    std::vector<std::size_t> euclidean_label, isophotic_label;
    if(!voronoi_labels(mesh, seeds, IM::parameters::isophotic_weight(0), euclidean_label) ||
       !voronoi_labels(mesh, seeds,
                       IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L),
                       isophotic_label))
      return 1;

    std::size_t changed = 0;
    for(face_descriptor f : faces(mesh))
      if(euclidean_label[f] != isophotic_label[f])
        ++changed;
    std::cout << seeds.size() << " seeds; " << changed << " of " << num_faces(mesh)
              << " faces change cell from the Euclidean to the isophotic metric" << std::endl;

    const Vector shift = side_by_side_shift(mesh, oblique_view_horizontal, 1.1);
    Coloured_soup soup;
    auto no_vertex_colour = [](vertex_descriptor) { return Colour{0, 0, 0}; };
    soup.add_mesh(mesh, Vector(0, 0, 0), no_vertex_colour, [&](face_descriptor f) { return label_colour(euclidean_label[f]); });
    soup.add_mesh(mesh, shift, no_vertex_colour, [&](face_descriptor f) { return label_colour(isophotic_label[f]); });
    for(vertex_descriptor s : seeds)
    {
      soup.add_marker(mesh.point(s), 0.008 * L, Colour{10, 10, 10});
      soup.add_marker(mesh.point(s) + shift, 0.008 * L, Colour{10, 10, 10});
    }
    const std::string output = stem(filename) + "_voronoi.ply";
    if(!soup.write_ply(output, Colours_on::faces))
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
