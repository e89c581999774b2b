// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Basic measures of the isophotic metric: length of an edge and of a polyline on the lifted mesh,
// and the purely isophotic distance between two normals.
#ifndef CGAL_ISOPHOTIC_METRIC_ISOPHOTIC_LENGTH_H
#define CGAL_ISOPHOTIC_METRIC_ISOPHOTIC_LENGTH_H

#include <CGAL/Isophotic_metric/compute_lifted_embedding.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/validate_triangle_mesh.h>

#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/boost/graph/iterator.h>

#include <boost/container/small_vector.hpp>
#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

// Barycentric coordinates this close to zero put a point on an edge or at a vertex of its face.
constexpr double barycentric_zero = 1e-12;

template <typename TriangleMesh>
void check_face_location(const CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double>& loc,
                         std::size_t index)
{
  typedef boost::graph_traits<TriangleMesh> Graph_traits;
  if(loc.first == Graph_traits::null_face())
    throw Invalid_source_error(message("polyline point ", index, " has the null face"));
  const auto& b = loc.second;
  bool valid = std::isfinite(b[0]) && std::isfinite(b[1]) && std::isfinite(b[2]);
  for(double c : b)
    valid = valid && c >= -1e-9;
  valid = valid && std::abs(b[0] + b[1] + b[2] - 1.) <= 1e-9;
  if(!valid)
    throw Invalid_source_error(message("polyline point ", index, " has barycentric coordinates (", b[0], ", ",
                                       b[1], ", ", b[2], "); they must be non-negative and sum to one"));
}

// The faces whose closure contains the point: its own face, plus the neighbours when it lies on
// an edge or at a vertex.
template <typename TriangleMesh>
boost::container::small_vector<typename boost::graph_traits<TriangleMesh>::face_descriptor, 8>
faces_containing(const CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double>& loc,
                 const TriangleMesh& tm)
{
  typedef boost::graph_traits<TriangleMesh> Graph_traits;
  typedef typename Graph_traits::halfedge_descriptor halfedge_descriptor;
  typedef typename Graph_traits::face_descriptor face_descriptor;

  boost::container::small_vector<face_descriptor, 8> result;
  const halfedge_descriptor h = halfedge(loc.first, tm);
  // Corners in the order of locate.h: source(h), target(h), target(next(h)); the halfedge
  // ending at corner i, and the halfedge opposite corner i.
  const std::array<halfedge_descriptor, 3> to_corner = {prev(h, tm), h, next(h, tm)};
  const std::array<halfedge_descriptor, 3> facing_corner = {next(h, tm), prev(h, tm), h};

  std::array<bool, 3> zero;
  for(int i = 0; i < 3; ++i)
    zero[i] = std::abs(loc.second[i]) <= barycentric_zero;
  const int nb_zero = int(zero[0]) + int(zero[1]) + int(zero[2]);

  if(nb_zero == 2) // at a vertex
  {
    const int corner = !zero[0] ? 0 : (!zero[1] ? 1 : 2);
    for(face_descriptor f : CGAL::faces_around_target(to_corner[corner], tm))
      if(f != Graph_traits::null_face())
        result.push_back(f);
  }
  else
  {
    result.push_back(loc.first);
    if(nb_zero == 1) // on an edge
    {
      const int corner = zero[0] ? 0 : (zero[1] ? 1 : 2);
      const face_descriptor other = face(opposite(facing_corner[corner], tm), tm);
      if(other != Graph_traits::null_face())
        result.push_back(other);
    }
  }
  return result;
}

} // namespace internal

/// \ingroup PkgIsophoticMetricLift
///
/// \brief returns the point of the lifted mesh at a surface point: the barycentric interpolation of the
/// lifted vertices of its face (exact, since every lifted triangle is flat).
///
/// \tparam TriangleMesh a model of `FaceGraph`
/// \tparam LiftedPointMap a model of `ReadablePropertyMap` with
///         `boost::graph_traits<TriangleMesh>::%vertex_descriptor` as key type and `Lifted_point` as
///         value type, filled by `compute_lifted_embedding()`
///
/// \param loc a face and barycentric coordinates with respect to `source(halfedge(f))`,
///        `target(halfedge(f))` and `target(next(halfedge(f)))`, as in
///        `CGAL::Polygon_mesh_processing::locate()`
/// \param tm the mesh
/// \param lifted the lifted embedding of `tm`
///
/// \throws Invalid_source_error if the face is null or the coordinates are not finite,
///         are negative or do not sum to one
template <typename TriangleMesh, typename LiftedPointMap>
Lifted_point construct_lifted_point(const CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double>& loc,
                                    const TriangleMesh& tm,
                                    LiftedPointMap lifted)
{
  internal::check_face_location<TriangleMesh>(loc, 0);
  const auto h = halfedge(loc.first, tm);
  const Lifted_point x0 = get(lifted, source(h, tm));
  const Lifted_point x1 = get(lifted, target(h, tm));
  const Lifted_point x2 = get(lifted, target(next(h, tm), tm));
  Lifted_point x;
  for(int i = 0; i < 6; ++i)
    x[i] = loc.second[0] * x0[i] + loc.second[1] * x1[i] + loc.second[2] * x2[i];
  return x;
}

/// \ingroup PkgIsophoticMetricLift
///
/// \brief returns the isophotic length of the edge `e`: the Euclidean length of the lifted edge,
/// \f$ \sqrt{w\,\|p_u-p_v\|^2 + w' L^2 \|n_u-n_v\|^2} \f$ for constant weights.
///
/// \tparam TriangleMesh a model of `HalfedgeGraph`
/// \tparam LiftedPointMap as in `construct_lifted_point()`
template <typename TriangleMesh, typename LiftedPointMap>
double edge_isophotic_length(typename boost::graph_traits<TriangleMesh>::edge_descriptor e,
                             const TriangleMesh& tm,
                             LiftedPointMap lifted)
{
  return std::sqrt(internal::squared_distance(get(lifted, source(e, tm)), get(lifted, target(e, tm))));
}

/// \ingroup PkgIsophoticMetricLift
///
/// \brief returns the isophotic length of a polyline on the surface: the sum of the Euclidean lengths
/// of its lifted segments.
///
/// Every segment must lie in one face (its two end points in the closure of a common face: the same
/// face, or neighbouring faces when an end point lies on their common edge or vertex). Each segment is
/// then a straight segment of a flat lifted triangle, so the length is exact for the lifted mesh.
///
/// \tparam TriangleMesh a model of `FaceGraph`
/// \tparam FaceLocationRange a model of `ConstRange` with value type
///         `CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double>`
/// \tparam LiftedPointMap as in `construct_lifted_point()`
///
/// \param polyline the points of the polyline, in order
/// \param tm the mesh
/// \param lifted the lifted embedding of `tm`
///
/// \throws Invalid_source_error if a point is malformed (see `construct_lifted_point()`) or if two
///         consecutive points do not lie in a common face; the message names the points by index.
template <typename TriangleMesh, typename FaceLocationRange, typename LiftedPointMap>
double polyline_isophotic_length(const FaceLocationRange& polyline,
                                 const TriangleMesh& tm,
                                 LiftedPointMap lifted)
{
  double length = 0.;
  std::size_t index = 0;
  Lifted_point previous_point{};
  boost::container::small_vector<typename boost::graph_traits<TriangleMesh>::face_descriptor, 8> previous_faces;
  for(const auto& loc : polyline)
  {
    internal::check_face_location<TriangleMesh>(loc, index);
    const auto current_faces = internal::faces_containing(loc, tm);
    const Lifted_point current_point = construct_lifted_point(loc, tm, lifted);
    if(index > 0)
    {
      const bool share_a_face =
        std::any_of(current_faces.begin(), current_faces.end(), [&](const auto& f) {
          return std::find(previous_faces.begin(), previous_faces.end(), f) != previous_faces.end();
        });
      if(!share_a_face)
        throw Invalid_source_error(internal::message("polyline points ", index - 1, " and ", index,
                                                     " do not lie in a common face"));
      length += std::sqrt(internal::squared_distance(previous_point, current_point));
    }
    previous_point = current_point;
    previous_faces = current_faces;
    ++index;
  }
  return length;
}

/// \ingroup PkgIsophoticMetricLift
///
/// \brief returns the purely isophotic distance between two normals: the great-circle distance
/// (the angle, in radians, in \f$ [0, \pi] \f$) between their directions on the unit sphere.
///
/// This is the length of the shortest curve on the sphere joining the two points of the Gaussian
/// image. The lifted mesh of `compute_lifted_embedding()` measures the chord
/// \f$ 2\sin(\theta/2) \f$ along each edge instead, which agrees to \f$ O(\theta^3) \f$ for the short
/// edges of a fine mesh.
///
/// \tparam Vector_3 a vector type with `x()`, `y()`, `z()` (for example `Kernel::Vector_3`);
///         the vectors need not be of unit length
///
/// \throws Invalid_parameter_error if a vector is zero or not finite
template <typename Vector_3>
double purely_isophotic_distance(const Vector_3& n1, const Vector_3& n2)
{
  const double a[3] = {CGAL::to_double(n1.x()), CGAL::to_double(n1.y()), CGAL::to_double(n1.z())};
  const double b[3] = {CGAL::to_double(n2.x()), CGAL::to_double(n2.y()), CGAL::to_double(n2.z())};
  const double na = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  const double nb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  if(!(std::isfinite(na) && na > 0.))
    throw Invalid_parameter_error(internal::message("the first normal (", a[0], ", ", a[1], ", ", a[2],
                                                    ") is zero or not finite"));
  if(!(std::isfinite(nb) && nb > 0.))
    throw Invalid_parameter_error(internal::message("the second normal (", b[0], ", ", b[1], ", ", b[2],
                                                    ") is zero or not finite"));
  // atan2 of |a x b| and a.b is accurate for nearly equal and nearly opposite directions alike.
  const double cross[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const double sine = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
  const double cosine = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  return std::atan2(sine, cosine);
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_ISOPHOTIC_LENGTH_H
