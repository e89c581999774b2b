// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Distance field from one source vertex on a CAD part, in the Euclidean metric and in the isophotic
// metric (w = w' = 0.5, length scale = bounding-box diagonal). Each field is drawn with level sets,
// spaced equally where the surface is flat: the Euclidean ones stay evenly spaced, the isophotic
// ones crowd on fillets and sharp edges, where the normal turns (Fig. 4 of Pottmann et al.).
// Writes <name>_distance_field.ply: Euclidean field left, isophotic right, per-vertex colours from
// yellow (near) to purple (far), dark level sets, red source.
//
// Usage: geodesic_distance_field [mesh.off]   (default: CGAL's fandisk)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Isophotic_metric.h>

#include "example_output.h" // PLY files, colours, picking

#include <CGAL/Real_timer.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
typedef boost::graph_traits<Mesh>::face_descriptor face_descriptor;
namespace IM = CGAL::Isophotic_metric;
using namespace example_output;

int main(int argc, char* argv[])
{
  const std::string filename = (argc > 1) ? argv[1] : CGAL::data_file_path("meshes/fandisk.off");
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(filename, mesh) || is_empty(mesh))
  {
    std::cerr << "Cannot read " << filename << std::endl;
    return 1;
  }
  const vertex_descriptor source = vertex_near(mesh, {0.7, 0.5, 0.15}); // on fandisk: its largest face
  CGAL::Real_timer timer;
  timer.start();

  try
  {
    /// [one-shot]
    // One source vertex, all vertex distances, in two metrics: the Euclidean geodesic distance
    // (w' = 0) and the isophotic one with dimensionless weights (see weight_length_scale).
    const double L = IM::suggested_weight_length_scale(mesh);
    const double w = 0.5, w_prime = 0.5;
    const auto isophotic = IM::parameters::euclidean_weight(w)
                                          .isophotic_weight(w_prime)
                                          .weight_length_scale(L);
    auto d_euclidean = mesh.add_property_map<vertex_descriptor, double>("v:d_euclidean").first;
    auto d_isophotic = mesh.add_property_map<vertex_descriptor, double>("v:d_isophotic").first;
    const vertex_descriptor sources[1] = {source};
    IM::compute_geodesic_distances(sources, mesh, d_euclidean, IM::parameters::isophotic_weight(0));
    IM::compute_geodesic_distances(sources, mesh, d_isophotic, isophotic);
    /// [one-shot]

    // The lifted mesh is at least sqrt(w) times longer than the surface everywhere, so is every path.
    double max_euclidean = 0, max_isophotic = 0;
    for(vertex_descriptor v : vertices(mesh))
    {
      if(!(d_isophotic[v] >= std::sqrt(w) * d_euclidean[v] * (1 - 1e-12)))
      {
        std::cerr << "isophotic distance below sqrt(w) times the Euclidean one at vertex " << v << std::endl;
        return 1;
      }
      max_euclidean = std::max(max_euclidean, d_euclidean[v]);
      max_isophotic = std::max(max_isophotic, d_isophotic[v]);
    }

    /// [threads]
    // The same field with the propagation on two threads (the distances do not depend on the number
    // of threads; worth it on meshes of a few hundred thousand faces, see the manual).
    auto d_threads = mesh.add_property_map<vertex_descriptor, double>("v:d_threads").first;
    IM::compute_geodesic_distances(sources, mesh, d_threads, isophotic.propagation_threads(2));
    /// [threads]
    for(vertex_descriptor v : vertices(mesh))
      if(d_threads[v] != d_isophotic[v])
      {
        std::cerr << "the propagation on two threads differs from the serial one at vertex " << v << std::endl;
        return 1;
      }

    /// [bounded]
    // A geodesic disc: the propagation stops at the radius, and costs what the disc covers.
    IM::Geodesic_solver<Mesh> solver(mesh, isophotic.store_windows(false));
    solver.add_source(source);
    const double radius = 0.25 * max_isophotic;
    solver.propagate(radius);
    std::size_t inside = 0;
    for(vertex_descriptor v : vertices(mesh))
      if(solver.distance(v) <= radius) // +infinity beyond the radius
        ++inside;
    /// [bounded]
    std::size_t expected_inside = 0;
    for(vertex_descriptor v : vertices(mesh))
    {
      if(d_isophotic[v] <= radius)
      {
        ++expected_inside;
        if(std::abs(solver.distance(v) - d_isophotic[v]) > 1e-9 * max_isophotic)
        {
          std::cerr << "bounded and full propagation differ at vertex " << v << std::endl;
          return 1;
        }
      }
    }
    if(inside != expected_inside)
    {
      std::cerr << inside << " vertices in the disc, expected " << expected_inside << std::endl;
      return 1;
    }
    /// [edge minimum]
    // Inside an edge the distance can dip below its value at both ends (where a geodesic arrives
    // perpendicularly); the exact minimum over an edge of a face, and where it is reached:
    IM::Geodesic_solver<Mesh> with_windows(mesh, isophotic); // keeps its windows for such queries
    with_windows.add_source(source);
    with_windows.propagate();
    typedef IM::Geodesic_solver<Mesh>::Face_location Face_location;
    std::size_t dipping_edges = 0, above_ends = 0;
    for(face_descriptor f : faces(mesh))
    {
      double t; // where, from the first corner, source(halfedge(f)), to the second
      const double minimum = with_windows.minimum_distance_on_segment(Face_location(f, {{1, 0, 0}}),
                                                                      Face_location(f, {{0, 1, 0}}), &t);
      const auto h = halfedge(f, mesh);
      const double at_ends = std::min(d_isophotic[mesh.source(h)], d_isophotic[mesh.target(h)]);
      if(minimum < at_ends - 1e-9 * max_isophotic)
        ++dipping_edges;
      if(minimum > at_ends + 1e-12 * max_isophotic) // cannot be: the ends belong to the edge
        ++above_ends;
    }
    /// [edge minimum]
    if(above_ends != 0)
    {
      std::cerr << above_ends << " edge minima above the values at the edge's ends" << std::endl;
      return 1;
    }
    /// [prepared mesh]
    // The set-up of a solver (validation, numbering, edge lengths) is a Metric_mesh: built once,
    // shared by every solver built from it. Its edge lengths may come from the user: here the
    // Euclidean ones, keyed by edge, which give back the Euclidean field.
    auto lengths = get(CGAL::dynamic_edge_property_t<double>(), mesh);
    for(auto e : edges(mesh))
      put(lengths, e, std::sqrt(CGAL::squared_distance(mesh.point(mesh.vertex(e, 0)), mesh.point(mesh.vertex(e, 1)))));
    const IM::Metric_mesh<Mesh> prepared(mesh, IM::parameters::edge_length_map(lengths));
    IM::Geodesic_solver<Mesh> from_lengths(prepared, IM::parameters::store_windows(false));
    from_lengths.add_source(source);
    from_lengths.propagate();
    /// [prepared mesh]
    for(vertex_descriptor v : vertices(mesh))
      if(std::abs(from_lengths.distance(v) - d_euclidean[v]) > 1e-12 * max_euclidean)
      {
        std::cerr << "the field from edge lengths differs from the Euclidean one at vertex " << v << std::endl;
        return 1;
      }

    std::cout << "first edge of every face: " << dipping_edges << " of " << num_faces(mesh)
              << " have their minimum inside, below both ends" << std::endl;

    std::cout << "farthest vertex: " << max_euclidean << " (Euclidean), " << max_isophotic
              << " (isophotic); disc of radius " << radius << ": " << inside << " of " << num_vertices(mesh)
              << " vertices; " << timer.time() << " s" << std::endl;

    // Level sets at the same spacing on flat regions in both pictures (the isophotic metric is
    // sqrt(w) times the Euclidean one where the normal is constant): where the isophotic ones crowd,
    // the normal turns.
    const double period = max_euclidean / 20;
    const double width = 0.003 * L;
    const Vector shift = side_by_side_shift(mesh, oblique_view_horizontal, 1.1);
    Coloured_soup soup;
    auto no_face_colour = [](face_descriptor) { return Colour{0, 0, 0}; };
    auto pale = [](double t) { return mix(ramp(t), Colour{255, 255, 255}, 0.4); };
    soup.add_mesh(mesh, Vector(0, 0, 0), [&](vertex_descriptor v) { return pale(d_euclidean[v] / max_euclidean); },
                  no_face_colour);
    soup.add_level_sets(mesh, Vector(0, 0, 0), d_euclidean, period, width, Colour{25, 25, 35});
    soup.add_mesh(mesh, shift, [&](vertex_descriptor v) { return pale(d_isophotic[v] / max_isophotic); },
                  no_face_colour);
    soup.add_level_sets(mesh, shift, d_isophotic, std::sqrt(w) * period, width, Colour{25, 25, 35});
    soup.add_marker(mesh.point(source), 3 * width, Colour{220, 20, 30});
    soup.add_marker(mesh.point(source) + shift, 3 * width, Colour{220, 20, 30});
    const std::string output = stem(filename) + "_distance_field.ply";
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
