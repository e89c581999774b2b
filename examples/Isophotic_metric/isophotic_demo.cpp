// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Feature-sensitive dilation on a CAD part: the same small selection is dilated in the Euclidean
// metric and in the isophotic metric (w = w' = 0.5, unit-free with its default length scale, the
// bounding-box diagonal), each to 5 % of the area (a face joins when half of its area is within the
// radius). The Euclidean dilation spreads over the sharp edges and fillets around the seed; the
// isophotic one flows along the features and stays on its side of them (Fig. 6 of Pottmann et al.).
// Writes <name>_dilation_euclidean.ply, <name>_dilation_isophotic.ply and
// <name>_dilation_side_by_side.ply (Euclidean left, isophotic right) with per-face colours:
// dark red = seed, orange = growth on the seed's feature patches, blue = growth beyond a sharp edge;
// beside each, a .camera file with the f3d options of a view that looks at the seed and the growth
// (./run demo renders them).
//
// Usage: isophotic_demo [--repair] [mesh.off [fx fy fz]]   (default: CGAL's fandisk; the seed is the face
// nearest to the point at fractions fx, fy, fz of the bounding box, default 0.5 0.25 0.75; --repair
// first prepares a mesh straight from a scanner with IM::repair_scanned_mesh() and prints its report)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Real_timer.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/selection.h>
#include <CGAL/Polygon_mesh_processing/measure.h>

#include <CGAL/Isophotic_metric.h>

#include "morphology_helpers.h"                // the pictures' colours, feature patches, PLY writing
#include "../../tools/isophotic/view_camera.h" // the camera of the pictures

#include <fstream>
#include <iostream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Vector_3 Vector;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef boost::graph_traits<Mesh>::face_descriptor face_descriptor;
namespace IM = CGAL::Isophotic_metric;
namespace PMP = CGAL::Polygon_mesh_processing;
using namespace morphology_helpers;

// Writes the f3d options of a view, for ./run demo.
bool write_camera(const std::string& filename, const view_camera::View<Mesh>& view)
{
  std::ofstream out(filename);
  for(const std::string& option : view.f3d_arguments())
    out << option << "\n";
  return bool(out);
}

int main(int argc, char* argv[])
{
  std::vector<std::string> args(argv + 1, argv + argc);
  const bool repair = !args.empty() && args.front() == "--repair";
  if(repair)
    args.erase(args.begin());
  const std::string filename = !args.empty() ? args[0] : CGAL::data_file_path("meshes/fandisk.off");
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(filename, mesh) || is_empty(mesh))
  {
    std::cerr << "Cannot read " << filename << std::endl;
    return 1;
  }
  if(repair)
    std::cout << filename << ": " << IM::repair_scanned_mesh(mesh) << std::endl;
  CGAL::Real_timer timer;
  timer.start();

  // A small seed: a face on fandisk's curved band and its neighbours.
  std::array<double, 3> where{0.5, 0.25, 0.75};
  if(args.size() > 3)
    where = {std::stod(args[1]), std::stod(args[2]), std::stod(args[3])};
  const face_descriptor seed_face = face_near(mesh, where);
  std::set<face_descriptor> seed{seed_face};
  {
    auto selected = mesh.add_property_map<face_descriptor, bool>("f:seed", false).first;
    selected[seed_face] = true;
    std::vector<face_descriptor> ring;
    CGAL::expand_face_selection(std::vector<face_descriptor>{seed_face}, mesh, 1, selected, std::back_inserter(ring));
    seed.insert(ring.begin(), ring.end());
    mesh.remove_property_map(selected);
  }

  try
  {
    /// [dilation]
    // Euclidean (w' = 0) and isophotic metric, with their geometry prepared once each.
    IM::Face_band_solver<Mesh> euclidean(mesh, IM::parameters::isophotic_weight(0));
    IM::Face_band_solver<Mesh> isophotic(mesh, IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5));
    // The seed dilated to 5 % of the surface; a face joins when half of its area is within the radius.
    auto dilation = [&](IM::Face_band_solver<Mesh>& band, double& radius) {
      const auto rule = IM::parameters::face_band_solver(&band).area_fraction(0.5);
      radius = IM::radius_for_area_share(seed, mesh, 0.05, rule);
      auto selected = get(CGAL::dynamic_face_property_t<bool>(), mesh);
      for(face_descriptor f : faces(mesh))
        put(selected, f, seed.count(f) > 0);
      std::set<face_descriptor> grown(seed);
      IM::dilate_face_selection(seed, mesh, radius, selected, std::inserter(grown, grown.end()), rule);
      return grown;
    };
    double r_euclidean = 0, r_isophotic = 0;
    const std::set<face_descriptor> grown_euclidean = dilation(euclidean, r_euclidean);
    const std::set<face_descriptor> grown_isophotic = dilation(isophotic, r_isophotic);
    /// [dilation]
    const double L = IM::suggested_weight_length_scale(mesh);

    std::size_t number_of_patches = 0;
    const std::vector<std::size_t> patch = feature_patches(mesh, 30, number_of_patches);
    std::set<std::size_t> seed_patches;
    for(face_descriptor f : seed)
      seed_patches.insert(patch[f]);
    auto colouring = [&](const std::set<face_descriptor>& grown) {
      return [&, grown](face_descriptor f) {
        if(seed.count(f)) return seed_colour;
        if(!grown.count(f)) return background;
        return seed_patches.count(patch[f]) ? inside_colour : beyond_colour;
      };
    };
    // One view for both pictures, looking at the seed and at both dilations; the side-by-side
    // picture puts the isophotic copy to the right of the Euclidean one in that view.
    std::vector<face_descriptor> focus(grown_euclidean.begin(), grown_euclidean.end());
    focus.insert(focus.end(), grown_isophotic.begin(), grown_isophotic.end());
    const view_camera::View<Mesh> view = view_camera::view_of(mesh, focus, false);
    const CGAL::Bbox_3 box = PMP::bbox(mesh);
    const Vector right = view.right();
    const double width = std::abs(right.x()) * (box.xmax() - box.xmin()) + std::abs(right.y()) * (box.ymax() - box.ymin()) +
                         std::abs(right.z()) * (box.zmax() - box.zmin());
    const Vector no_shift(0, 0, 0), shift = 1.1 * width * right;
    view_camera::View<Mesh> both = view;
    both.eye = view.eye + 0.5 * shift;
    both.focal = view.focal + 0.5 * shift;
    const double pi = 3.14159265358979323846, distance = std::sqrt(CGAL::squared_distance(view.eye, view.focal));
    both.angle = std::min(120., 2 * std::atan(std::tan(view.angle * pi / 360) + 0.5 * width * 1.1 / distance) * 180 / pi);

    const std::string name = stem(filename);
    bool ok = write_face_coloured_meshes(name + "_dilation_euclidean.ply", {&mesh}, {no_shift}, {colouring(grown_euclidean)});
    ok = ok && write_face_coloured_meshes(name + "_dilation_isophotic.ply", {&mesh}, {no_shift}, {colouring(grown_isophotic)});
    ok = ok && write_face_coloured_meshes(name + "_dilation_side_by_side.ply", {&mesh, &mesh}, {no_shift, shift},
                                          {colouring(grown_euclidean), colouring(grown_isophotic)});
    ok = ok && write_camera(name + "_dilation_euclidean.camera", view) &&
         write_camera(name + "_dilation_isophotic.camera", view) && write_camera(name + "_dilation_side_by_side.camera", both);
    if(!ok)
    {
      std::cerr << "Cannot write the PLY and camera files" << std::endl;
      return 1;
    }
    timer.stop();
    std::cout << filename << ": " << num_faces(mesh) << " faces, seed of " << seed.size() << " faces, "
              << number_of_patches << " patches between sharp edges (dihedral angle > 30 degrees)\n"
              << "dilation to 5 % of the area: Euclidean radius " << r_euclidean << ", isophotic radius "
              << r_isophotic << " (w = w' = 0.5, L = " << L << ")\n"
              << "share of the dilated area beyond a sharp edge: Euclidean "
              << 100 * share_beyond_features(mesh, seed, grown_euclidean, patch) << " %, isophotic "
              << 100 * share_beyond_features(mesh, seed, grown_isophotic, patch) << " %\n"
              << "wrote " << name << "_dilation_{euclidean,isophotic,side_by_side}.ply in " << timer.time() << " s"
              << std::endl;
  }
  catch(const IM::Error& e) // bad input: the message names the element
  {
    std::cerr << filename << ": " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
