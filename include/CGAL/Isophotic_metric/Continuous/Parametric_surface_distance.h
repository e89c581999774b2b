// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Isophotic distance fields and geodesic curves on parametric surfaces:
// (grad d)^T M^{-1} grad d = 1 with M = w I + w' III, solved by fast sweeping on a (u,v) grid.
#ifndef CGAL_ISOPHOTIC_METRIC_CONTINUOUS_PARAMETRIC_SURFACE_DISTANCE_H
#define CGAL_ISOPHOTIC_METRIC_CONTINUOUS_PARAMETRIC_SURFACE_DISTANCE_H

#include <CGAL/Isophotic_metric/Continuous/Fast_sweeping_2.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/Continuous/Parametric_surface_metric.h>
#include <CGAL/Isophotic_metric/exceptions.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#endif

#include <Eigen/Dense>

#include <cmath>
#include <memory>
#include <sstream>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricContinuousRef
/// A geodesic curve on a parametric surface, as a polyline in the parameter domain and in space.
struct Parametric_geodesic
{
  std::vector<Eigen::Vector2d> uv;      ///< parameter points, from `from` to `to`
  std::vector<Eigen::Vector3d> points;  ///< the surface points `x(uv)`
  double distance = 0.;                 ///< distance field value at `to` (the geodesic distance)
  double length = 0.;                   ///< isophotic length of the polyline (see `isophotic_length()`)
  bool reached_source = false;          ///< false if the back-tracking stalled before reaching `from`
};

/// \ingroup PkgIsophoticMetricContinuousRef
/// Isophotic length of a parameter polyline: the sum of the chords of its lift
/// `X = (sqrt(w) x, sqrt(w') n)` to R^6 (Remark 1 of the paper), which converges to the length
/// in the metric `w I + w' III` as the polyline is refined.  Independent of any grid.
template <typename ParametricSurface>
double isophotic_length(const ParametricSurface& surface, const std::vector<Eigen::Vector2d>& uv,
                        double w, double w_prime)
{
  check_isophotic_weights(w, w_prime);
  double length = 0.;
  Eigen::Matrix<double, 6, 1> previous;
  for(std::size_t k = 0; k < uv.size(); ++k)
  {
    const Surface_differentials sd = surface_differentials(surface, uv[k].x(), uv[k].y());
    Eigen::Matrix<double, 6, 1> lifted;
    lifted << std::sqrt(w) * sd.point, std::sqrt(w_prime) * sd.normal;
    if(k > 0) length += (lifted - previous).norm();
    previous = lifted;
  }
  return length;
}

/// \ingroup PkgIsophoticMetricContinuousRef
/// Stateful solver for repeated distance and geodesic queries on one parametric surface:
/// the metric field `M = w I + w' III` is evaluated once at the grid nodes (in parallel with TBB
/// when linked; the values do not depend on it).
///
/// \tparam ParametricSurface a model of `ParametricSurface`
template <typename ParametricSurface>
class Parametric_surface_distance
{
public:
  /// \param surface the surface (kept by reference: it must outlive this object)
  /// \param grid the parameter grid on which the distance fields are computed
  /// \param np optional named parameters among:
  /// \cgalNamedParamsBegin
  ///   \cgalParamNBegin{euclidean_weight} \cgalParamDescription{weight `w` of the Euclidean part}
  ///     \cgalParamType{double} \cgalParamDefault{1} \cgalParamNEnd
  ///   \cgalParamNBegin{isophotic_weight} \cgalParamDescription{weight `w'` of the Gaussian-image part}
  ///     \cgalParamType{double} \cgalParamDefault{0} \cgalParamNEnd
  ///   \cgalParamNBegin{fast_sweeping_options} \cgalParamDescription{stencil, source initialisation, tolerance}
  ///     \cgalParamType{`Fast_sweeping_options`} \cgalParamDefault{`Fast_sweeping_options()`} \cgalParamNEnd
  /// \cgalNamedParamsEnd
  /// \throws Invalid_parameter_error on invalid weights, or if the metric is not positive
  ///         definite at some node (the message names it), e.g. `w = 0` where `K = 0`
  template <typename NamedParameters = parameters::Default_named_parameters>
  Parametric_surface_distance(const ParametricSurface& surface, const Grid_2& grid,
                              const NamedParameters& np = parameters::default_values())
    : surface_(surface)
  {
    using parameters::choose_parameter;
    using parameters::get_parameter;
    w_ = choose_parameter(get_parameter(np, internal_np::euclidean_weight), 1.);
    w_prime_ = choose_parameter(get_parameter(np, internal_np::isophotic_weight), 0.);
    check_isophotic_weights(w_, w_prime_);
    const Fast_sweeping_options options =
      choose_parameter(get_parameter(np, internal_np::fast_sweeping_options), Fast_sweeping_options());

    std::vector<Eigen::Matrix2d> metric(grid.size());
    auto fill_rows = [&](int j0, int j1) {
      for(int j = j0; j < j1; ++j)
        for(int i = 0; i < grid.nu(); ++i)
        {
          const Eigen::Vector2d uv = grid.node(i, j);
          const Surface_differentials sd = surface_differentials(surface_, uv.x(), uv.y());
          metric[grid.index(i, j)] = w_ * sd.first_fundamental_form + w_prime_ * sd.third_fundamental_form;
        }
    };
#ifdef CGAL_LINKED_WITH_TBB
    tbb::parallel_for(tbb::blocked_range<int>(0, grid.nv()),
                      [&](const tbb::blocked_range<int>& r) { fill_rows(r.begin(), r.end()); });
#else
    fill_rows(0, grid.nv());
#endif
    solver_ = std::make_unique<Fast_sweeping_2>(grid, std::move(metric), options);
  }

  double euclidean_weight() const { return w_; }
  double isophotic_weight() const { return w_prime_; }
  const Fast_sweeping_2& solver() const { return *solver_; }
  const Grid_2& grid() const { return solver_->grid(); }
  /// The nodes where distances are computed: all of them (one entry per node, for `GridDistanceSolver`).
  std::vector<char> domain() const { return std::vector<char>(grid().size(), 1); }

  /// Distance field to point sources given in parameter coordinates (label = position in `sources`)
  /// and, optionally, to a set of grid nodes (`mask[grid.index(i,j)] != 0`, label = `sources.size()`).
  /// \throws Invalid_source_error for a source outside the rectangle, non-finite, or no source at all
  Distance_field_2 distance_field(const std::vector<Eigen::Vector2d>& sources,
                                  const std::vector<char>& source_mask = {}) const
  {
    Fast_sweeping_2 solver = *solver_; // copies the metric field, keeps this object reusable
    for(const Eigen::Vector2d& s : sources) solver.add_point_source(s);
    if(!source_mask.empty()) solver.add_node_sources(source_mask);
    return solver.solve();
  }

  /// Geodesic curve from `from` to `to`: the distance field of `from` is computed and
  /// `dx/dt = -M^{-1} grad d` is integrated back from `to`.
  /// \throws Invalid_source_error if a point is outside the rectangle
  Parametric_geodesic geodesic(const Eigen::Vector2d& from, const Eigen::Vector2d& to) const
  {
    if(!grid().contains(to))
    {
      std::ostringstream os;
      os << "geodesic: target (u,v) = (" << to.transpose() << ") is outside the parameter rectangle";
      throw Invalid_source_error(os.str());
    }
    const Distance_field_2 field = distance_field({from});
    return geodesic_in_field(field, to);
  }

  /// Geodesic from the nearest source of `field` (returned by `distance_field()`) to `to`.
  Parametric_geodesic geodesic_in_field(const Distance_field_2& field, const Eigen::Vector2d& to) const
  {
    const Traced_path_2 traced = solver_->trace_back(field, to);
    Parametric_geodesic g;
    g.uv.assign(traced.points.rbegin(), traced.points.rend());
    g.reached_source = traced.reached_source;
    for(const Eigen::Vector2d& p : g.uv) g.points.push_back(surface_.point(p.x(), p.y()));
    g.distance = field.interpolate(to);
    g.length = isophotic_length(surface_, g.uv, w_, w_prime_);
    return g;
  }

private:
  const ParametricSurface& surface_;
  double w_ = 1., w_prime_ = 0.;
  std::unique_ptr<Fast_sweeping_2> solver_;
};

/// \ingroup PkgIsophoticMetricContinuousRef
/// One-shot isophotic distance field on a parametric surface from point sources (parameter
/// coordinates).  Named parameters as for `Parametric_surface_distance`.
template <typename ParametricSurface, typename NamedParameters = parameters::Default_named_parameters>
Distance_field_2 parametric_distance_field(const ParametricSurface& surface, const Grid_2& grid,
                                           const std::vector<Eigen::Vector2d>& sources,
                                           const NamedParameters& np = parameters::default_values())
{
  return Parametric_surface_distance<ParametricSurface>(surface, grid, np).distance_field(sources);
}

/// \ingroup PkgIsophoticMetricContinuousRef
/// One-shot geodesic curve between two parameter points.  Named parameters as for
/// `Parametric_surface_distance`.
template <typename ParametricSurface, typename NamedParameters = parameters::Default_named_parameters>
Parametric_geodesic parametric_geodesic(const ParametricSurface& surface, const Grid_2& grid,
                                        const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                                        const NamedParameters& np = parameters::default_values())
{
  return Parametric_surface_distance<ParametricSurface>(surface, grid, np).geodesic(from, to);
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_CONTINUOUS_PARAMETRIC_SURFACE_DISTANCE_H
