// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A length L that makes the weights of the isophotic metric dimensionless (see weight_length_scale).
#ifndef CGAL_ISOPHOTIC_METRIC_SUGGESTED_WEIGHT_LENGTH_SCALE_H
#define CGAL_ISOPHOTIC_METRIC_SUGGESTED_WEIGHT_LENGTH_SCALE_H

#include <CGAL/Isophotic_metric/Named_function_parameters.h>

#include <CGAL/Polygon_mesh_processing/bbox.h>

#include <cmath>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricLift
///
/// \brief returns the diagonal of the axis-aligned bounding box of `tm`, a length scale to pass as
/// `weight_length_scale` to `compute_lifted_embedding()`.
///
/// Why the bounding-box diagonal `D`: with `L = D`, the lifted squared length of a short step is
/// \f$ (w + w' D^2 \kappa^2)\,ds^2 \f$ across a curvature \f$ \kappa \f$, so `w` and `w'` weigh
/// positions and normals equally on a bend of radius `D`, i.e. on a bend at the scale of the whole
/// model, while fillets and blends (radius much smaller than `D`) are dominated by the normal part.
/// The diagonal depends on the shape only, not on the triangulation: refining the mesh does not change
/// the metric (a mean edge length would). It scales with the model, as required for scale invariance.
/// It is not invariant under rotation (the box is axis-aligned), which only changes `L` by a bounded
/// factor.
///
/// \tparam TriangleMesh a model of `VertexListGraph`
/// \tparam NamedParameters a sequence of \ref IsophoticMetricNamedParameters "Named Parameters"
///
/// \param tm the mesh
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map}
///     \cgalParamDescription{a property map associating points to the vertices of `tm`}
///     \cgalParamType{a class model of `ReadablePropertyMap` with
///                    `boost::graph_traits<TriangleMesh>::%vertex_descriptor` as key type and
///                    `%Point_3` as value type}
///     \cgalParamDefault{`boost::get(CGAL::vertex_point, tm)`}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \return the diagonal length, `0` for a mesh without vertices or with a single point
template <typename TriangleMesh,
          typename NamedParameters = parameters::Default_named_parameters>
double suggested_weight_length_scale(const TriangleMesh& tm,
                                     const NamedParameters& np = parameters::default_values())
{
  if(vertices(tm).begin() == vertices(tm).end())
    return 0.;
  const CGAL::Bbox_3 box = CGAL::Polygon_mesh_processing::bbox(tm, parameters::cgal_np(np));
  const double dx = box.xmax() - box.xmin(), dy = box.ymax() - box.ymin(), dz = box.zmax() - box.zmin();
  return std::hypot(dx, dy, dz); // (squares of a model at 1e-160 are subnormal, at 1e200 infinite)
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_SUGGESTED_WEIGHT_LENGTH_SCALE_H
