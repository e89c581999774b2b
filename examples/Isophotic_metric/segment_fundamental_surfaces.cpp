// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Segmentation of a CAD mesh into fundamental surfaces (plane, cylinder, cone, sphere, torus,
// free-form), each with its fitted parameters and residual. Prints how much of the area each type
// takes and the largest segments; writes <name>_fundamental_surfaces.ply, each face coloured by the
// type of its segment (a lighter or darker shade per segment).
//
// Usage: segment_fundamental_surfaces [mesh.off]   (default: CGAL's fandisk)
#include "example_output.h"

#include <CGAL/Isophotic_metric/Segmentation/segment_fundamental_surfaces.h>

#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/measure.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

using namespace example_output;
namespace IM = CGAL::Isophotic_metric;

// plane blue-grey, cylinder orange, cone green, sphere red, torus purple, free-form yellow
Colour type_colour(IM::Surface_type t, std::size_t segment)
{
  static const Colour base[6] = {{150, 170, 200}, {240, 140, 40}, {80, 180, 90}, {220, 50, 50}, {150, 80, 190}, {240, 220, 60}};
  const double shade[4] = {0, 0.25, -0.2, 0.4};
  const double s = shade[segment % 4];
  return s >= 0 ? mix(base[int(t)], {255, 255, 255}, s) : mix(base[int(t)], {0, 0, 0}, -s);
}

int main(int argc, char** argv)
{
  const std::string filename = argc > 1 ? argv[1] : std::string(CGAL_DATA_DIR) + "/meshes/fandisk.off";
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(filename, mesh) || !CGAL::is_triangle_mesh(mesh))
  {
    std::cerr << "cannot read a triangle mesh from " << filename << "\n";
    return 1;
  }

  //! [segment]
  auto segment = mesh.add_property_map<face_descriptor, std::size_t>("f:segment", 0).first;
  std::vector<IM::Fundamental_surface_segment> segments;
  const std::size_t n = IM::segment_fundamental_surfaces(mesh, segment, std::back_inserter(segments));
  //! [segment]

  //! [describe]
  double area_of_type[6] = {0, 0, 0, 0, 0, 0}, total = 0;
  for(const IM::Fundamental_surface_segment& s : segments)
  {
    area_of_type[int(s.surface.type)] += s.area;
    total += s.area;
  }
  std::cout << filename << ": " << mesh.number_of_faces() << " faces, " << n << " segments\n";
  for(int t = 0; t < 6; ++t)
    std::printf("  %-9s %5.1f %% of the area\n", IM::surface_type_name(IM::Surface_type(t)), 100 * area_of_type[t] / total);
  std::vector<std::size_t> largest(n);
  for(std::size_t i = 0; i < n; ++i)
    largest[i] = i;
  std::sort(largest.begin(), largest.end(), [&](std::size_t a, std::size_t b) { return segments[a].area > segments[b].area; });
  std::cout << "largest segments:\n";
  for(std::size_t k = 0; k < std::min<std::size_t>(8, n); ++k)
  {
    const IM::Fundamental_surface& s = segments[largest[k]].surface;
    std::printf("  %3zu %-9s area %8.4g  faces %6zu  residual %.3g", largest[k], IM::surface_type_name(s.type),
                segments[largest[k]].area, segments[largest[k]].number_of_faces, s.residual);
    if(s.type == IM::Surface_type::cylinder || s.type == IM::Surface_type::sphere)
      std::printf("  radius %.4g", s.radius);
    if(s.type == IM::Surface_type::torus)
      std::printf("  radii %.4g / %.4g", s.radius, s.minor_radius);
    if(s.type == IM::Surface_type::cone)
      std::printf("  half angle %.2f deg", s.half_angle * 180 / CGAL_PI);
    std::printf("\n");
  }
  //! [describe]

  // every face in a segment, and the segments' areas make up the mesh's
  std::size_t faces_counted = 0;
  for(const IM::Fundamental_surface_segment& s : segments)
    faces_counted += s.number_of_faces;
  const double mesh_area = CGAL::Polygon_mesh_processing::area(mesh);
  if(faces_counted != mesh.number_of_faces() || std::abs(total - mesh_area) > 1e-9 * mesh_area)
  {
    std::cerr << "segments do not cover the mesh\n";
    return 1;
  }
  for(face_descriptor f : mesh.faces())
    if(segment[f] >= n)
    {
      std::cerr << "face " << f << " has no segment\n";
      return 1;
    }

  const std::string out = stem(filename) + "_fundamental_surfaces.ply";
  if(!write_face_coloured_meshes(out, {&mesh}, {Vector(0, 0, 0)},
                                 {[&](face_descriptor f) { return type_colour(segments[segment[f]].surface.type, segment[f]); }}))
    return 1;
  std::cout << "wrote " << out << "\n";
  return 0;
}
