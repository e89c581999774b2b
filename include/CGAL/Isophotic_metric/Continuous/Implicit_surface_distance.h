// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Isophotic distance fields on implicit surfaces: 3D fast sweeping of (grad d)^T M^{-1} grad d = 1
// in a narrow band around F = 0, distances and nearest sources read off on the surface.
#ifndef CGAL_ISOPHOTIC_METRIC_CONTINUOUS_IMPLICIT_SURFACE_DISTANCE_H
#define CGAL_ISOPHOTIC_METRIC_CONTINUOUS_IMPLICIT_SURFACE_DISTANCE_H

#include <CGAL/Isophotic_metric/Continuous/Fast_sweeping_3.h>
#include <CGAL/Isophotic_metric/Continuous/Implicit_surface_metric.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#endif

#include <Eigen/Dense>

#include <cmath>
#include <memory>
#include <sstream>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricContinuousRef
/// Stateful solver of isophotic distance fields on an implicit surface `F = 0`.
///
/// The metric `M` (see `Implicit_metric_extension`) is evaluated at the nodes of a narrow band
/// `|F|/|grad F| <= narrow_band_width`, in parallel with TBB when linked (same values either way),
/// and `Fast_sweeping_3` solves the eikonal equation there.  Read the result on the surface with
/// `Distance_field_3::interpolate()` at surface points (e.g. the vertices of a mesh of `F = 0`).
class Implicit_surface_distance
{
public:
  /// Solver for a model of `ImplicitFunction`, on `grid`.
  /// \param F the implicit function, a model of `ImplicitFunction`
  /// \param grid the grid that holds the narrow band and the distance field
  /// \param np optional named parameters among:
  /// \cgalNamedParamsBegin
  ///   \cgalParamNBegin{euclidean_weight} \cgalParamDescription{`w`} \cgalParamDefault{1} \cgalParamNEnd
  ///   \cgalParamNBegin{isophotic_weight} \cgalParamDescription{`w'`} \cgalParamDefault{0} \cgalParamNEnd
  ///   \cgalParamNBegin{narrow_band_width} \cgalParamDescription{half-width of the band, in world units}
  ///     \cgalParamDefault{`3.5 * grid.h()`} \cgalParamNEnd
  ///   \cgalParamNBegin{fast_sweeping_options} \cgalParamType{`Fast_sweeping_options`} \cgalParamNEnd
  /// \cgalNamedParamsEnd
  /// \param extension how the metric is extended off the surface (last argument, not a named parameter)
  /// \throws Invalid_parameter_error on invalid weights or band width, or if the band is empty
  template <typename ImplicitFunction, typename NamedParameters = parameters::Default_named_parameters>
  Implicit_surface_distance(const ImplicitFunction& F, const Grid_3& grid,
                            const NamedParameters& np = parameters::default_values(),
                            Implicit_metric_extension extension = Implicit_metric_extension::foot_point)
  {
    build(grid, np, extension, [&](int i, int j, int k) { return implicit_differentials(F, grid.node(i, j, k)); },
          [&](int i, int j, int k) { return F(grid.node(i, j, k)); });
  }

  /// Solver for a sampled function; the distance field lives on the same grid.
  template <typename NamedParameters = parameters::Default_named_parameters>
  Implicit_surface_distance(const Sampled_function_3& F, const NamedParameters& np = parameters::default_values(),
                            Implicit_metric_extension extension = Implicit_metric_extension::foot_point)
  {
    build(F.grid(), np, extension, [&](int i, int j, int k) { return F.node_differentials(i, j, k); },
          [&](int i, int j, int k) { return F.values()[F.grid().index(i, j, k)]; });
  }

  const Fast_sweeping_3& solver() const { return *solver_; }
  const Grid_3& grid() const { return solver_->grid(); }
  /// The nodes where distances are computed: the band (one entry per node, for `GridDistanceSolver`).
  const std::vector<char>& domain() const { return solver_->active(); }
  double euclidean_weight() const { return w_; }
  double isophotic_weight() const { return w_prime_; }
  /// Number of active (band) nodes.
  std::size_t band_size() const { return band_size_; }

  /// Distance field to point sources (label = position in `sources`; put them on or near the
  /// surface) and optionally to a set of band nodes (label = `sources.size()`).
  /// \throws Invalid_source_error for a source away from the band, or no source at all
  Distance_field_3 distance_field(const std::vector<Eigen::Vector3d>& sources,
                                  const std::vector<char>& source_mask = {}) const
  {
    Fast_sweeping_3 solver = *solver_;
    for(const Eigen::Vector3d& s : sources) solver.add_point_source(s);
    if(!source_mask.empty()) solver.add_node_sources(source_mask);
    return solver.solve();
  }

private:
  template <typename NamedParameters, typename Differentials, typename Value>
  void build(const Grid_3& grid, const NamedParameters& np, Implicit_metric_extension extension,
             const Differentials& differentials, const Value& value)
  {
    using parameters::choose_parameter;
    using parameters::get_parameter;
    w_ = choose_parameter(get_parameter(np, internal_np::euclidean_weight), 1.);
    w_prime_ = choose_parameter(get_parameter(np, internal_np::isophotic_weight), 0.);
    check_isophotic_weights(w_, w_prime_);
    const double band = choose_parameter(get_parameter(np, internal_np::narrow_band_width), 3.5 * grid.h());
    if(!std::isfinite(band) || !(band >= grid.h()))
      throw Invalid_parameter_error("narrow_band_width = " + std::to_string(band)
                                    + " must be finite and at least one grid cell (" + std::to_string(grid.h()) + ")");
    const Fast_sweeping_options options =
      choose_parameter(get_parameter(np, internal_np::fast_sweeping_options), Fast_sweeping_options());

    std::vector<char> active(grid.size(), 0);
    std::vector<Eigen::Matrix3d> metric(grid.size(), Eigen::Matrix3d::Identity());
    auto fill_slices = [&](int k0, int k1) {
      for(int k = k0; k < k1; ++k)
        for(int j = 0; j < grid.ny(); ++j)
          for(int i = 0; i < grid.nx(); ++i)
          {
            const std::size_t n = grid.index(i, j, k);
            Implicit_differentials id;
            // A vanishing gradient (medial axis of a distance function, flat far field) cannot
            // carry a normal: such nodes stay outside the band.  A value that is not a number is
            // bad input, not a point away from the surface.
            try { id = differentials(i, j, k); }
            catch(const Invalid_parameter_error&)
            {
              const double f = value(i, j, k);
              if(std::isfinite(f)) continue;
              std::ostringstream os;
              os << "Implicit_surface_distance: the implicit function is " << f << " at node (" << i << "," << j << ","
                 << k << "), x = (" << grid.node(i, j, k).transpose() << "): it must be finite on the whole grid";
              throw Invalid_parameter_error(os.str());
            }
            if(std::abs(id.value) > band * id.gradient.norm()) continue;
            active[n] = 1;
            metric[n] = implicit_isophotic_metric_tensor(id, w_, w_prime_, extension);
          }
    };
#ifdef CGAL_LINKED_WITH_TBB
    tbb::parallel_for(tbb::blocked_range<int>(0, grid.nz()),
                      [&](const tbb::blocked_range<int>& r) { fill_slices(r.begin(), r.end()); });
#else
    fill_slices(0, grid.nz());
#endif
    band_size_ = 0;
    for(char a : active) band_size_ += a ? 1 : 0;
    if(band_size_ == 0)
      throw Invalid_parameter_error("Implicit_surface_distance: no grid node in the narrow band (the surface F = 0 "
                                    "does not cross the grid?)");
    solver_ = std::make_unique<Fast_sweeping_3>(grid, std::move(active), std::move(metric), options);
  }

  double w_ = 1., w_prime_ = 0.;
  std::size_t band_size_ = 0;
  std::unique_ptr<Fast_sweeping_3> solver_;
};

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_CONTINUOUS_IMPLICIT_SURFACE_DISTANCE_H
