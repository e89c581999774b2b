// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Grey-level morphology of scalar fields on a mesh ("images on surfaces"), per vertex or per face,
// with flat or non-flat geodesic structuring elements in the isophotic metric.
#ifndef CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_GREY_LEVEL_MORPHOLOGY_H
#define CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_GREY_LEVEL_MORPHOLOGY_H

#include <CGAL/Isophotic_metric/Morphology/Face_band_solver.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Morphology/geodesic_neighborhoods.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricMorphology
/// Where a scalar field lives: one value per vertex or per face.
enum class Field_location { VERTICES, FACES };

/// \ingroup PkgIsophoticMetricMorphology
///
/// Grey-level morphology with geodesic structuring elements: the neighbourhoods of every element (the
/// vertices within `radius` of a vertex, or the faces whose centroid is within `radius` of a face's
/// centroid) are computed once, in parallel, then any number of fields can be dilated, eroded, opened
/// and closed.
///
/// With a structuring function \f$ b \f$ of the distance (flat: \f$ b = 0 \f$ on \f$ [0, r] \f$):
/// \f[ (\delta u)(x) = \max_{y:\ d(x,y) \le r} u(y) + b(d(x,y)), \qquad
///     (\varepsilon u)(y) = \min_{x:\ d(x,y) \le r} u(x) - b(d(x,y)). \f]
/// The erosion runs over the transposed neighbourhoods with the same distance values, so dilation and
/// erosion form an exact adjunction even where the two directions of a geodesic distance differ by
/// rounding: opening is anti-extensive and idempotent, closing extensive and idempotent. With
/// \f$ b(0) = 0 \f$ and \f$ b \le 0 \f$ (e.g. \f$ b(d) = -k d^2 \f$, a non-flat "paraboloid" element),
/// dilation is extensive and erosion anti-extensive.
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph`
/// \tparam ConcurrencyTag `CGAL::Parallel_tag` (what the default `CGAL::Parallel_if_available_tag` is when
///   `CGAL_LINKED_WITH_TBB` is defined) computes the neighbourhoods on TBB's threads,
///   `CGAL::Sequential_tag` one after the other; the results do not depend on it
template <class TriangleMesh, class ConcurrencyTag = CGAL::Parallel_if_available_tag>
class Grey_level_morphology
{
public:
  typedef std::vector<std::vector<std::pair<std::uint32_t, double>>> Neighborhoods;

  /// Computes the neighbourhoods of radius `radius` of every vertex or face.
  ///
  /// \cgalNamedParamsBegin
  ///   \cgalParamNBegin{structuring_function}
  ///     \cgalParamDescription{\f$ b \f$, a callable `double(double distance)`} \cgalParamDefault{flat: `0`} \cgalParamNEnd
  ///   \cgalParamNBegin{euclidean_weight, isophotic_weight, weight_length_scale, vertex_point_map, vertex_normal_map, lifted_embedding_map}
  ///     \cgalParamDescription{the metric, see `Geodesic_solver`} \cgalParamNEnd
  ///   \cgalParamNBegin{face_band_solver, callback} \cgalParamDescription{see `dilate_face_selection()`} \cgalParamNEnd
  /// \cgalNamedParamsEnd
  /// \throws Invalid_parameter_error for a negative or non-finite radius
  template <class NamedParameters = parameters::Default_named_parameters>
  Grey_level_morphology(const TriangleMesh& tm, double radius, Field_location location,
                        const NamedParameters& np = parameters::default_values())
    : tm_(tm), location_(location)
  {
    using parameters::choose_parameter;
    using parameters::get_parameter;
    internal::check_radius(radius);
    const std::function<double(double)> flat = [](double) { return 0.0; };
    structuring_ = choose_parameter(get_parameter(np, internal_np::structuring_function), flat);
    internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) {
      const Metric_mesh<TriangleMesh>& mesh = band.metric_mesh();
      // Fields are indexed by position in vertices(tm) / faces(tm). Vertex indices of the prepared
      // mesh are those positions; its face indices are not, hence `position`.
      if(location == Field_location::VERTICES)
        forward_ = internal::vertex_neighborhoods_by_index<ConcurrencyTag>(band, radius);
      else
      {
        std::vector<std::uint32_t> position(mesh.number_of_faces());
        std::uint32_t p = 0;
        for(auto f : faces(tm))
          position[mesh.face_index(f)] = p++;
        forward_.assign(mesh.number_of_faces(), {});
        internal::for_each_index<ConcurrencyTag>(mesh.number_of_faces(), 16, [&] { return band.sibling(); },
                                                 [&](Face_band_solver<TriangleMesh>& local, std::size_t i) {
          internal::add_center(local, Neighborhood_center::FACE_CENTROID, static_cast<std::uint32_t>(i));
          auto& neighbours = forward_[position[i]];
          local.visit_band(radius, false, false, [&](const typename Face_band_solver<TriangleMesh>::Face_visit& v) {
            const double d = local.distance(typename Face_band_solver<TriangleMesh>::Face_location(v.face, {{1.0 / 3, 1.0 / 3, 1.0 / 3}}));
            if(d <= radius)
              neighbours.push_back({position[v.face_index], d});
          });
        }, band.progress_callback(), "face neighbourhoods");
      }
      for(std::size_t i = 0; i < forward_.size(); ++i)
        if(forward_[i].empty())
          forward_[i].push_back({static_cast<std::uint32_t>(i), 0.0}); // an isolated vertex sees itself
      return 0;
    });
    element_names_.reserve(forward_.size());
    if(location == Field_location::VERTICES)
      for(auto v : vertices(tm))
        element_names_.push_back(internal::describe_element("vertex", v, element_names_.size()));
    else
      for(auto f : faces(tm))
        element_names_.push_back(internal::describe_element("face", f, element_names_.size()));
    transposed_.assign(forward_.size(), {});
    for(std::uint32_t x = 0; x < forward_.size(); ++x)
      for(const auto& yd : forward_[x])
        transposed_[yd.first].push_back({x, yd.second});
  }

  /// Number of elements (vertices or faces) of the fields.
  std::size_t size() const { return forward_.size(); }

  /// Dilation of a field given as one value per element, in the order of `vertices(tm)` / `faces(tm)`.
  /// \throws Invalid_parameter_error when a value is NaN (the message names the element)
  std::vector<double> dilate(const std::vector<double>& u) const { return apply(u, forward_, +1); }
  /// Erosion (over the transposed neighbourhoods).
  std::vector<double> erode(const std::vector<double>& u) const { return apply(u, transposed_, -1); }
  /// Opening: erosion, then dilation.
  std::vector<double> open(const std::vector<double>& u) const { return dilate(erode(u)); }
  /// Closing: dilation, then erosion.
  std::vector<double> close(const std::vector<double>& u) const { return erode(dilate(u)); }

  /// Reads a field from a property map (keyed by vertex or face descriptor).
  template <class ValueMap>
  std::vector<double> read(const ValueMap& map) const
  {
    std::vector<double> u;
    u.reserve(size());
    if(location_ == Field_location::VERTICES)
    {
      if constexpr(std::is_convertible<typename boost::graph_traits<TriangleMesh>::vertex_descriptor,
                                       typename boost::property_traits<ValueMap>::key_type>::value)
        for(auto v : vertices(tm_))
          u.push_back(CGAL::to_double(get(map, v)));
    }
    else
    {
      if constexpr(std::is_convertible<typename boost::graph_traits<TriangleMesh>::face_descriptor,
                                       typename boost::property_traits<ValueMap>::key_type>::value)
        for(auto f : faces(tm_))
          u.push_back(CGAL::to_double(get(map, f)));
    }
    if(u.size() != size())
      throw Invalid_parameter_error("the value map's key type does not match the field's location");
    return u;
  }

  /// Writes a field into a property map.
  template <class ValueMap>
  void write(const std::vector<double>& u, ValueMap map) const
  {
    std::size_t i = 0;
    if(location_ == Field_location::VERTICES)
    {
      if constexpr(std::is_convertible<typename boost::graph_traits<TriangleMesh>::vertex_descriptor,
                                       typename boost::property_traits<ValueMap>::key_type>::value)
        for(auto v : vertices(tm_))
          put(map, v, u[i++]);
    }
    else
    {
      if constexpr(std::is_convertible<typename boost::graph_traits<TriangleMesh>::face_descriptor,
                                       typename boost::property_traits<ValueMap>::key_type>::value)
        for(auto f : faces(tm_))
          put(map, f, u[i++]);
    }
  }

private:
  std::vector<double> apply(const std::vector<double>& u, const Neighborhoods& n, int sign) const
  {
    if(u.size() != size())
      throw Invalid_parameter_error("field of " + std::to_string(u.size()) + " values for " + std::to_string(size()) +
                                    " elements");
    for(std::size_t i = 0; i < u.size(); ++i)
      if(std::isnan(u[i]))
        throw Invalid_parameter_error("the value of " + element_names_[i] + " is NaN");
    std::vector<double> r(u.size());
    for(std::size_t x = 0; x < u.size(); ++x)
    {
      double best = sign > 0 ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
      for(const auto& yd : n[x])
      {
        const double v = u[yd.first] + sign * structuring_(yd.second);
        best = sign > 0 ? std::max(best, v) : std::min(best, v);
      }
      r[x] = best;
    }
    return r;
  }

  const TriangleMesh& tm_;
  Field_location location_;
  std::function<double(double)> structuring_;
  Neighborhoods forward_, transposed_;
  std::vector<std::string> element_names_;
};

namespace internal {

template <class ConcurrencyTag, class TriangleMesh, class ValueMap, class OutputMap, class NamedParameters, class Operation>
void grey_level(const TriangleMesh& tm, double radius, const ValueMap& values, OutputMap result,
                const NamedParameters& np, Operation&& operation)
{
  typedef typename boost::property_traits<ValueMap>::key_type key_type;
  constexpr bool on_faces = std::is_convertible<typename boost::graph_traits<TriangleMesh>::face_descriptor, key_type>::value &&
                            !std::is_convertible<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, key_type>::value;
  Grey_level_morphology<TriangleMesh, ConcurrencyTag> m(tm, radius, on_faces ? Field_location::FACES : Field_location::VERTICES, np);
  m.write(operation(m, m.read(values)), result);
}

} // namespace internal

/// \ingroup PkgIsophoticMetricMorphology
/// \brief grey-level dilation of a per-vertex or per-face field (the key type of `values` decides),
/// written into `result`; see `Grey_level_morphology` for the definition, `ConcurrencyTag` and the named
/// parameters.
template <class ConcurrencyTag = CGAL::Parallel_if_available_tag, class TriangleMesh, class ValueMap, class OutputMap,
          class NamedParameters = parameters::Default_named_parameters>
void dilate_values(const TriangleMesh& tm, double radius, const ValueMap& values, OutputMap result,
                   const NamedParameters& np = parameters::default_values())
{
  internal::grey_level<ConcurrencyTag>(tm, radius, values, result, np, [](const auto& m, const auto& u) { return m.dilate(u); });
}

/// \ingroup PkgIsophoticMetricMorphology
/// \brief grey-level erosion, as `dilate_values()`.
template <class ConcurrencyTag = CGAL::Parallel_if_available_tag, class TriangleMesh, class ValueMap, class OutputMap,
          class NamedParameters = parameters::Default_named_parameters>
void erode_values(const TriangleMesh& tm, double radius, const ValueMap& values, OutputMap result,
                  const NamedParameters& np = parameters::default_values())
{
  internal::grey_level<ConcurrencyTag>(tm, radius, values, result, np, [](const auto& m, const auto& u) { return m.erode(u); });
}

/// \ingroup PkgIsophoticMetricMorphology
/// \brief grey-level opening (removes peaks narrower than the structuring element), as `dilate_values()`.
template <class ConcurrencyTag = CGAL::Parallel_if_available_tag, class TriangleMesh, class ValueMap, class OutputMap,
          class NamedParameters = parameters::Default_named_parameters>
void open_values(const TriangleMesh& tm, double radius, const ValueMap& values, OutputMap result,
                 const NamedParameters& np = parameters::default_values())
{
  internal::grey_level<ConcurrencyTag>(tm, radius, values, result, np, [](const auto& m, const auto& u) { return m.open(u); });
}

/// \ingroup PkgIsophoticMetricMorphology
/// \brief grey-level closing (fills valleys narrower than the structuring element), as `dilate_values()`.
template <class ConcurrencyTag = CGAL::Parallel_if_available_tag, class TriangleMesh, class ValueMap, class OutputMap,
          class NamedParameters = parameters::Default_named_parameters>
void close_values(const TriangleMesh& tm, double radius, const ValueMap& values, OutputMap result,
                  const NamedParameters& np = parameters::default_values())
{
  internal::grey_level<ConcurrencyTag>(tm, radius, values, result, np, [](const auto& m, const auto& u) { return m.close(u); });
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_GREY_LEVEL_MORPHOLOGY_H
