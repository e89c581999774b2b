// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Helpers shared by the morphology examples: the colours of their pictures, feature patches (faces
// connected without crossing a sharp edge), areas, and dilations of face sets.
// The generic output code (PLY writing, colour maps, picking) is in example_output.h.
#ifndef ISOPHOTIC_METRIC_EXAMPLES_MORPHOLOGY_HELPERS_H
#define ISOPHOTIC_METRIC_EXAMPLES_MORPHOLOGY_HELPERS_H

#include "example_output.h"

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/measure.h>

#include <CGAL/Isophotic_metric.h>

#include <cmath>
#include <set>
#include <vector>

namespace morphology_helpers {

using namespace example_output;
namespace IM = CGAL::Isophotic_metric;
namespace PMP = CGAL::Polygon_mesh_processing;

// Colours of the pictures: light grey surface, dark red seed, orange growth within the seed's
// feature patch, blue growth beyond a feature.
const Colour background{215, 217, 222}, seed_colour{165, 15, 25}, inside_colour{245, 150, 35},
  beyond_colour{40, 110, 220};

// Patch id of every face: faces connected across edges whose dihedral angle is below `angle_degrees`.
inline std::vector<std::size_t> feature_patches(const Mesh& m, double angle_degrees, std::size_t& number_of_patches)
{
  Mesh& mutable_mesh = const_cast<Mesh&>(m);
  auto is_sharp = mutable_mesh.add_property_map<Mesh::Edge_index, bool>("e:morphology_sharp", false).first;
  PMP::detect_sharp_edges(m, angle_degrees, is_sharp);
  auto patch = mutable_mesh.add_property_map<face_descriptor, std::size_t>("f:morphology_patch", 0).first;
  number_of_patches = PMP::connected_components(m, patch, CGAL::parameters::edge_is_constrained_map(is_sharp));
  std::vector<std::size_t> result(m.number_of_faces() + m.number_of_removed_faces(), 0);
  for(face_descriptor f : faces(m))
    result[f] = patch[f];
  mutable_mesh.remove_property_map(is_sharp);
  mutable_mesh.remove_property_map(patch);
  return result;
}

inline double face_area(const Mesh& m, face_descriptor f) { return PMP::face_area(f, m); }

inline double area_of(const Mesh& m, const std::set<face_descriptor>& fs)
{
  double a = 0;
  for(face_descriptor f : fs)
    a += face_area(m, f);
  return a;
}

// Dilation of `seed` by `radius` with a prepared band solver: a face joins when half of its area
// (by default) lies within the radius.
inline std::set<face_descriptor> dilate(const Mesh& m, const std::set<face_descriptor>& seed, double radius,
                                        IM::Face_band_solver<Mesh>& band, double area_fraction = 0.5)
{
  Mesh& mutable_mesh = const_cast<Mesh&>(m);
  auto selected = mutable_mesh.add_property_map<face_descriptor, bool>("f:morphology_selected", false).first;
  for(face_descriptor f : seed)
    selected[f] = true;
  std::set<face_descriptor> result(seed);
  std::vector<face_descriptor> added;
  IM::dilate_face_selection(seed, m, radius, selected, std::back_inserter(added), IM::parameters::face_band_solver(&band).area_fraction(area_fraction));
  result.insert(added.begin(), added.end());
  mutable_mesh.remove_property_map(selected);
  return result;
}

// The radius whose dilation of `seed` by `dilate()` (half of a face's area within the radius) covers
// the share `share` of the surface.
inline double radius_for_share(const std::set<face_descriptor>& seed, double share, IM::Face_band_solver<Mesh>& band)
{
  return IM::radius_for_area_share(seed, band.mesh(), share, IM::parameters::face_band_solver(&band).area_fraction(0.5));
}

// Share of the area of `grown` (minus the seed) lying outside the feature patches touched by the seed.
inline double share_beyond_features(const Mesh& m, const std::set<face_descriptor>& seed,
                                    const std::set<face_descriptor>& grown, const std::vector<std::size_t>& patch)
{
  std::set<std::size_t> seed_patches;
  for(face_descriptor f : seed)
    seed_patches.insert(patch[f]);
  double beyond = 0, total = 0;
  for(face_descriptor f : grown)
  {
    if(seed.count(f))
      continue;
    total += face_area(m, f);
    if(!seed_patches.count(patch[f]))
      beyond += face_area(m, f);
  }
  return total > 0 ? beyond / total : 0;
}

} // namespace morphology_helpers

#endif // ISOPHOTIC_METRIC_EXAMPLES_MORPHOLOGY_HELPERS_H
