// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Figures of Pottmann et al. (ECCV 2004) on CGAL's fandisk, as per-face coloured PLYs:
//   fig2_discs.ply    geodesic discs around one point: Euclidean | purely isophotic (w = 0.01) | isophotic (w = w' = 0.5)
//   fig5_closing.ply  a broken stripe along a feature, Euclidean dilation then isophotic erosion: the gaps close
//                     along the feature only (input | Euclidean dilation | result)
//   fig7_dilation.ply dilation with w = 0.2, w' = 0.8 against the Euclidean one, same area (Euclidean | isophotic)
// The weights are made dimensionless with the bounding-box diagonal as length scale.
//
// Usage: morphology_figures [mesh.off]
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Isophotic_metric.h>

#include "morphology_helpers.h" // colours, feature patches, PLY files, picking

#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <iostream>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
typedef boost::graph_traits<Mesh>::face_descriptor face_descriptor;
namespace IM = CGAL::Isophotic_metric;
using namespace morphology_helpers;

int main(int argc, char* argv[])
{
  const std::string filename = (argc > 1) ? argv[1] : CGAL::data_file_path("meshes/fandisk.off");
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(filename, mesh) || is_empty(mesh))
  {
    std::cerr << "Cannot read " << filename << std::endl;
    return 1;
  }
  const double L = IM::suggested_weight_length_scale(mesh);
  const CGAL::Bbox_3 box = PMP::bbox(mesh);
  const Vector no_shift(0, 0, 0), shift = side_by_side_shift(mesh, Vector(0, 1, 0), 1.15);
  auto colour_of = [](const std::set<face_descriptor>& seed, const std::set<face_descriptor>& grown) {
    return [seed, grown](face_descriptor f) {
      return seed.count(f) ? seed_colour : grown.count(f) ? inside_colour : background;
    };
  };

  // Fig. 2: discs around one surface point, same area in each metric.
  {
    const face_descriptor centre = face_near(mesh, {0.5, 0.25, 0.75});
    const std::set<face_descriptor> seed{centre};
    IM::Face_band_solver<Mesh> euclidean(mesh, IM::parameters::isophotic_weight(0));
    IM::Face_band_solver<Mesh> purely(mesh, IM::parameters::euclidean_weight(0.01).isophotic_weight(1).weight_length_scale(L));
    IM::Face_band_solver<Mesh> isophotic(mesh, IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L));
    std::vector<std::set<face_descriptor>> discs;
    for(IM::Face_band_solver<Mesh>* band : {&euclidean, &purely, &isophotic})
      discs.push_back(dilate(mesh, seed, radius_for_share(seed, 0.04, *band), *band));
    write_face_coloured_meshes("fig2_discs.ply", {&mesh, &mesh, &mesh}, {no_shift, shift, 2 * shift},
                               {colour_of(seed, discs[0]), colour_of(seed, discs[1]), colour_of(seed, discs[2])});
    std::cout << "fig2_discs.ply: discs of " << discs[0].size() << ", " << discs[1].size() << ", " << discs[2].size()
              << " faces (Euclidean, purely isophotic, isophotic)\n";
  }

  // Fig. 5: closing along a feature. The stripe: faces of the curved band near its upper sharp edge,
  // with gaps; Euclidean dilation fills the gaps and spills over the edge, isophotic erosion then
  // removes what spilled while the filled gaps along the band stay.
  {
    const face_descriptor start = face_near(mesh, {0.5, 0.25, 0.75});
    /// [closing along a feature]
    IM::Face_band_solver<Mesh> euclidean(mesh, IM::parameters::isophotic_weight(0));
    IM::Face_band_solver<Mesh> isophotic(mesh, IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L));
    // the band around the start face (its isophotic neighbourhood), then every other slice of it along x
    std::vector<IM::Neighborhood_face<face_descriptor>> band_faces;
    IM::geodesic_neighborhood(start, mesh, 0.6 * L, std::back_inserter(band_faces),
                              IM::parameters::face_band_solver(&isophotic).area_fraction(0.5));
    std::set<face_descriptor> stripe;
    for(const auto& neighbour : band_faces)
    {
      const face_descriptor f = neighbour.face;
      const auto c = CGAL::centroid(mesh.point(source(halfedge(f, mesh), mesh)), mesh.point(target(halfedge(f, mesh), mesh)),
                                    mesh.point(target(next(halfedge(f, mesh), mesh), mesh)));
      if(std::fmod(c.x() - box.xmin(), 0.08 * (box.xmax() - box.xmin())) < 0.05 * (box.xmax() - box.xmin()))
        stripe.insert(f);
    }
    auto selected = mesh.add_property_map<face_descriptor, bool>("f:stripe", false).first;
    for(face_descriptor f : stripe)
      selected[f] = true;
    const double r = 0.03 * L;
    std::vector<face_descriptor> added;
    IM::dilate_face_selection(stripe, mesh, r, selected, std::back_inserter(added),
                              IM::parameters::face_band_solver(&euclidean).area_fraction(0.5));
    std::set<face_descriptor> dilated(stripe);
    dilated.insert(added.begin(), added.end());
    // isophotic erosion by the isophotic radius that matches the Euclidean one on flat parts (sqrt(w) r)
    std::vector<face_descriptor> dilated_range(dilated.begin(), dilated.end()), removed;
    IM::erode_face_selection(dilated_range, mesh, std::sqrt(0.5) * r, selected, std::back_inserter(removed),
                             IM::parameters::face_band_solver(&isophotic).area_fraction(0.5));
    /// [closing along a feature]
    std::set<face_descriptor> closed;
    for(face_descriptor f : faces(mesh))
      if(selected[f])
        closed.insert(f);
    write_face_coloured_meshes("fig5_closing.ply", {&mesh, &mesh, &mesh}, {no_shift, shift, 2 * shift},
                               {colour_of(stripe, {}), colour_of(stripe, dilated), colour_of(stripe, closed)});
    std::cout << "fig5_closing.ply: stripe of " << stripe.size() << " faces, Euclidean dilation " << dilated.size()
              << ", then isophotic erosion " << closed.size() << "\n";
  }

  // Fig. 7: w = 0.2, w' = 0.8 against Euclidean, same area.
  {
    const face_descriptor start = face_near(mesh, {0.5, 0.5, 1.0});
    const std::set<face_descriptor> seed{start};
    IM::Face_band_solver<Mesh> euclidean(mesh, IM::parameters::isophotic_weight(0));
    IM::Face_band_solver<Mesh> isophotic(mesh, IM::parameters::euclidean_weight(0.2).isophotic_weight(0.8).weight_length_scale(L));
    const auto e = dilate(mesh, seed, radius_for_share(seed, 0.08, euclidean), euclidean);
    const auto i = dilate(mesh, seed, radius_for_share(seed, 0.08, isophotic), isophotic);
    write_face_coloured_meshes("fig7_dilation.ply", {&mesh, &mesh}, {no_shift, shift}, {colour_of(seed, e), colour_of(seed, i)});
    std::cout << "fig7_dilation.ply: Euclidean " << e.size() << " faces, isophotic " << i.size() << " faces\n";
  }
  return 0;
}
