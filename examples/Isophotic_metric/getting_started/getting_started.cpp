// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Getting started: the isophotic distance from a vertex, a dilation of a face to 5 % of the area,
// and a PLY with the distance per vertex and the dilation as face colours.
// Usage: getting_started mesh.off [out.ply]
/// [program]
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Isophotic_metric.h>

#include <iostream>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef Mesh::Vertex_index vertex_descriptor;
typedef Mesh::Face_index face_descriptor;
namespace IM = CGAL::Isophotic_metric;

int main(int argc, char* argv[])
{
  Mesh mesh;
  if(argc < 2 || !CGAL::IO::read_polygon_mesh(argv[1], mesh) || is_empty(mesh))
  {
    std::cerr << "usage: getting_started mesh.off [out.ply]" << std::endl;
    return 1;
  }
  try
  {
    // w = w' = 0.5; the length scale (here its default, the bounding-box diagonal) makes the
    // weights independent of the model's units
    const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5)
                          .weight_length_scale(IM::suggested_weight_length_scale(mesh));

    // exact isophotic distance from the first vertex to every vertex, stored as a PLY property
    auto distance = mesh.add_property_map<vertex_descriptor, double>("v:distance").first;
    const std::vector<vertex_descriptor> sources{*vertices(mesh).begin()};
    IM::compute_geodesic_distances(sources, mesh, distance, metric);

    // dilation of the first face to 5 % of the area (a face joins when half of it is within the radius)
    const std::vector<face_descriptor> seed{*faces(mesh).begin()};
    const auto rule = metric.area_fraction(0.5);
    const double radius = IM::radius_for_area_share(seed, mesh, 0.05, rule);
    auto selected = get(CGAL::dynamic_face_property_t<bool>(), mesh);
    for(face_descriptor f : faces(mesh))
      put(selected, f, f == seed[0]);
    std::vector<face_descriptor> grown;
    IM::dilate_face_selection(seed, mesh, radius, selected, std::back_inserter(grown), rule);

    // face colours: red seed, orange dilation, light grey elsewhere
    auto colour = mesh.add_property_map<face_descriptor, CGAL::IO::Color>("f:color").first;
    for(face_descriptor f : faces(mesh))
      colour[f] = f == seed[0] ? CGAL::IO::red() : get(selected, f) ? CGAL::IO::orange() : CGAL::IO::Color(210, 210, 210);
    const char* out = argc > 2 ? argv[2] : "getting_started.ply";
    std::cout << "radius " << radius << " dilates to " << grown.size() + 1 << " of " << num_faces(mesh)
              << " faces; writing " << out << std::endl;
    return CGAL::IO::write_PLY(out, mesh) ? 0 : 1;
  }
  catch(const IM::Error& e) // bad input: the message names the element
  {
    std::cerr << e.what() << std::endl;
    return 1;
  }
}
/// [program]
