// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Feature sensitivity in numbers, on CAD meshes of CGAL's data set:
//  1. figure of merit of dilation: the same seed dilated to the same area (3 % of the surface) in the
//     Euclidean and in the isophotic metric; share of the grown area that lies beyond a sharp edge
//     (dihedral angle > 30 degrees), averaged over three seeds;
//  2. segmentation: number of patches of PMP::sharp_edges_segmentation, of Shape_detection's plane
//     region growing and of isophotic region growing (greedy cover alone, then with the merge of
//     patches whose common boundary is not a feature), and how the fillets fare. A fillet is a
//     connected set of at least 20 faces whose edges bend by more than 3 degrees but less than 30.
//     "whole" is the area share of a fillet inside the patch that holds most of it (it rewards not
//     splitting a fillet); "IoU" is the intersection over union of a fillet and that patch (it also
//     penalizes merging the fillet with its neighbours). Both are area-weighted means over fillets.
//  <mesh>_segmentations.ply: the three segmentations side by side (sharp edges, planes, isophotic).
//
// Usage: morphology_comparison [--all]   (default: fandisk and couplingdown; --all adds turbine,
//                                         anchor_dense and rotor)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Isophotic_metric.h>

#include "morphology_helpers.h" // colours, feature patches, PLY files, picking

#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Shape_detection/Region_growing/Region_growing.h>
#include <CGAL/Shape_detection/Region_growing/Region_growing_on_polygon_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/selection.h>

#include <chrono>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
typedef boost::graph_traits<Mesh>::face_descriptor face_descriptor;
namespace IM = CGAL::Isophotic_metric;
using namespace morphology_helpers;

namespace {

double dihedral_degrees(const Mesh& m, Mesh::Halfedge_index h)
{
  const auto n1 = PMP::compute_face_normal(face(h, m), m), n2 = PMP::compute_face_normal(face(opposite(h, m), m), m);
  return std::acos(std::clamp(n1 * n2, -1.0, 1.0)) * 180 / CGAL_PI;
}

// Fillet components (lists of faces).
std::vector<std::vector<face_descriptor>> fillets(const Mesh& m)
{
  std::vector<char> blend(m.number_of_faces() + m.number_of_removed_faces(), 0);
  for(auto e : edges(m))
  {
    const auto h = halfedge(e, m);
    if(is_border_edge(h, m))
      continue;
    const double a = dihedral_degrees(m, h);
    if(a > 3 && a < 30)
      blend[face(h, m)] = blend[face(opposite(h, m), m)] = 1;
  }
  std::vector<char> seen(blend.size(), 0);
  std::vector<std::vector<face_descriptor>> result;
  for(face_descriptor f : faces(m))
  {
    if(!blend[f] || seen[f])
      continue;
    std::vector<face_descriptor> component{f};
    seen[f] = 1;
    for(std::size_t i = 0; i < component.size(); ++i)
      for(auto h : CGAL::halfedges_around_face(halfedge(component[i], m), m))
      {
        if(is_border_edge(h, m))
          continue;
        const face_descriptor g = face(opposite(h, m), m);
        if(blend[g] && !seen[g] && dihedral_degrees(m, h) < 30)
        {
          seen[g] = 1;
          component.push_back(g);
        }
      }
    if(component.size() >= 20)
      result.push_back(component);
  }
  return result;
}

// Area-weighted means over the fillets of the share of a fillet inside its majority patch P
// ("whole") and of the intersection over union of the fillet and P.
std::array<double, 2> fillet_scores(const Mesh& m, const std::vector<std::vector<face_descriptor>>& fs,
                                    const std::vector<std::size_t>& patch)
{
  std::map<std::size_t, double> patch_area;
  for(face_descriptor f : faces(m))
    patch_area[patch[f]] += face_area(m, f);
  double kept = 0, iou = 0, total = 0;
  for(const auto& fillet : fs)
  {
    std::map<std::size_t, double> by_patch;
    double area = 0;
    for(face_descriptor f : fillet)
    {
      by_patch[patch[f]] += face_area(m, f);
      area += face_area(m, f);
    }
    std::pair<std::size_t, double> best{0, 0};
    for(const auto& p : by_patch)
      if(p.second > best.second)
        best = p;
    kept += best.second;
    iou += area * best.second / (area + patch_area[best.first] - best.second);
    total += area;
  }
  return total > 0 ? std::array<double, 2>{kept / total, iou / total} : std::array<double, 2>{1, 1};
}

} // namespace

int main(int argc, char* argv[])
{
  std::vector<std::string> names{"fandisk", "couplingdown"};
  if(argc > 1 && std::string(argv[1]) == "--all")
    names.insert(names.end(), {"turbine", "anchor_dense", "rotor"});
  std::cout << std::fixed << std::setprecision(1)
            << "mesh | faces | beyond sharp edges: Euclidean % | isophotic % | fillets"
            << " | patches: sharp edges | planes (+unassigned faces) | isophotic greedy | isophotic merged"
            << " | fillets whole / IoU %: sharp edges | planes | isophotic greedy | isophotic merged | segmentation time s\n";
  for(const std::string& name : names)
  {
    Mesh mesh;
    if(!CGAL::IO::read_polygon_mesh(CGAL::data_file_path("meshes/" + name + ".off"), mesh))
    {
      std::cerr << "Cannot read " << name << std::endl;
      return 1;
    }
    const double L = IM::suggested_weight_length_scale(mesh);
    const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);
    std::size_t sharp_patches = 0;
    const std::vector<std::size_t> patch = feature_patches(mesh, 30, sharp_patches);

    // 1. figure of merit
    IM::Face_band_solver<Mesh> euclidean(mesh, IM::parameters::isophotic_weight(0));
    IM::Face_band_solver<Mesh> isophotic(mesh, metric);
    double beyond_euclidean = 0, beyond_isophotic = 0;
    const std::size_t nf = num_faces(mesh);
    for(std::size_t s : {nf / 5, nf / 2, 4 * nf / 5})
    {
      std::set<face_descriptor> seed{face_descriptor(static_cast<Mesh::size_type>(s))};
      beyond_euclidean += share_beyond_features(mesh, seed, dilate(mesh, seed, radius_for_share(seed, 0.03, euclidean), euclidean), patch) / 3;
      beyond_isophotic += share_beyond_features(mesh, seed, dilate(mesh, seed, radius_for_share(seed, 0.03, isophotic), isophotic), patch) / 3;
    }

    // 2. segmentations
    const auto start = std::chrono::steady_clock::now();
    /// [segmentation]
    // area_fraction 0: a face joins a region when it meets the disc (no area computation, fast);
    // the merge step (default merge_tolerance 0.5) then joins patches across boundaries that are
    // not features of the metric. The callback is told how far each step has come and may stop the
    // call (Cancelled_error): here, a time budget.
    auto segment = mesh.add_property_map<face_descriptor, std::size_t>("f:isophotic_patch", 0).first;
    const auto deadline = start + std::chrono::minutes(10);
    const std::function<bool(double)> within_budget = [&](double) { return std::chrono::steady_clock::now() < deadline; };
    const std::size_t isophotic_patches = IM::segment_by_region_growing(
      mesh, 0.1 * L, segment, IM::parameters::face_band_solver(&isophotic).area_fraction(0).callback(within_budget));
    /// [segmentation]
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::vector<std::size_t> isophotic_patch(nf), greedy_patch(nf);
    for(face_descriptor f : faces(mesh))
      isophotic_patch[f] = segment[f];
    const std::size_t greedy_patches = IM::segment_by_region_growing(
      mesh, 0.1 * L, segment, IM::parameters::face_band_solver(&isophotic).area_fraction(0).merge_tolerance(-1));
    for(face_descriptor f : faces(mesh))
      greedy_patch[f] = segment[f];

    typedef CGAL::Shape_detection::Polygon_mesh::One_ring_neighbor_query<Mesh> Neighbor_query;
    typedef CGAL::Shape_detection::Polygon_mesh::Least_squares_plane_fit_region<K, Mesh> Region_type;
    typedef CGAL::Shape_detection::Polygon_mesh::Least_squares_plane_fit_sorting<K, Mesh, Neighbor_query> Sorting;
    typedef CGAL::Shape_detection::Region_growing<Mesh::Face_range, Neighbor_query, Region_type, Sorting::Seed_map> Region_growing;
    Neighbor_query neighbors(mesh);
    // the point maps are passed explicitly: their default-constructed values are empty maps
    Region_type planes(mesh, 0.002 * L, 20, 1, get(CGAL::vertex_point, mesh));
    Sorting sorting(mesh, neighbors, get(CGAL::vertex_point, mesh));
    sorting.sort();
    const Mesh::Face_range face_range = faces(mesh); // Region_growing keeps a reference to it
    Region_growing growing(face_range, neighbors, planes, sorting.seed_map());
    std::vector<std::vector<std::size_t>> regions;
    growing.detect(std::back_inserter(regions));
    std::vector<std::size_t> plane_patch(nf, regions.size());
    std::size_t unassigned = nf;
    for(std::size_t r = 0; r < regions.size(); ++r)
      for(std::size_t f : regions[r])
      {
        plane_patch[f] = r;
        --unassigned;
      }
    // unassigned faces each count as their own patch for the wholeness measure
    for(std::size_t f = 0, next = regions.size(); f < nf; ++f)
      if(plane_patch[f] == regions.size())
        plane_patch[f] = ++next;

    const auto fs = fillets(mesh);
    std::cout << name << " | " << nf << " | " << 100 * beyond_euclidean << " | " << 100 * beyond_isophotic << " | "
              << fs.size() << " | " << sharp_patches << " | " << regions.size() << " (+" << unassigned << ") | "
              << greedy_patches << " | " << isophotic_patches;
    for(const std::vector<std::size_t>& p : {patch, plane_patch, greedy_patch, isophotic_patch})
    {
      const std::array<double, 2> score = fillet_scores(mesh, fs, p);
      std::cout << " | " << 100 * score[0] << " / " << 100 * score[1];
    }
    std::cout << " | " << std::setprecision(2) << seconds << std::setprecision(1) << std::endl;

    // the three segmentations side by side; unassigned faces of the plane fitting in grey
    const Vector shift = side_by_side_shift(mesh, Vector(0, 1, 0), 1.15);
    write_face_coloured_meshes(name + "_segmentations.ply", {&mesh, &mesh, &mesh}, {Vector(0, 0, 0), shift, 2 * shift},
                               {[&](face_descriptor f) { return patch_colour(patch[f]); },
                                [&](face_descriptor f) { return plane_patch[f] >= regions.size() ? background : patch_colour(plane_patch[f]); },
                                [&](face_descriptor f) { return patch_colour(isophotic_patch[f]); }});
  }
  return 0;
}
