// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Region growing in the isophotic metric: growth from seed faces that stops at features, geodesic
// Voronoi partition from several seeds, and a greedy segmentation built on them.
#ifndef CGAL_ISOPHOTIC_METRIC_SEGMENTATION_REGION_GROWING_H
#define CGAL_ISOPHOTIC_METRIC_SEGMENTATION_REGION_GROWING_H

#include <CGAL/Isophotic_metric/Morphology/Face_band_solver.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Morphology/face_selection_morphology.h>

#include <CGAL/Polygon_mesh_processing/measure.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

namespace internal {

// Faces reached from `seeds` (indices) within `radius`, passing `accept`, with at least `fraction` of
// their area within the radius, and connected to the seeds across edges through such faces.
template <class TriangleMesh, class Accept>
std::vector<std::uint32_t> grow_connected(Face_band_solver<TriangleMesh>& band, const std::vector<std::uint32_t>& seeds,
                                          double radius, double fraction, Accept&& accept)
{
  band.clear_sources();
  add_source_region_by_index(band, seeds);
  std::vector<char> reached(band.metric_mesh().number_of_faces(), 0);
  std::vector<std::uint32_t> reached_list;
  band.visit_band(radius, fraction > 0, false, [&](const typename Face_band_solver<TriangleMesh>::Face_visit& v) {
    if((fraction == 0 || v.covered_fraction >= fraction) && accept(v.face_index))
    {
      reached[v.face_index] = 1;
      reached_list.push_back(v.face_index);
    }
  });
  for(std::uint32_t s : seeds)
    reached[s] = 1;
  // keep what is edge-connected to the seeds
  const TriangleMesh& tm = band.mesh();
  std::vector<char> kept(band.metric_mesh().number_of_faces(), 0);
  std::vector<std::uint32_t> queue(seeds.begin(), seeds.end());
  for(std::uint32_t s : seeds)
    kept[s] = 1;
  for(std::size_t i = 0; i < queue.size(); ++i)
    for(auto h : CGAL::halfedges_around_face(halfedge(band.metric_mesh().face(queue[i]), tm), tm))
    {
      const auto o = opposite(h, tm);
      if(is_border(o, tm))
        continue;
      const std::uint32_t g = band.metric_mesh().face_index(face(o, tm));
      if(reached[g] && !kept[g])
      {
        kept[g] = 1;
        queue.push_back(g);
      }
    }
  for(std::uint32_t f : reached_list)
    reached[f] = 0;
  return queue;
}

// Stretch of the metric across the edges of a patch partition, from edge lengths only. The segment
// from the centroid of a face to the midpoint of one of its edges is a third of the median to that
// edge, whose length follows from the three edge lengths; it is measured in the metric (lifted edge
// lengths) and in space. The stretch of a face is the largest of its three ratios (the metric's
// strongest direction, where the normal turns fastest); the stretch across an edge is the ratio of
// the two halves of the centroid-to-centroid path through the edge's midpoint.
struct Patch_merge_geometry
{
  std::vector<std::array<double, 3>> lifted, euclidean; // third medians to edge k of face f
  std::vector<std::array<std::uint32_t, 3>> neighbour;  // face across edge k, or -1 on a border
  std::vector<std::array<std::uint8_t, 3>> neighbour_edge;
  std::vector<std::array<double, 3>> edge_length;        // Euclidean length of edge k of face f
  std::vector<double> face_stretch, area;

  static double third_median(const std::array<double, 3>& l, int k)
  {
    const double a = l[(k + 1) % 3], b = l[(k + 2) % 3], c = l[k];
    return std::sqrt(std::max(0.0, 2 * a * a + 2 * b * b - c * c)) / 6;
  }
};

template <class TriangleMesh, class VertexPointMap>
Patch_merge_geometry patch_merge_geometry(const Face_band_solver<TriangleMesh>& band, VertexPointMap vpm)
{
  const TriangleMesh& tm = band.mesh();
  const std::size_t nf = band.metric_mesh().number_of_faces();
  Patch_merge_geometry g;
  g.lifted.resize(nf);
  g.euclidean.resize(nf);
  g.neighbour.assign(nf, {{std::uint32_t(-1), std::uint32_t(-1), std::uint32_t(-1)}});
  g.neighbour_edge.assign(nf, {{0, 0, 0}});
  g.face_stretch.assign(nf, 1.0);
  g.area.resize(nf);
  g.edge_length.resize(nf);
  for(std::uint32_t f = 0; f < nf; ++f)
  {
    const auto& c = band.metric_mesh().corners(f);
    std::array<double, 3> lifted_length, length;
    for(int k = 0; k < 3; ++k)
    {
      lifted_length[k] = band.metric_mesh().edge_length(f, k);
      length[k] = std::sqrt(CGAL::to_double(CGAL::squared_distance(get(vpm, band.metric_mesh().vertex(c[k])), get(vpm, band.metric_mesh().vertex(c[(k + 1) % 3])))));
    }
    g.edge_length[f] = length;
    const double s = 0.5 * (length[0] + length[1] + length[2]);
    g.area[f] = std::sqrt(std::max(0.0, s * (s - length[0]) * (s - length[1]) * (s - length[2])));
    double stretch = 0;
    for(int k = 0; k < 3; ++k)
    {
      g.lifted[f][k] = Patch_merge_geometry::third_median(lifted_length, k);
      g.euclidean[f][k] = Patch_merge_geometry::third_median(length, k);
      if(g.euclidean[f][k] > 0)
        stretch = std::max(stretch, g.lifted[f][k] / g.euclidean[f][k]);
    }
    if(stretch > 0)
      g.face_stretch[f] = stretch;
    // the face across edge k (corners k, k+1), and the index of that edge in it
    for(auto h : CGAL::halfedges_around_face(halfedge(band.metric_mesh().face(f), tm), tm))
    {
      const auto o = opposite(h, tm);
      if(is_border(o, tm))
        continue;
      const std::uint32_t u = band.metric_mesh().vertex_index(source(h, tm)), v = band.metric_mesh().vertex_index(target(h, tm));
      const std::uint32_t other = band.metric_mesh().face_index(face(o, tm));
      const auto& oc = band.metric_mesh().corners(other);
      for(int k = 0; k < 3; ++k)
        if(c[k] == u && c[(k + 1) % 3] == v)
          g.neighbour[f][k] = other;
      for(int k = 0; k < 3; ++k)
        if(oc[k] == v && oc[(k + 1) % 3] == u)
          for(int j = 0; j < 3; ++j)
            if(c[j] == u && c[(j + 1) % 3] == v)
              g.neighbour_edge[f][j] = std::uint8_t(k);
    }
  }
  return g;
}

// Whether two stretches agree within the factor 1 + tolerance.
inline bool similar_stretch(double a, double b, double tolerance)
{
  return std::max(a, b) <= (1 + tolerance) * std::min(a, b);
}

// Weighted median of (value, weight) pairs (sorts them); 1 when empty.
inline double weighted_median(std::vector<std::pair<double, double>>& samples)
{
  std::sort(samples.begin(), samples.end());
  double total = 0, seen = 0;
  for(const auto& x : samples)
    total += x.second;
  for(const auto& x : samples)
  {
    seen += x.second;
    if(seen >= 0.5 * total)
      return x.first;
  }
  return samples.empty() ? 1.0 : samples.back().first;
}

// Area-weighted median face stretch of every patch.
inline std::vector<double> typical_stretches(const Patch_merge_geometry& g, const std::vector<std::size_t>& patch,
                                             std::size_t patches)
{
  std::vector<std::vector<std::pair<double, double>>> samples(patches);
  for(std::size_t f = 0; f < patch.size(); ++f)
    samples[patch[f]].push_back({g.face_stretch[f], g.area[f]});
  std::vector<double> typical(patches);
  for(std::size_t p = 0; p < patches; ++p)
    typical[p] = weighted_median(samples[p]);
  return typical;
}

// Renumbers patch indices from 0 in order of first face; returns the number of patches.
inline std::size_t renumber_patches(std::vector<std::size_t>& patch, std::size_t patches)
{
  std::vector<std::size_t> index(patches, std::size_t(-1));
  std::size_t next = 0;
  for(std::size_t& p : patch)
  {
    if(index[p] == std::size_t(-1))
      index[p] = next++;
    p = index[p];
  }
  return next;
}

// Merges adjacent patches whose common boundary is not a feature: the median stretch across their
// common edges (weighted by edge length) is at most (1 + tolerance) times the typical stretch of each
// of the two patches (the area-weighted median of its face stretches), and the two typical stretches
// agree within the factor 1 + tolerance. Medians, so that the few faces at the end of a boundary
// that touch a sharp edge do not decide. Rounds of merges, each patch
// merged at most once per round, most similar pairs first, until no pair qualifies. Patch indices are
// renumbered from 0 in order of first face; returns the number of patches.
inline std::size_t merge_non_feature_patches(const Patch_merge_geometry& g, std::vector<std::size_t>& patch,
                                             std::size_t patches, double tolerance)
{
  const std::uint32_t nf = static_cast<std::uint32_t>(patch.size());
  for(;;)
  {
    const std::vector<double> typical = typical_stretches(g, patch, patches);
    // median stretch across the common boundary of every adjacent pair
    std::vector<std::pair<std::pair<std::size_t, std::size_t>, std::array<double, 2>>> crossings;
    for(std::uint32_t f = 0; f < nf; ++f)
      for(int k = 0; k < 3; ++k)
      {
        const std::uint32_t o = g.neighbour[f][k];
        if(o == std::uint32_t(-1) || o < f || patch[o] == patch[f])
          continue;
        const int j = g.neighbour_edge[f][k];
        const double across = g.euclidean[f][k] + g.euclidean[o][j];
        if(!(across > 0))
          continue;
        crossings.push_back({std::minmax(patch[f], patch[o]), {{(g.lifted[f][k] + g.lifted[o][j]) / across, g.edge_length[f][k]}}});
      }
    std::sort(crossings.begin(), crossings.end());
    std::vector<std::pair<double, std::pair<std::size_t, std::size_t>>> candidates;
    for(std::size_t i = 0; i < crossings.size();)
    {
      std::vector<std::pair<double, double>> boundary; // (stretch, weight)
      std::size_t j = i;
      for(; j < crossings.size() && crossings[j].first == crossings[i].first; ++j)
        boundary.push_back({crossings[j].second[0], crossings[j].second[1]});
      const auto pair = crossings[i].first;
      const double ratio = weighted_median(boundary) / std::min(typical[pair.first], typical[pair.second]);
      if(ratio <= 1 + tolerance && similar_stretch(typical[pair.first], typical[pair.second], tolerance))
        candidates.push_back({ratio, pair});
      i = j;
    }
    if(candidates.empty())
      break;
    std::sort(candidates.begin(), candidates.end());
    std::vector<std::size_t> target(patches);
    std::iota(target.begin(), target.end(), 0);
    std::vector<char> used(patches, 0);
    for(const auto& c : candidates)
    {
      const auto [a, b] = c.second;
      if(used[a] || used[b])
        continue;
      used[a] = used[b] = 1;
      target[b] = a;
    }
    for(std::uint32_t f = 0; f < nf; ++f)
      patch[f] = target[patch[f]];
    patches = renumber_patches(patch, patches);
  }
  return patches;
}

// Gives every edge-connected piece of a patch its own patch index; returns the number of patches.
inline std::size_t split_into_connected_patches(const Patch_merge_geometry& g, std::vector<std::size_t>& patch)
{
  const std::size_t none = std::size_t(-1);
  std::vector<std::size_t> piece_of(patch.size(), none);
  std::size_t pieces = 0;
  for(std::uint32_t f = 0; f < patch.size(); ++f)
    if(piece_of[f] == none)
    {
      std::vector<std::uint32_t> piece{f};
      piece_of[f] = pieces;
      for(std::size_t i = 0; i < piece.size(); ++i)
        for(int k = 0; k < 3; ++k)
        {
          const std::uint32_t o = g.neighbour[piece[i]][k];
          if(o != std::uint32_t(-1) && piece_of[o] == none && patch[o] == patch[f])
          {
            piece_of[o] = pieces;
            piece.push_back(o);
          }
        }
      ++pieces;
    }
  patch.swap(piece_of);
  return pieces;
}

// Splits off the faces whose stretch is unlike the typical stretch of their patch (outside the factor
// 1 + tolerance) into new patches: edge-connected faces of one patch whose stretches are within that
// factor of the first one's. The greedy cover's regions reach across the line where a fillet meets a
// plane tangentially (the normal turns continuously there, so crossing it is short in the metric)
// and across the faces along a sharp edge: the fillet's first row and these faces must not count as
// the plane. What remains of a patch may fall apart: each piece becomes a patch. Returns the number
// of patches, renumbered as by renumber_patches().
inline std::size_t split_unlike_faces(const Patch_merge_geometry& g, std::vector<std::size_t>& patch,
                                      std::size_t patches, double tolerance)
{
  const std::uint32_t nf = static_cast<std::uint32_t>(patch.size());
  const std::vector<double> typical = typical_stretches(g, patch, patches);
  std::vector<char> unlike(nf, 0);
  for(std::uint32_t f = 0; f < nf; ++f)
    unlike[f] = !similar_stretch(g.face_stretch[f], typical[patch[f]], tolerance);
  const std::size_t before = patches;
  for(std::uint32_t f = 0; f < nf; ++f)
    if(unlike[f] && patch[f] < before)
    {
      const std::size_t from = patch[f];
      std::vector<std::uint32_t> piece{f};
      patch[f] = patches;
      for(std::size_t i = 0; i < piece.size(); ++i)
        for(int k = 0; k < 3; ++k)
        {
          const std::uint32_t o = g.neighbour[piece[i]][k];
          if(o != std::uint32_t(-1) && unlike[o] && patch[o] == from && similar_stretch(g.face_stretch[o], g.face_stretch[f], tolerance))
          {
            patch[o] = patches;
            piece.push_back(o);
          }
        }
      ++patches;
    }
  return split_into_connected_patches(g, patch);
}

// Patches one face wide (every face has an edge on the patch's boundary), such as the faces along a
// sharp edge, where the lift smears the jump of the normal over the adjacent faces, or the row of
// faces along the line where a fillet meets a plane, are below the resolution of the mesh: each of
// their faces joins, among the patches across its edges that lead out of the strips, the one whose
// typical stretch is closest to its own (as a ratio: a row at a tangent line goes to its own side), the
// longest edge deciding between equally close ones (the two planes at a sharp edge); repeated inward
// for faces with no such edge. Returns the number of patches, renumbered as by renumber_patches().
inline std::size_t absorb_strip_patches(const Patch_merge_geometry& g, std::vector<std::size_t>& patch, std::size_t patches)
{
  const std::uint32_t nf = static_cast<std::uint32_t>(patch.size());
  std::vector<char> strip(patches, 1);
  for(std::uint32_t f = 0; f < nf; ++f)
  {
    bool on_boundary = false;
    for(int k = 0; k < 3; ++k)
      on_boundary = on_boundary || (g.neighbour[f][k] != std::uint32_t(-1) && patch[g.neighbour[f][k]] != patch[f]);
    if(!on_boundary)
      strip[patch[f]] = 0;
  }
  const std::vector<double> typical = typical_stretches(g, patch, patches);
  std::vector<char> pending(nf, 0);
  std::vector<std::uint32_t> left;
  for(std::uint32_t f = 0; f < nf; ++f)
    if(strip[patch[f]])
    {
      pending[f] = 1;
      left.push_back(f);
    }
  for(bool changed = true; changed && !left.empty();)
  {
    changed = false;
    std::vector<std::pair<std::uint32_t, std::size_t>> moves;
    std::vector<std::uint32_t> still;
    for(std::uint32_t f : left)
    {
      // (stretch unlike the patch's, -length): smallest first
      std::array<double, 2> best{{std::numeric_limits<double>::infinity(), 0}};
      std::size_t to = patches;
      for(int k = 0; k < 3; ++k)
      {
        const std::uint32_t o = g.neighbour[f][k];
        if(o == std::uint32_t(-1) || pending[o])
          continue;
        const std::array<double, 2> key{{std::abs(std::log(g.face_stretch[f] / typical[patch[o]])), -g.edge_length[f][k]}};
        if(key < best)
        {
          best = key;
          to = patch[o];
        }
      }
      if(to != patches)
        moves.push_back({f, to});
      else
        still.push_back(f);
    }
    for(const auto& m : moves)
    {
      patch[m.first] = m.second;
      pending[m.first] = 0;
      changed = true;
    }
    left.swap(still);
  }
  return renumber_patches(patch, patches);
}

} // namespace internal

/// \ingroup PkgIsophoticMetricRegionGrowing
///
/// \brief grows a region from seed faces in the isophotic metric: the faces within `radius` of the
/// seeds that pass the optional predicate and are connected to the seeds across edges through such
/// faces. Because crossing a sharp edge or a fillet is long in the isophotic metric, the region spreads
/// along features and stops at them.
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{face_predicate}
///     \cgalParamDescription{a callable `bool(face_descriptor)`: faces for which it is `false` never join
///       (e.g. a normal-deviation or curvature test)} \cgalParamDefault{every face may join} \cgalParamNEnd
///   \cgalParamNBegin{area_fraction} \cgalParamDescription{fraction of a face's area that must lie within
///     `radius`, as for `dilate_face_selection()`} \cgalParamDefault{`0`: the face joins when it meets the
///     disc} \cgalParamNEnd
///   \cgalParamNBegin{euclidean_weight, isophotic_weight, weight_length_scale, face_band_solver}
///     \cgalParamDescription{the metric, see `dilate_face_selection()`} \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \returns `out` after the faces of the region (the seeds first)
template <class FaceRange, class TriangleMesh, class OutputIterator, class NamedParameters = parameters::Default_named_parameters>
OutputIterator grow_region(const FaceRange& seeds, const TriangleMesh& tm, double radius, OutputIterator out,
                           const NamedParameters& np = parameters::default_values())
{
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;
  internal::check_radius(radius);
  const double fraction = internal::read_area_fraction(np);
  const std::function<bool(face_descriptor)> all = [](face_descriptor) { return true; };
  const auto predicate = parameters::choose_parameter(parameters::get_parameter(np, internal_np::face_predicate), all);
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) {
    const std::vector<std::uint32_t> seed_ids = internal::face_indices(band, seeds);
    if(seed_ids.empty())
      return out;
    for(std::uint32_t f : internal::grow_connected(band, seed_ids, radius, fraction,
                                                   [&](std::uint32_t f) { return bool(predicate(band.metric_mesh().face(f))); }))
      *out++ = band.metric_mesh().face(f);
    return out;
  });
}

/// \ingroup PkgIsophoticMetricRegionGrowing
///
/// \brief partitions the faces by their nearest seed in the isophotic metric (a geodesic Voronoi
/// partition): seed `i` (a range of faces, the `i`-th element of `seeds`) is source `i`, and every face
/// whose centroid is within `max_distance` (default: no bound) takes the index of the seed nearest to its
/// centroid. Faces beyond the bound, or unreachable, get `seeds.size()`. One propagation in all.
///
/// \tparam SeedRange a range of ranges of face descriptors
/// \tparam FacePatchMap a writable property map from faces to an integer type
/// \returns the number of faces assigned to a seed
template <class SeedRange, class TriangleMesh, class FacePatchMap, class NamedParameters = parameters::Default_named_parameters>
std::size_t partition_by_nearest_seed(const SeedRange& seeds, const TriangleMesh& tm, FacePatchMap patch,
                                      const NamedParameters& np = parameters::default_values())
{
  const double max_distance = parameters::choose_parameter(parameters::get_parameter(np, internal_np::max_distance),
                                                           std::numeric_limits<double>::infinity());
  if(!(max_distance >= 0))
    throw Invalid_parameter_error("max_distance must be non-negative (got " + std::to_string(max_distance) + ")");
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) -> std::size_t {
    band.clear_sources();
    std::size_t n = 0;
    for(const auto& seed : seeds)
    {
      const std::vector<std::uint32_t> ids = internal::face_indices(band, seed);
      if(ids.empty())
        throw Invalid_source_error("seed " + std::to_string(n) + " has no face");
      internal::add_source_region_by_index(band, ids);
      ++n;
    }
    std::size_t assigned = 0;
    if(n == 0)
      return 0;
    band.propagate_to(max_distance);
    for(std::uint32_t f = 0; f < band.metric_mesh().number_of_faces(); ++f)
    {
      const typename Face_band_solver<TriangleMesh>::Face_location c(band.metric_mesh().face(f), {{1.0 / 3, 1.0 / 3, 1.0 / 3}});
      const std::size_t label = band.geodesic_solver().nearest_source(c);
      const bool ok = label != Face_band_solver<TriangleMesh>::no_source && band.geodesic_solver().distance(c) <= max_distance;
      put(patch, band.metric_mesh().face(f), ok ? label : n);
      assigned += ok;
    }
    return assigned;
  });
}

/// \ingroup PkgIsophoticMetricRegionGrowing
///
/// \brief segments the mesh by region growing in the isophotic metric, then merges the patches whose
/// common boundary is not a feature.
///
/// 1. Greedy cover: the unassigned face of largest area seeds a region grown by `grow_region()` with
///    radius `radius` among the unassigned faces, which becomes a patch; repeated until every face is
///    assigned. The radius bounds every patch, so a large smooth surface ends up in several patches.
/// 2. Merge. The *stretch* of the metric along a segment is its metric length over its length in
///    space: \f$ \sqrt{w} \f$ on a plane, up to \f$ \sqrt{w + w' L^2 \kappa^2} \f$ across a curvature
///    \f$ \kappa \f$. It is measured from edge lengths only, on the segments from the centroid of a face
///    to the midpoints of its edges (a third of a median, known from the three edge lengths in space
///    and in the metric). The stretch of a face is the largest of its three; the stretch across an edge
///    is that of the path from one centroid to the other through the edge's midpoint. First, the faces
///    whose stretch is not within the factor \f$ 1 + \tau \f$ of their patch's typical stretch
///    (area-weighted median of the face stretches) are split off into patches of their own (grouped by
///    edge-connected faces of like stretch): where a fillet meets a plane tangentially the normal turns
///    continuously, so crossing that line is short in the metric and a region of the cover reaches into
///    the fillet's first row; it also takes the faces along a sharp edge. Then two adjacent
///    patches merge when the length-weighted median stretch across their common edges is at most
///    \f$ 1 + \tau \f$ times the typical stretch of each,
///    and their typical stretches agree within the factor \f$ 1 + \tau \f$, \f$ \tau \f$ =
///    `merge_tolerance`. So pieces of one plane, or of one fillet, merge; a plane and a fillet, or two
///    planes across a sharp edge, do not. Patches one face wide (every face with an edge on the patch's
///    boundary), typically the faces along a sharp edge, over which the lift smears the jump of the
///    normal, or the row of faces along a tangent line, whose vertex normals average both sides, are
///    below the resolution of the mesh: each of their faces joins the neighbouring patch whose typical
///    stretch is closest to its own (across its longest edge between equally close ones). Merges run
///    in rounds, each patch merged at most once per round, most similar pairs first, until no pair
///    qualifies.
///
/// Patch indices start at 0, numbered in the order of the faces. Named parameters as `grow_region()`, and:
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{merge_tolerance} \cgalParamDescription{\f$ \tau \ge 0 \f$: the factor
///     \f$ 1 + \tau \f$ by which two stretches may differ and still be the same surface; a negative
///     value skips the merge (the greedy cover alone); NaN throws `Invalid_parameter_error`}
///     \cgalParamDefault{`0.5`} \cgalParamNEnd
///   \cgalParamNBegin{vertex_point_map} \cgalParamDescription{the vertex positions (lengths in space
///     of the merge test)} \cgalParamDefault{`boost::get(CGAL::vertex_point, tm)`} \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \param tm the mesh
/// \param radius the radius of the greedy cover's regions
/// \param patch receives the patch index of every face
/// \param np the named parameters
/// \returns the number of patches
template <class TriangleMesh, class FacePatchMap, class NamedParameters = parameters::Default_named_parameters>
std::size_t segment_by_region_growing(const TriangleMesh& tm, double radius, FacePatchMap patch,
                                      const NamedParameters& np = parameters::default_values())
{
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;
  internal::check_radius(radius);
  const double fraction = internal::read_area_fraction(np);
  const std::function<bool(face_descriptor)> all = [](face_descriptor) { return true; };
  const auto predicate = parameters::choose_parameter(parameters::get_parameter(np, internal_np::face_predicate), all);
  const double merge_tolerance = parameters::choose_parameter(parameters::get_parameter(np, internal_np::merge_tolerance), 0.5);
  if(std::isnan(merge_tolerance))
    throw Invalid_parameter_error("merge_tolerance must be a number");
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) -> std::size_t {
    const std::size_t nf = band.metric_mesh().number_of_faces();
    std::vector<double> area(nf);
    for(std::uint32_t f = 0; f < nf; ++f)
      area[f] = CGAL::Polygon_mesh_processing::face_area(band.metric_mesh().face(f), tm);
    std::vector<std::uint32_t> order(nf);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return area[a] > area[b]; });
    const std::size_t none = static_cast<std::size_t>(-1);
    std::vector<std::size_t> assigned(nf, none);
    std::size_t patches = 0;
    for(std::uint32_t seed : order)
    {
      if(assigned[seed] != none)
        continue;
      const std::vector<std::uint32_t> region = internal::grow_connected(band, {seed}, radius, fraction, [&](std::uint32_t f) {
        return assigned[f] == none && bool(predicate(band.metric_mesh().face(f)));
      });
      for(std::uint32_t f : region)
        assigned[f] = patches;
      ++patches;
    }
    if(merge_tolerance >= 0)
    {
      const auto vpm = parameters::choose_parameter(parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                                                    get_const_property_map(CGAL::vertex_point, tm));
      const internal::Patch_merge_geometry geometry = internal::patch_merge_geometry(band, vpm);
      patches = internal::split_unlike_faces(geometry, assigned, patches, merge_tolerance);
      patches = internal::absorb_strip_patches(geometry, assigned, patches);
      patches = internal::merge_non_feature_patches(geometry, assigned, patches, merge_tolerance);
      patches = internal::absorb_strip_patches(geometry, assigned, patches);
      patches = internal::merge_non_feature_patches(geometry, assigned, patches, merge_tolerance);
    }
    for(std::uint32_t f = 0; f < nf; ++f)
      put(patch, band.metric_mesh().face(f), assigned[f]);
    return patches;
  });
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_SEGMENTATION_REGION_GROWING_H
