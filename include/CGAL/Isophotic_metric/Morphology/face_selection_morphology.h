// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Binary morphology of face selections with a metric radius (dilation, erosion, opening, closing),
// in the style of CGAL's expand_face_selection / reduce_face_selection, plus their k-ring variants.
#ifndef CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_FACE_SELECTION_MORPHOLOGY_H
#define CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_FACE_SELECTION_MORPHOLOGY_H

#include <CGAL/Isophotic_metric/Morphology/Face_band_solver.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/exceptions.h>

#include <CGAL/boost/graph/selection.h>
#include <CGAL/iterator.h>

#include <cstdint>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

namespace internal {


// Adds to `is_selected` the faces that are not selected and whose covered fraction of the disc of
// radius r around the region `source_faces` reaches `fraction` (or that meet it when fraction is 0);
// calls `report(face index)` for each of them. The selection map is written after the search.
template <class TriangleMesh, class IsSelected, class Report>
void grow_into_unselected(Face_band_solver<TriangleMesh>& band, const std::vector<std::uint32_t>& source_faces,
                          double radius, double fraction, IsSelected&& is_selected, Report&& report)
{
  if(source_faces.empty())
    return;
  band.clear_sources();
  add_source_region_by_index(band, source_faces);
  std::vector<std::uint32_t> reached;
  band.visit_band(radius, fraction > 0, false, [&](const typename Face_band_solver<TriangleMesh>::Face_visit& v) {
    if(!is_selected(v.face_index) && (fraction == 0 || v.covered_fraction >= fraction))
      reached.push_back(v.face_index);
  });
  for(std::uint32_t f : reached)
    report(f);
}

// Indices of the faces of a range, checked to belong to the mesh.
template <class TriangleMesh, class FaceRange>
std::vector<std::uint32_t> face_indices(const Face_band_solver<TriangleMesh>& band, const FaceRange& faces)
{
  std::vector<std::uint32_t> ids;
  for(const auto& f : faces)
    ids.push_back(band.metric_mesh().face_index(f));
  return ids;
}

// The unselected faces sharing a vertex with a selected one: the part of the complement that is
// nearest to every selected face (a geodesic leaving the selection first enters one of them).
template <class TriangleMesh, class InSelection>
std::vector<std::uint32_t> complement_next_to(const Face_band_solver<TriangleMesh>& band,
                                              const std::vector<std::uint32_t>& selection, InSelection&& in_selection)
{
  std::vector<char> taken(band.metric_mesh().number_of_faces(), 0);
  std::vector<std::uint32_t> border;
  for(std::uint32_t f : selection)
    for(std::uint32_t c : band.metric_mesh().corners(f))
      for(std::uint32_t g : band.metric_mesh().incident_faces(c))
        if(!in_selection(g) && !taken[g])
        {
          taken[g] = 1;
          border.push_back(g);
        }
  return border;
}

template <class TriangleMesh, class IsFaceSelectedPMap, class OutputIterator>
OutputIterator dilate(Face_band_solver<TriangleMesh>& band, const std::vector<std::uint32_t>& selection, double radius,
                      double fraction, IsFaceSelectedPMap is_selected, OutputIterator out)
{
  grow_into_unselected(band, selection, radius, fraction,
                       [&](std::uint32_t f) { return bool(get(is_selected, band.metric_mesh().face(f))); },
                       [&](std::uint32_t f) {
                         put(is_selected, band.metric_mesh().face(f), true);
                         *out++ = band.metric_mesh().face(f);
                       });
  return out;
}

template <class TriangleMesh, class IsFaceSelectedPMap, class OutputIterator>
OutputIterator erode(Face_band_solver<TriangleMesh>& band, const std::vector<std::uint32_t>& selection, double radius,
                     double fraction, IsFaceSelectedPMap is_selected, OutputIterator out)
{
  std::vector<char> in_selection(band.metric_mesh().number_of_faces(), 0);
  for(std::uint32_t f : selection)
    in_selection[f] = 1;
  const std::vector<std::uint32_t> complement =
    complement_next_to(band, selection, [&](std::uint32_t f) { return in_selection[f] != 0; });
  // erosion = complement of the dilation of the complement
  grow_into_unselected(band, complement, radius, fraction, [&](std::uint32_t f) { return in_selection[f] == 0; },
                       [&](std::uint32_t f) {
                         put(is_selected, band.metric_mesh().face(f), false);
                         *out++ = band.metric_mesh().face(f);
                       });
  return out;
}

template <class TriangleMesh, class IsFaceSelectedPMap>
std::vector<std::uint32_t> selected_faces(const Face_band_solver<TriangleMesh>& band, IsFaceSelectedPMap is_selected)
{
  std::vector<std::uint32_t> s;
  for(std::uint32_t f = 0; f < band.metric_mesh().number_of_faces(); ++f)
    if(get(is_selected, band.metric_mesh().face(f)))
      s.push_back(f);
  return s;
}

} // namespace internal

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief dilates a selection of faces by a metric radius: a face joins when it comes within
/// `radius` of the selection in the isophotic metric.
///
/// The distance is the exact distance to the union of the selected closed faces, computed by one
/// bounded propagation (its cost follows the dilated band, not the mesh). With `area_fraction` 0 a face
/// joins when the minimum distance over the closed face is at most `radius` (so a radius of 0 adds the
/// faces sharing a vertex with the selection); with `area_fraction` \f$ a > 0 \f$ it joins when at least
/// the fraction \f$ a \f$ of its area lies within `radius` (see `Face_band_solver` for how the minimum and
/// the fraction are computed).
///
/// As `CGAL::expand_face_selection()`: `is_selected` is updated and every face added is written once
/// into `out`. Faces already selected in `is_selected` are never written.
///
/// \tparam FaceRange a range of `boost::graph_traits<TriangleMesh>::%face_descriptor`
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph`
/// \tparam IsFaceSelectedPMap a model of `ReadWritePropertyMap` with face descriptors as key and `bool` as value
/// \tparam OutputIterator an output iterator accepting face descriptors
///
/// \param selection the selected faces
/// \param tm the mesh
/// \param radius the metric radius, finite and non-negative
/// \param is_selected whether a face is selected; updated
/// \param out receives the faces added
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{area_fraction}
///     \cgalParamDescription{the fraction of its area a face must have within `radius` to join}
///     \cgalParamType{`double` in [0,1]} \cgalParamDefault{`0`: the face joins when it meets the disc} \cgalParamNEnd
///   \cgalParamNBegin{area_resolution}
///     \cgalParamDescription{subdivision of a face (`n²` sub-triangles) for the area fraction}
///     \cgalParamType{`int` in [1,64]} \cgalParamDefault{`4`} \cgalParamNEnd
///   \cgalParamNBegin{euclidean_weight, isophotic_weight, weight_length_scale, vertex_point_map, vertex_normal_map, lifted_embedding_map}
///     \cgalParamDescription{the metric, see `Geodesic_solver`} \cgalParamNEnd
///   \cgalParamNBegin{face_band_solver}
///     \cgalParamDescription{a `Face_band_solver<TriangleMesh>*` built on `tm`, reused instead of building
///       a new one (the metric parameters are then ignored)} \cgalParamDefault{a new solver} \cgalParamNEnd
///   \cgalParamNBegin{callback}
///     \cgalParamDescription{told now and then of the advancement in [0,1] of the current propagation
///       (or loop over faces or vertices), at least once each; returning `false` stops the operation
///       with a `Cancelled_error` (a `face_band_solver` passed in must then have its sources cleared)}
///     \cgalParamType{a callable `bool(double)`, called from one thread at a time} \cgalParamDefault{none} \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// With `area_fraction` 0, on a `Surface_mesh` and a metric of constant weights, only the part of the
/// mesh within reach of the radius is prepared and validated (see \ref IsophoticMetricReach).
///
/// \returns `out` after the faces added
/// \throws Invalid_parameter_error for a negative or non-finite radius, or an area fraction outside [0,1]
/// \throws Invalid_source_error when a face of `selection` is not a face of `tm`
/// \throws Cancelled_error when the callback asks to stop
template <class FaceRange, class TriangleMesh, class IsFaceSelectedPMap, class OutputIterator,
          class NamedParameters = parameters::Default_named_parameters>
OutputIterator dilate_face_selection(const FaceRange& selection, const TriangleMesh& tm, double radius,
                                     IsFaceSelectedPMap is_selected, OutputIterator out,
                                     const NamedParameters& np = parameters::default_values())
{
  internal::check_radius(radius);
  const double fraction = internal::read_area_fraction(np);
  internal::Reach_sources<TriangleMesh> sources;
  sources.faces.assign(std::begin(selection), std::end(selection));
  return internal::with_band_solver(tm, np, sources, radius, fraction, [&](Face_band_solver<TriangleMesh>& band) {
    return internal::dilate(band, internal::face_indices(band, selection), radius, fraction, is_selected, out);
  });
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief erodes a selection of faces by a metric radius: the dual of `dilate_face_selection()`.
///
/// A selected face leaves when it comes within `radius` of the unselected faces (the complement of
/// the selection given by `is_selected`; the border of the mesh is not part of it), with the same
/// rule and named parameters as `dilate_face_selection()`. The result is exactly the complement of the
/// dilation of the complement. As `CGAL::reduce_face_selection()`: `is_selected` is updated and every
/// face removed is written once into `out`.
///
/// \returns `out` after the faces removed
/// \throws Invalid_parameter_error for a negative or non-finite radius, or an area fraction outside [0,1]
/// \throws Invalid_source_error when a face of `selection` is not a face of `tm`
template <class FaceRange, class TriangleMesh, class IsFaceSelectedPMap, class OutputIterator,
          class NamedParameters = parameters::Default_named_parameters>
OutputIterator erode_face_selection(const FaceRange& selection, const TriangleMesh& tm, double radius,
                                    IsFaceSelectedPMap is_selected, OutputIterator out,
                                    const NamedParameters& np = parameters::default_values())
{
  internal::check_radius(radius);
  const double fraction = internal::read_area_fraction(np);
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) {
    return internal::erode(band, internal::face_indices(band, selection), radius, fraction, is_selected, out);
  });
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief opens the selection `is_selected` (erosion, then dilation, by `radius`): removes the parts of
/// the selection narrower than the disc, keeps the rest. With `area_fraction` 0 the opening is
/// anti-extensive and idempotent (erosion and dilation form an adjunction); see the manual for the
/// fraction rule. Named parameters as `dilate_face_selection()`; the metric is built once.
template <class TriangleMesh, class IsFaceSelectedPMap, class NamedParameters = parameters::Default_named_parameters>
void open_face_selection(const TriangleMesh& tm, double radius, IsFaceSelectedPMap is_selected,
                         const NamedParameters& np = parameters::default_values())
{
  internal::check_radius(radius);
  const double fraction = internal::read_area_fraction(np);
  internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) {
    internal::erode(band, internal::selected_faces(band, is_selected), radius, fraction, is_selected, CGAL::Emptyset_iterator());
    internal::dilate(band, internal::selected_faces(band, is_selected), radius, fraction, is_selected, CGAL::Emptyset_iterator());
    return 0;
  });
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief closes the selection `is_selected` (dilation, then erosion, by `radius`): fills the gaps
/// and notches narrower than the disc. With `area_fraction` 0 the closing is extensive and idempotent.
/// Named parameters as `dilate_face_selection()`; the metric is built once.
template <class TriangleMesh, class IsFaceSelectedPMap, class NamedParameters = parameters::Default_named_parameters>
void close_face_selection(const TriangleMesh& tm, double radius, IsFaceSelectedPMap is_selected,
                          const NamedParameters& np = parameters::default_values())
{
  internal::check_radius(radius);
  const double fraction = internal::read_area_fraction(np);
  internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) {
    internal::dilate(band, internal::selected_faces(band, is_selected), radius, fraction, is_selected, CGAL::Emptyset_iterator());
    internal::erode(band, internal::selected_faces(band, is_selected), radius, fraction, is_selected, CGAL::Emptyset_iterator());
    return 0;
  });
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief the combinatorial dilation \f$ N_k \f$ of the paper: `k` times, every face sharing a vertex
/// (or an edge) with the selection joins. This is `CGAL::expand_face_selection()`, whose adjacency is
/// "share a vertex or an edge"; offered here for symmetry with the metric version.
template <class FaceRange, class TriangleMesh, class IsFaceSelectedPMap, class OutputIterator>
OutputIterator dilate_face_selection_k_ring(const FaceRange& selection, const TriangleMesh& tm, unsigned int k,
                                            IsFaceSelectedPMap is_selected, OutputIterator out)
{
  return CGAL::expand_face_selection(selection, tm, k, is_selected, out);
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief the combinatorial erosion: `k` times, every selected face sharing a vertex (or an edge) with
/// an unselected face leaves. This is `CGAL::reduce_face_selection()`.
template <class FaceRange, class TriangleMesh, class IsFaceSelectedPMap, class OutputIterator>
OutputIterator erode_face_selection_k_ring(const FaceRange& selection, const TriangleMesh& tm, unsigned int k,
                                           IsFaceSelectedPMap is_selected, OutputIterator out)
{
  return CGAL::reduce_face_selection(selection, tm, k, is_selected, out);
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_FACE_SELECTION_MORPHOLOGY_H
