// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Uses the package through add_subdirectory: reads a mesh and prints its default length scale.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Isophotic_metric/suggested_weight_length_scale.h>

#include <iostream>

int main(int argc, char* argv[])
{
  CGAL::Surface_mesh<CGAL::Exact_predicates_inexact_constructions_kernel::Point_3> mesh;
  if(argc < 2 || !CGAL::IO::read_polygon_mesh(argv[1], mesh))
    return 1;
  const double L = CGAL::Isophotic_metric::suggested_weight_length_scale(mesh);
  std::cout << argv[1] << ": " << num_faces(mesh) << " faces, bounding-box diagonal " << L << std::endl;
  return L > 0 ? 0 : 1;
}
