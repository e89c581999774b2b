// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Morphology of labelled meshes (indexed partitions of the faces): geodesic Voronoi growth of labels
// into unlabelled faces, per-class erosion, opening and closing, and series of closings.
#ifndef CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_LABEL_MORPHOLOGY_H
#define CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_LABEL_MORPHOLOGY_H

#include <CGAL/Isophotic_metric/Morphology/Face_band_solver.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Morphology/face_selection_morphology.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

namespace internal {

// The faces of every class, by label value (in increasing label order).
template <class TriangleMesh, class FaceLabelMap, class Label>
std::map<Label, std::vector<std::uint32_t>> label_classes(const Face_band_solver<TriangleMesh>& band, const FaceLabelMap& labels,
                                                         const Label& unlabelled)
{
  std::map<Label, std::vector<std::uint32_t>> classes;
  for(std::uint32_t f = 0; f < band.metric_mesh().number_of_faces(); ++f)
  {
    const Label l = get(labels, band.metric_mesh().face(f));
    if(!(l == unlabelled))
      classes[l].push_back(f);
  }
  return classes;
}

// A class as a binary selection: a read-write property map over a membership vector (1 = selected),
// as the binary operations of face_selection_morphology.h take it.
template <class TriangleMesh>
struct Membership_map
{
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor key_type;
  typedef bool value_type;
  typedef bool reference;
  typedef boost::read_write_property_map_tag category;
  const Face_band_solver<TriangleMesh>* band;
  std::vector<char>* member;
  friend bool get(const Membership_map& m, key_type f) { return (*m.member)[m.band->metric_mesh().face_index(f)] != 0; }
  friend void put(const Membership_map& m, key_type f, bool b) { (*m.member)[m.band->metric_mesh().face_index(f)] = b; }
};

template <class TriangleMesh>
std::vector<std::uint32_t> members_of(const std::vector<char>& member)
{
  std::vector<std::uint32_t> m;
  for(std::uint32_t f = 0; f < member.size(); ++f)
    if(member[f])
      m.push_back(f);
  return m;
}

// Runs `operation(label, faces, selection, member)` for every class, one at a time on the same scratch
// membership vector: `member` and `selection` (its property map) start as the class's faces, the
// operation may change them, and they are cleared before the next class, so that every class is
// processed from the input labelling.
template <class TriangleMesh, class Classes, class Operation>
void for_each_class_selection(const Face_band_solver<TriangleMesh>& band, const Classes& classes, Operation&& operation)
{
  std::vector<char> member(band.metric_mesh().number_of_faces(), 0);
  for(const auto& c : classes)
  {
    for(std::uint32_t f : c.second)
      member[f] = 1;
    operation(c.first, c.second, Membership_map<TriangleMesh>{&band, &member}, member);
    std::fill(member.begin(), member.end(), 0);
  }
}

// The skeleton of the per-class operations that only remove faces from classes (erosion, opening):
// `transform(band, faces, radius, fraction, selection, member)` changes each class's selection, from
// the input labelling; the faces of a class that its transform dropped become unlabelled at the end.
template <class TriangleMesh, class FaceLabelMap, class NamedParameters, class Transform>
std::size_t unlabel_what_each_class_drops(const TriangleMesh& tm, double radius, FaceLabelMap labels,
                                          const typename boost::property_traits<FaceLabelMap>::value_type& unlabelled,
                                          const NamedParameters& np, Transform&& transform)
{
  check_radius(radius);
  const double fraction = read_area_fraction(np);
  return with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) -> std::size_t {
    std::vector<std::uint32_t> removed;
    for_each_class_selection(band, label_classes(band, labels, unlabelled),
                             [&](const auto&, const auto& faces, auto selection, const std::vector<char>& member) {
      transform(band, faces, radius, fraction, selection, member);
      for(std::uint32_t f : faces)
        if(!member[f])
          removed.push_back(f);
    });
    for(std::uint32_t f : removed)
      put(labels, band.metric_mesh().face(f), unlabelled);
    return removed.size();
  });
}

} // namespace internal

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief grows every label into the unlabelled faces within `radius`: a geodesic Voronoi partition
/// of the band around the labelled faces in the isophotic metric.
///
/// One propagation with one region source per label (the union of the faces carrying it). An unlabelled
/// face that meets the disc (with `area_fraction` \f$ a > 0 \f$: whose area lies within `radius` of the
/// labelled faces for at least the fraction \f$ a \f$) takes the label of the source nearest to its
/// closest point (located to \f$ 10^{-6} \f$ of its longest edge). Where two labels are at exactly
/// the same distance the propagation's choice is kept (deterministic for a given mesh and labelling).
/// Labelled faces never change.
///
/// \tparam FaceLabelMap a model of `ReadWritePropertyMap` with face descriptors as key; its value type
///   is the label type, comparable with `<` and `==`
/// `unlabelled` is the label value of unlabelled faces.
/// \returns the number of faces that received a label
///
/// Named parameters as `dilate_face_selection()`.
template <class TriangleMesh, class FaceLabelMap, class NamedParameters = parameters::Default_named_parameters>
std::size_t dilate_face_labels(const TriangleMesh& tm, double radius, FaceLabelMap labels,
                               const typename boost::property_traits<FaceLabelMap>::value_type& unlabelled,
                               const NamedParameters& np = parameters::default_values())
{
  typedef typename boost::property_traits<FaceLabelMap>::value_type Label;
  internal::check_radius(radius);
  const double fraction = internal::read_area_fraction(np);
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) -> std::size_t {
    const auto classes = internal::label_classes(band, labels, unlabelled);
    if(classes.empty())
      return 0;
    band.clear_sources();
    std::vector<Label> label_of_source;
    for(const auto& c : classes)
    {
      internal::add_source_region_by_index(band, c.second);
      label_of_source.push_back(c.first);
    }
    std::vector<std::pair<std::uint32_t, Label>> grown;
    band.visit_band(radius, fraction > 0, true, [&](const typename Face_band_solver<TriangleMesh>::Face_visit& v) {
      if(get(labels, v.face) == unlabelled && (fraction == 0 || v.covered_fraction >= fraction) &&
         v.label < label_of_source.size())
        grown.push_back({v.face_index, label_of_source[v.label]});
    });
    for(const auto& g : grown)
      put(labels, band.metric_mesh().face(g.first), g.second);
    return grown.size();
  });
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief erodes every class: a labelled face becomes unlabelled when it comes within `radius` of a
/// face that does not carry its label (another class or an unlabelled face; the border of the mesh
/// does not count). Each class is eroded as a binary selection (`erode_face_selection()`), all from the
/// input labelling. Returns the number of faces unlabelled. Named parameters as `dilate_face_selection()`.
template <class TriangleMesh, class FaceLabelMap, class NamedParameters = parameters::Default_named_parameters>
std::size_t erode_face_labels(const TriangleMesh& tm, double radius, FaceLabelMap labels,
                              const typename boost::property_traits<FaceLabelMap>::value_type& unlabelled,
                              const NamedParameters& np = parameters::default_values())
{
  return internal::unlabel_what_each_class_drops(tm, radius, labels, unlabelled, np,
                                                 [](auto& band, const auto& faces, double r, double fraction, auto selection, const auto&) {
    internal::erode(band, faces, r, fraction, selection, CGAL::Emptyset_iterator());
  });
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief opens every class (binary opening of its faces, intersected with the class so that the
/// result stays a partition): the parts of a class narrower than the disc become unlabelled.
/// Returns the number of faces unlabelled. Named parameters as `dilate_face_selection()`.
template <class TriangleMesh, class FaceLabelMap, class NamedParameters = parameters::Default_named_parameters>
std::size_t open_face_labels(const TriangleMesh& tm, double radius, FaceLabelMap labels,
                             const typename boost::property_traits<FaceLabelMap>::value_type& unlabelled,
                             const NamedParameters& np = parameters::default_values())
{
  return internal::unlabel_what_each_class_drops(tm, radius, labels, unlabelled, np,
                                                 [](auto& band, const auto& faces, double r, double fraction, auto selection,
                                                    const std::vector<char>& member) {
    internal::erode(band, faces, r, fraction, selection, CGAL::Emptyset_iterator());
    internal::dilate(band, internal::members_of<TriangleMesh>(member), r, fraction, selection, CGAL::Emptyset_iterator());
  });
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief closes every class: each class is closed as a binary selection (dilation then erosion) from
/// the input labelling; an unlabelled face added by exactly one class's closing takes its label, a face
/// claimed by several classes stays unlabelled (a conflict: the closings of an indexed partition
/// overlap there, Hanbury 2003), and labelled faces keep their label. Returns the number of faces
/// labelled. Named parameters as `dilate_face_selection()`.
template <class TriangleMesh, class FaceLabelMap, class NamedParameters = parameters::Default_named_parameters>
std::size_t close_face_labels(const TriangleMesh& tm, double radius, FaceLabelMap labels,
                              const typename boost::property_traits<FaceLabelMap>::value_type& unlabelled,
                              const NamedParameters& np = parameters::default_values())
{
  typedef typename boost::property_traits<FaceLabelMap>::value_type Label;
  internal::check_radius(radius);
  const double fraction = internal::read_area_fraction(np);
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) -> std::size_t {
    std::vector<int> claims(band.metric_mesh().number_of_faces(), 0);
    std::vector<Label> claimed_by(band.metric_mesh().number_of_faces(), unlabelled);
    internal::for_each_class_selection(band, internal::label_classes(band, labels, unlabelled),
                                       [&](const Label& label, const auto& faces, auto selection, const std::vector<char>& member) {
      internal::dilate(band, faces, radius, fraction, selection, CGAL::Emptyset_iterator());
      internal::erode(band, internal::members_of<TriangleMesh>(member), radius, fraction, selection, CGAL::Emptyset_iterator());
      for(std::uint32_t f = 0; f < member.size(); ++f)
        if(member[f] && get(labels, band.metric_mesh().face(f)) == unlabelled)
        {
          ++claims[f];
          claimed_by[f] = label;
        }
    });
    std::size_t labelled = 0;
    for(std::uint32_t f = 0; f < claims.size(); ++f)
      if(claims[f] == 1)
      {
        put(labels, band.metric_mesh().face(f), claimed_by[f]);
        ++labelled;
      }
    return labelled;
  });
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief a series of closings of increasing radius (the radii are sorted first), each applied to the
/// result of the previous one: small gaps between classes are filled first, by the nearest classes,
/// before larger radii may claim them. Returns the total number of faces labelled.
template <class TriangleMesh, class RadiusRange, class FaceLabelMap, class NamedParameters = parameters::Default_named_parameters>
std::size_t series_close_face_labels(const TriangleMesh& tm, const RadiusRange& radii, FaceLabelMap labels,
                                     const typename boost::property_traits<FaceLabelMap>::value_type& unlabelled,
                                     const NamedParameters& np = parameters::default_values())
{
  std::vector<double> sorted(radii.begin(), radii.end());
  for(double r : sorted)
    internal::check_radius(r);
  std::sort(sorted.begin(), sorted.end());
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) -> std::size_t {
    std::size_t total = 0;
    for(double r : sorted)
      total += close_face_labels(tm, r, labels, unlabelled,
                                 parameters::face_band_solver(&band).area_fraction(internal::read_area_fraction(np)));
    return total;
  });
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_LABEL_MORPHOLOGY_H
