// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Computes results with the C++ API on a mesh and writes them as raw little-endian arrays into a
// directory, for the Python tests to compare the module's results with (same mesh, same calls):
//   cpp_reference <mesh> <output directory> [<CAD part>]
// Files: lift.f64 (n x 6), euclidean.f64 and isophotic.f64 (n, source vertex 0), dilation.u8 (m,
// face 0 dilated by a tenth of the bounding-box diagonal), patches.i64 (m, segmentation),
// robust_normals.f64 (n x 3, estimate_vertex_normals() at twice the mean edge length).
// With a CAD part, its segmentation into fundamental surfaces, with the default options and with
// options(L) below: fundamental.i64 and fundamental_options.i64 (segment id of every face), and
// surfaces.f64, surfaces_options.f64 (one row of 13 per segment: type, centre, axis, radius,
// minor radius, half angle, residual, area, number of faces).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Isophotic_metric.h>
#include <CGAL/Isophotic_metric/Segmentation/segment_fundamental_surfaces.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <iostream>
#include <string>
#include <vector>

namespace IM = CGAL::Isophotic_metric;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef Mesh::Vertex_index vertex_descriptor;
typedef Mesh::Face_index face_descriptor;

template <class T>
void write(const std::string& path, const std::vector<T>& values)
{
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(T)));
}

// Segments `part` into fundamental surfaces and writes <dir>/<name>.i64 and the surfaces.
template <class NamedParameters>
void write_fundamental_segmentation(Mesh& part, const NamedParameters& np, const std::string& dir,
                                    const std::string& ids_name, const std::string& surfaces_name)
{
  auto segment = part.add_property_map<face_descriptor, std::int64_t>("f:fundamental").first;
  std::vector<IM::Fundamental_surface_segment> segments;
  IM::segment_fundamental_surfaces(part, segment, std::back_inserter(segments), np);
  std::vector<std::int64_t> ids;
  for(face_descriptor f : faces(part))
    ids.push_back(segment[f]);
  write(dir + "/" + ids_name, ids);
  std::vector<double> rows;
  for(const IM::Fundamental_surface_segment& s : segments)
  {
    const IM::Fundamental_surface& f = s.surface;
    rows.insert(rows.end(), {double(static_cast<int>(f.type)), f.center.x(), f.center.y(), f.center.z(), f.axis.x(),
                             f.axis.y(), f.axis.z(), f.radius, f.minor_radius, f.half_angle, f.residual, s.area,
                             double(s.number_of_faces)});
  }
  write(dir + "/" + surfaces_name, rows);
}

int main(int argc, char* argv[])
{
  if(argc != 3 && argc != 4)
  {
    std::cerr << "usage: cpp_reference <mesh> <output directory> [<CAD part>]" << std::endl;
    return 2;
  }
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(argv[1], mesh))
  {
    std::cerr << "cannot read " << argv[1] << std::endl;
    return 1;
  }
  const std::string dir = argv[2];
  const double L = IM::suggested_weight_length_scale(mesh);
  const auto isophotic = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);

  auto lifted = mesh.add_property_map<vertex_descriptor, IM::Lifted_point>("v:lifted").first;
  IM::compute_lifted_embedding(mesh, lifted, isophotic);
  std::vector<double> lift;
  for(vertex_descriptor v : vertices(mesh))
    lift.insert(lift.end(), lifted[v].begin(), lifted[v].end());
  write(dir + "/lift.f64", lift);

  const vertex_descriptor sources[1] = {vertex_descriptor(0)};
  auto distance = mesh.add_property_map<vertex_descriptor, double>("v:distance").first;
  std::vector<double> d;
  IM::compute_geodesic_distances(sources, mesh, distance, IM::parameters::isophotic_weight(0));
  for(vertex_descriptor v : vertices(mesh))
    d.push_back(distance[v]);
  write(dir + "/euclidean.f64", d);
  d.clear();
  IM::compute_geodesic_distances(sources, mesh, distance, isophotic);
  for(vertex_descriptor v : vertices(mesh))
    d.push_back(distance[v]);
  write(dir + "/isophotic.f64", d);

  auto selected = mesh.add_property_map<face_descriptor, bool>("f:selected", false).first;
  selected[face_descriptor(0)] = true;
  const face_descriptor seed[1] = {face_descriptor(0)};
  IM::dilate_face_selection(seed, mesh, 0.1 * L, selected, CGAL::Emptyset_iterator(), isophotic);
  std::vector<std::uint8_t> dilation;
  for(face_descriptor f : faces(mesh))
    dilation.push_back(selected[f] ? 1 : 0);
  write(dir + "/dilation.u8", dilation);

  auto patch = mesh.add_property_map<face_descriptor, std::int64_t>("f:patch").first;
  IM::segment_by_region_growing(mesh, 0.05 * L, patch, isophotic);
  std::vector<std::int64_t> patches;
  for(face_descriptor f : faces(mesh))
    patches.push_back(patch[f]);
  write(dir + "/patches.i64", patches);

  auto robust = mesh.add_property_map<vertex_descriptor, K::Vector_3>("v:robust_normal").first;
  IM::estimate_vertex_normals(mesh, 2. * IM::estimate_mesh_noise(mesh).mean_edge_length, robust);
  std::vector<double> normals;
  for(vertex_descriptor v : vertices(mesh))
    normals.insert(normals.end(), {robust[v].x(), robust[v].y(), robust[v].z()});
  write(dir + "/robust_normals.f64", normals);

  if(argc == 4)
  {
    Mesh part;
    if(!CGAL::IO::read_polygon_mesh(argv[3], part))
    {
      std::cerr << "cannot read " << argv[3] << std::endl;
      return 1;
    }
    const double diagonal = IM::suggested_weight_length_scale(part);
    write_fundamental_segmentation(part, IM::parameters::default_values(), dir, "fundamental.i64", "surfaces.f64");
    // every option given (the Python test passes the same values)
    const auto options = IM::parameters::distance_tolerance(0.004 * diagonal)
                           .angle_tolerance(12.0)
                           .seed_spacing(0.08 * diagonal)
                           .minimum_segment_faces(std::size_t(12))
                           .euclidean_weight(0.4)
                           .isophotic_weight(0.6)
                           .weight_length_scale(0.5 * diagonal);
    write_fundamental_segmentation(part, options, dir, "fundamental_options.i64", "surfaces_options.f64");
  }
  return 0;
}
