// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Lifts a triangle mesh to R^6 and compares isophotic and Euclidean edge lengths. Also writes
// <name>_isophotic_stretch.ply: every face coloured by the largest stretch ell_iso / (sqrt(w) ell) of
// its edges (w = w' = 0.5), pale = 1 on flat parts, dark red >= 20 across fillets and sharp edges.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/IO/Color.h>

#include <CGAL/Isophotic_metric.h>

#include "example_output.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
typedef boost::graph_traits<Mesh>::face_descriptor face_descriptor;
namespace IM = CGAL::Isophotic_metric;

// Writes the mesh with per-face colours as a binary little-endian PLY with uchar red/green/blue
// (the layout image tools read as an "RGB" array), plus the face stretch as a float property.
template <class ColourMap, class ValueMap>
bool write_coloured_ply(const std::string& filename, const Mesh& mesh, ColourMap colour, ValueMap value)
{
  std::ofstream out(filename, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\n"
      << "element vertex " << num_vertices(mesh) << "\n"
      << "property float x\nproperty float y\nproperty float z\n"
      << "element face " << num_faces(mesh) << "\nproperty list uchar int vertex_indices\n"
      << "property float stretch\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  auto put_bytes = [&](std::uint32_t bits, int n) { example_output::put_little_endian(out, bits, n); };
  auto put_float = [&](double x) { example_output::put_little_endian_float(out, x); };
  std::vector<std::uint32_t> index(mesh.number_of_vertices() + mesh.number_of_removed_vertices());
  std::uint32_t next_index = 0;
  for(vertex_descriptor v : vertices(mesh))
  {
    index[v] = next_index++;
    const auto& p = mesh.point(v);
    put_float(p.x()); put_float(p.y()); put_float(p.z());
  }
  for(auto f : faces(mesh))
  {
    put_bytes(3, 1);
    for(vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, mesh), mesh))
      put_bytes(index[v], 4);
    put_float(get(value, f));
    const CGAL::IO::Color c = get(colour, f);
    put_bytes(c.red(), 1); put_bytes(c.green(), 1); put_bytes(c.blue(), 1);
  }
  return bool(out);
}

// A sequential colour map: pale grey (no stretch) -> blue -> orange -> dark red (strong stretch).
CGAL::IO::Color stretch_colour(double t)
{
  static const std::array<std::array<double, 3>, 5> stops = {{
    {{0.93, 0.94, 0.96}}, {{0.45, 0.65, 0.95}}, {{1.00, 0.80, 0.30}}, {{0.95, 0.40, 0.15}}, {{0.70, 0.08, 0.08}}}};
  t = std::clamp(t, 0., 1.) * (stops.size() - 1);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(t), stops.size() - 2);
  const double s = t - double(i);
  std::array<unsigned char, 3> rgb;
  for(int k = 0; k < 3; ++k)
    rgb[k] = static_cast<unsigned char>(255. * ((1 - s) * stops[i][k] + s * stops[i + 1][k]) + 0.5);
  return CGAL::IO::Color(rgb[0], rgb[1], rgb[2]);
}


int main(int argc, char* argv[])
{
  const std::string filename = (argc > 1) ? argv[1] : CGAL::data_file_path("meshes/fandisk.off");
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(filename, mesh))
  {
    std::cerr << "Cannot read " << filename << std::endl;
    return 1;
  }

  /// [lift]
  // X(v) = (sqrt(w) p, sqrt(w') L n): weights as in Fig. 7 of the paper, made
  // dimensionless by the length scale L (the bounding-box diagonal).
  auto lifted = mesh.add_property_map<vertex_descriptor, IM::Lifted_point>("v:lifted").first;
  const double L = IM::suggested_weight_length_scale(mesh);
  const auto np = IM::parameters::euclidean_weight(0.2)
                                 .isophotic_weight(0.8)
                                 .weight_length_scale(L);
  try
  {
    IM::compute_lifted_embedding(mesh, lifted, np);
  }
  catch(const IM::Error& e) // bad input: the message names the element
  {
    std::cerr << e.what() << std::endl;
    return 1;
  }
  /// [lift]

  /// [named parameters]
  // The package's parameters chain with CGAL's, and CGAL's functions accept the
  // whole pack: they ignore the tags they do not know. (Give CGAL functions that
  // also take a face range that range: their two-argument form would read the
  // pack as a mesh.)
  const auto with_points = IM::parameters::vertex_point_map(mesh.points())
                                          .euclidean_weight(0.2);
  const double area = CGAL::Polygon_mesh_processing::area(faces(mesh), mesh, with_points);
  /// [named parameters]

  /// [lengths]
  // Edges that cross a feature are much longer in the isophotic metric.
  std::size_t crossing = 0;
  for(auto e : edges(mesh))
  {
    const double euclidean = std::sqrt(CGAL::squared_distance(mesh.point(source(e, mesh)),
                                                              mesh.point(target(e, mesh))));
    if(IM::edge_isophotic_length(e, mesh, lifted) > 5 * std::sqrt(0.2) * euclidean)
      ++crossing;
  }
  /// [lengths]

  std::cout << "area " << area << "; " << crossing << " of " << num_edges(mesh)
            << " edges are more than 5 times longer than sqrt(w) times their Euclidean length" << std::endl;
  // The stretch picture (w = w' = 0.5): largest edge stretch of every face, on a log colour scale.
  const double w = 0.5;
  IM::compute_lifted_embedding(mesh, lifted, IM::parameters::euclidean_weight(w).isophotic_weight(0.5).weight_length_scale(L));
  auto stretch = mesh.add_property_map<face_descriptor, double>("f:stretch", 1.).first;
  for(auto e : edges(mesh))
  {
    const double euclidean = std::sqrt(CGAL::squared_distance(mesh.point(source(e, mesh)), mesh.point(target(e, mesh))));
    const double s = IM::edge_isophotic_length(e, mesh, lifted) / (std::sqrt(w) * euclidean);
    for(auto h : {halfedge(e, mesh), opposite(halfedge(e, mesh), mesh)})
      if(!is_border(h, mesh))
        stretch[face(h, mesh)] = (std::max)(stretch[face(h, mesh)], s);
  }
  auto colour = mesh.add_property_map<face_descriptor, CGAL::IO::Color>("f:color").first;
  for(face_descriptor f : faces(mesh))
    colour[f] = stretch_colour(std::log(stretch[f]) / std::log(20.));
  std::string stem = filename.substr(filename.find_last_of("/\\") + 1);
  stem = stem.substr(0, stem.find_last_of('.'));
  if(!write_coloured_ply(stem + "_isophotic_stretch.ply", mesh, colour, stretch))
  {
    std::cerr << "Cannot write " << stem << "_isophotic_stretch.ply" << std::endl;
    return 1;
  }
  std::cout << "wrote " << stem << "_isophotic_stretch.ply" << std::endl;
  return 0;
}
