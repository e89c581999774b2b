// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Fast sweeping for anisotropic Riemannian eikonal equations on a 2D grid:
//   (grad d)^T M^{-1} grad d = 1,   d = 0 on the sources,
// with M a symmetric positive definite 2x2 field given at the grid nodes.
#ifndef CGAL_ISOPHOTIC_METRIC_CONTINUOUS_FAST_SWEEPING_2_H
#define CGAL_ISOPHOTIC_METRIC_CONTINUOUS_FAST_SWEEPING_2_H

#include <CGAL/Isophotic_metric/Continuous/Fast_sweeping_options.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Continuous/internal/metric_tensor.h>
#include <CGAL/Isophotic_metric/Continuous/internal/hopf_lax_updates.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricContinuousRef
/// A regular grid of `nu` x `nv` nodes over the parameter rectangle `[u_min,u_max] x [v_min,v_max]`.
/// Node `(i,j)` sits at `(u_min + i*hu, v_min + j*hv)`; its linear index is `i + nu*j`.
/// A grid is checked when it is made and cannot be changed afterwards (assign another grid instead).
class Grid_2
{
public:
  /// The unit square with 3 x 3 nodes.
  Grid_2() = default;
  /// \throws Invalid_parameter_error if the rectangle is empty or not finite, its cells are not of
  ///         finite positive size, there are fewer than 3 nodes per side, or more than 2^32 nodes
  Grid_2(double u_min, double u_max, double v_min, double v_max, int nu, int nv)
    : u_min_(u_min), u_max_(u_max), v_min_(v_min), v_max_(v_max), nu_(nu), nv_(nv)
  {
    if(!(std::isfinite(u_min) && std::isfinite(u_max) && std::isfinite(v_min) && std::isfinite(v_max))
       || !(u_max > u_min) || !(v_max > v_min))
    {
      std::ostringstream os;
      os << "Grid_2: the parameter rectangle [" << u_min << "," << u_max << "] x [" << v_min << "," << v_max
         << "] must be finite and non-empty (u_min < u_max, v_min < v_max)";
      throw Invalid_parameter_error(os.str());
    }
    if(nu < 3 || nv < 3)
      throw Invalid_parameter_error("Grid_2: at least 3 nodes per side are needed, got "
                                    + std::to_string(nu) + " x " + std::to_string(nv));
    if(std::size_t(nu) * std::size_t(nv) > (std::size_t(1) << 32))
      throw Invalid_parameter_error("Grid_2: " + std::to_string(nu) + " x " + std::to_string(nv)
                                    + " nodes, more than 2^32: use a coarser grid");
    if(!(std::isfinite(hu()) && hu() > 0. && std::isfinite(hv()) && hv() > 0.))
      throw Invalid_parameter_error("Grid_2: the cells of the rectangle are not of finite positive size");
  }

  double u_min() const { return u_min_; }
  double u_max() const { return u_max_; }
  double v_min() const { return v_min_; }
  double v_max() const { return v_max_; }
  int nu() const { return nu_; }
  int nv() const { return nv_; }
  double hu() const { return (u_max_ - u_min_) / (nu_ - 1); }
  double hv() const { return (v_max_ - v_min_) / (nv_ - 1); }
  std::size_t size() const { return std::size_t(nu_) * std::size_t(nv_); }
  std::size_t index(int i, int j) const { return std::size_t(i) + std::size_t(nu_) * std::size_t(j); }
  Eigen::Vector2d node(int i, int j) const { return {u_min_ + i * hu(), v_min_ + j * hv()}; }
  /// Continuous index coordinates of a parameter point (node `(i,j)` has coordinates `(i,j)`).
  Eigen::Vector2d to_index(const Eigen::Vector2d& uv) const
  { return {(uv.x() - u_min_) / hu(), (uv.y() - v_min_) / hv()}; }
  bool contains(const Eigen::Vector2d& uv) const
  {
    return uv.allFinite() && uv.x() >= u_min_ && uv.x() <= u_max_ && uv.y() >= v_min_ && uv.y() <= v_max_;
  }

private:
  double u_min_ = 0., u_max_ = 1., v_min_ = 0., v_max_ = 1.;
  int nu_ = 3, nv_ = 3;
};

/// \ingroup PkgIsophoticMetricContinuousRef
/// The result of `Fast_sweeping_2::solve()`: distances and nearest sources at the grid nodes.
struct Distance_field_2
{
  Grid_2 grid;
  std::vector<double> distance;      ///< per node, `+inf` where no source is reachable
  std::vector<int> nearest_source;   ///< per node, label of the source the distance comes from, -1 if none
  /// position of each point source by label; NaN for the labels of set sources
  std::vector<Eigen::Vector2d> source_points;
  int sweeps = 0;                    ///< number of sweeps done
  bool converged = false;            ///< false if `max_sweeps` was reached

  double at(int i, int j) const { return distance[grid.index(i, j)]; }

  /// Bilinear interpolation of the distance at a parameter point (clamped to the rectangle).
  double interpolate(const Eigen::Vector2d& uv) const
  {
    int i, j; double s, t;
    locate(uv, i, j, s, t);
    const double d00 = at(i, j), d10 = at(i + 1, j), d01 = at(i, j + 1), d11 = at(i + 1, j + 1);
    return (1 - t) * ((1 - s) * d00 + s * d10) + t * ((1 - s) * d01 + s * d11);
  }

  /// Label of the nearest source at the grid node closest to `uv`.
  int nearest_source_at(const Eigen::Vector2d& uv) const
  {
    const Eigen::Vector2d x = grid.to_index(uv);
    const int i = std::clamp(int(std::lround(x.x())), 0, grid.nu() - 1);
    const int j = std::clamp(int(std::lround(x.y())), 0, grid.nv() - 1);
    return nearest_source[grid.index(i, j)];
  }

  /// Cell `(i,j)` containing `uv` and local coordinates `(s,t)` in [0,1]^2.
  void locate(const Eigen::Vector2d& uv, int& i, int& j, double& s, double& t) const
  {
    const Eigen::Vector2d x = grid.to_index(uv);
    i = std::clamp(int(std::floor(x.x())), 0, grid.nu() - 2);
    j = std::clamp(int(std::floor(x.y())), 0, grid.nv() - 2);
    s = std::clamp(x.x() - i, 0., 1.);
    t = std::clamp(x.y() - j, 0., 1.);
  }
};

/// \ingroup PkgIsophoticMetricContinuousRef
/// A curve traced back from a point to a source along `dx/dt = -M^{-1} grad d`.
struct Traced_path_2
{
  std::vector<Eigen::Vector2d> points; ///< from the start point to the source
  bool reached_source = false;         ///< false if the tracing stalled (e.g. on a cut locus)
};

/// \ingroup PkgIsophoticMetricContinuousRef
/// Fast-sweeping solver (Gauss-Seidel iterations in the 4 diagonal orderings, Tsai, Cheng, Osher,
/// Zhao 2003) of `(grad d)^T M^{-1} grad d = 1` on a `Grid_2`.
///
/// The local solver is the exact Hopf-Lax update on a fan of 8 or 16 neighbours: the new value of
/// a node is the minimum, over the fan boundary, of the linearly interpolated neighbour value plus
/// the metric length (metric frozen at the node) of the step to it.  It is monotone and first-order
/// accurate for any positive definite metric, however anisotropic; the 16-neighbour fan
/// keeps the error small when the metric's eigen-directions are not aligned with the grid.
/// Values only decrease; the iteration stops when a whole sweep changes nothing (up to the
/// relative tolerance), which is then a fixed point of the discrete scheme.
class Fast_sweeping_2
{
public:
  /// \param grid the parameter grid
  /// \param metric one symmetric matrix per node, indexed by `grid.index(i,j)`
  /// \param options stencil, initialisation and stopping settings
  /// \throws Invalid_parameter_error if `metric` has the wrong size, an option is invalid, or a matrix
  ///         is not finite, not symmetric or not positive definite (decided by a Cholesky
  ///         factorisation; accepted up to condition numbers of about 1e15; the message names the node)
  Fast_sweeping_2(const Grid_2& grid, std::vector<Eigen::Matrix2d> metric,
                  const Fast_sweeping_options& options = Fast_sweeping_options())
    : grid_(grid), metric_(std::move(metric)), options_(options)
  {
    if(metric_.size() != grid_.size())
      throw Invalid_parameter_error("Fast_sweeping_2: " + std::to_string(metric_.size())
                                    + " metric matrices given for " + std::to_string(grid_.size()) + " nodes");
    internal::check_fast_sweeping_options(options_, "Fast_sweeping_2");
    for(int j = 0; j < grid_.nv(); ++j)
      for(int i = 0; i < grid_.nu(); ++i)
      {
        Eigen::Matrix2d& M = metric_[grid_.index(i, j)];
        const char* defect = internal::metric_defect(M);
        if(defect)
        {
          std::ostringstream node;
          node << "node (" << i << "," << j << "), (u,v) = (" << grid_.node(i, j).transpose() << "),";
          throw Invalid_parameter_error(internal::metric_error_message("Fast_sweeping_2", node.str(), defect, M));
        }
        M = 0.5 * (M + M.transpose());
      }
    build_stencil();
    if(options_.adaptive_stencil) build_reduced_bases();
  }

  const Grid_2& grid() const { return grid_; }
  const Fast_sweeping_options& options() const { return options_; }
  const Eigen::Matrix2d& metric(int i, int j) const { return metric_[grid_.index(i, j)]; }

  /// Bilinear interpolation of the metric field.
  Eigen::Matrix2d metric_at(const Eigen::Vector2d& uv) const
  {
    const Eigen::Vector2d x = grid_.to_index(uv);
    const int i = std::clamp(int(std::floor(x.x())), 0, grid_.nu() - 2);
    const int j = std::clamp(int(std::floor(x.y())), 0, grid_.nv() - 2);
    const double s = std::clamp(x.x() - i, 0., 1.), t = std::clamp(x.y() - j, 0., 1.);
    return (1 - t) * ((1 - s) * metric(i, j) + s * metric(i + 1, j))
           + t * ((1 - s) * metric(i, j + 1) + s * metric(i + 1, j + 1));
  }

  /// Adds a source at a parameter point (not necessarily a node); returns its label.
  /// \throws Invalid_source_error if `uv` is not finite or outside the rectangle
  int add_point_source(const Eigen::Vector2d& uv)
  {
    if(!grid_.contains(uv))
    {
      std::ostringstream os;
      os << "Fast_sweeping_2: point source " << point_sources_.size() + node_sources_.size()
         << " at (u,v) = (" << uv.transpose() << ") is outside the parameter rectangle ["
         << grid_.u_min() << "," << grid_.u_max() << "] x [" << grid_.v_min() << "," << grid_.v_max() << "]";
      throw Invalid_source_error(os.str());
    }
    point_sources_.push_back({uv, next_label_});
    return next_label_++;
  }

  /// Adds a set source: every node with `mask[grid.index(i,j)] != 0` gets distance 0.
  /// All nodes of one call share one label, which is returned.
  /// \throws Invalid_source_error if the mask has the wrong size or selects no node
  template <typename Mask>
  int add_node_sources(const Mask& mask)
  {
    if(std::size_t(mask.size()) != grid_.size())
      throw Invalid_source_error("Fast_sweeping_2: source mask of size " + std::to_string(mask.size())
                                 + " for a grid of " + std::to_string(grid_.size()) + " nodes");
    std::vector<std::size_t> nodes;
    for(std::size_t n = 0; n < grid_.size(); ++n)
      if(mask[n]) nodes.push_back(n);
    if(nodes.empty())
      throw Invalid_source_error("Fast_sweeping_2: the source set (label " + std::to_string(next_label_)
                                 + ") selects no grid node");
    node_sources_.push_back({std::move(nodes), next_label_});
    return next_label_++;
  }

  /// Runs the sweeps.
  /// \throws Invalid_source_error if no source was added
  Distance_field_2 solve() const
  {
    if(point_sources_.empty() && node_sources_.empty())
      throw Invalid_source_error("Fast_sweeping_2: no source");
    Distance_field_2 field;
    field.grid = grid_;
    field.distance.assign(grid_.size(), std::numeric_limits<double>::infinity());
    field.nearest_source.assign(grid_.size(), -1);
    field.source_points.assign(next_label_, Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()));
    for(const Point_source& s : point_sources_) field.source_points[s.label] = s.uv;
    initialise_sources(field);
    // Sweep in which each node last decreased (-2: never): a node none of whose neighbours
    // changed since its last update would get the same value again, so it is skipped.
    std::vector<int> changed_in(grid_.size(), -2);
    for(std::size_t n = 0; n < grid_.size(); ++n)
      if(std::isfinite(field.distance[n])) changed_in[n] = -1;

    for(int sweep = 0; sweep < options_.max_sweeps; ++sweep)
    {
      const bool forward_u = (sweep % 4 == 0 || sweep % 4 == 3);
      const bool forward_v = (sweep % 4 < 2);
      const bool changed = sweep_once(field, changed_in, sweep, forward_u, forward_v);
      field.sweeps = sweep + 1;
      if(!changed) { field.converged = true; break; }
    }
    // Every node is reachable (the fan connects the whole grid): one left at +inf means the
    // sweeps stopped early, whatever the stopping test said.
    field.converged = field.converged
                      && std::all_of(field.distance.begin(), field.distance.end(), [](double d) { return d < std::numeric_limits<double>::infinity(); });
    return field;
  }

  /// Traces the geodesic from `start` back to its nearest source in `field` (computed by this
  /// solver) along the discrete characteristics of the scheme.
  ///
  /// At the current point `x`, the local update of the scheme is solved again, as if `x` were a node:
  /// the minimum over the stencil of the node nearest to `x` (shifted to `x`) of the interpolated
  /// distance at a stencil point `y` plus the length `||y - x||` in the metric at `x`.  The minimiser
  /// `y` is the foot of the discrete Hopf-Lax characteristic through `x`, and the curve moves
  /// towards it by at most one cell before the update is solved again.  Along this curve the
  /// update's value decreases by the metric length of each step, so the curve's length agrees with
  /// the distance up to the discretisation error of the scheme itself.  Unlike steepest descent
  /// along difference quotients of `d`, which mix both sides of the kink the distance has along a
  /// sharp feature (a narrow valley of a strongly anisotropic metric) and make the curve zig-zag
  /// across it, the step takes no derivative: it follows the feature.
  ///
  /// The last point is the source point (point sources: reached once within
  /// `source_initialization_radius` cells, where the metric is frozen and the geodesic straight)
  /// or, for set sources, the point one step of the remaining distance away along the direction
  /// of the foot, taken once the distance is below half a cell.  Consecutive points are at most one
  /// cell apart.
  /// \param field a distance field returned by `solve()` of this solver
  /// \param start the parameter point the curve starts from
  /// \throws Invalid_source_error if `start` is outside the rectangle or unreachable
  Traced_path_2 trace_back(const Distance_field_2& field, const Eigen::Vector2d& start) const
  {
    if(!grid_.contains(start) || !std::isfinite(field.interpolate(start)))
    {
      std::ostringstream os;
      os << "trace_back: start point (u,v) = (" << start.transpose()
         << ") is outside the parameter rectangle or not reached by the distance field";
      throw Invalid_source_error(os.str());
    }
    Traced_path_2 path;
    path.points.push_back(start);
    Eigen::Vector2d x = start;
    // Each step lowers the update's value by about its metric length (exactly while the foot stays
    // on the stencil; interpolation makes it fluctuate by a fraction of that).  A curve whose value
    // has not reached a new minimum for many steps is cycling around a stagnation point: abandoned.
    double lowest = std::numeric_limits<double>::infinity();
    int since_lowest = 0;
    const int max_steps = 16 * (grid_.nu() + grid_.nv());
    for(int step = 0; step < max_steps; ++step)
    {
      if(reached_point_source(field, x))
      {
        path.points.push_back(field.source_points[field.nearest_source_at(x)]);
        path.reached_source = true;
        return path;
      }
      if(is_set_source(field, x))
      {
        // Within half a cell (in the metric) of the source set: land on it along the characteristic.
        const Eigen::Matrix2d M = metric_at(x);
        const double half_cell = 0.5 * std::sqrt(std::min(grid_.hu() * grid_.hu() * M(0, 0), grid_.hv() * grid_.hv() * M(1, 1)));
        const double remaining = field.interpolate(x);
        if(remaining <= half_cell)
        {
          const Candidate c = update_at(field, x);
          const double cells = c.foot.norm();
          if(remaining > 0. && std::isfinite(c.value) && cells > 0.)
          {
            // Move by the remaining distance along the direction to the foot (unit metric speed).
            const Eigen::Vector2d step(c.foot.x() * grid_.hu(), c.foot.y() * grid_.hv());
            x = clamp_to_grid(x + remaining * step / std::sqrt(step.dot(M * step)));
            path.points.push_back(x);
          }
          path.reached_source = true;
          return path;
        }
      }
      const Candidate c = update_at(field, x);
      if(!std::isfinite(c.value)) break;
      if(c.value < lowest) { lowest = c.value; since_lowest = 0; }
      else if(++since_lowest > 32) break;
      const Eigen::Vector2d foot_uv = x + Eigen::Vector2d(c.foot.x() * grid_.hu(), c.foot.y() * grid_.hv());
      const double cells = c.foot.norm();
      if(!(cells > 0.)) break;
      if(cells <= 1.)
      {
        x = clamp_to_grid(foot_uv);
        path.points.push_back(x);
      }
      else
      {
        x = clamp_to_grid(x + (foot_uv - x) / cells);
        path.points.push_back(x);
      }
    }
    return path;
  }

  /// Gradient of the distance at a parameter point: node gradients by central differences
  /// (one-sided on the border), interpolated bilinearly.
  Eigen::Vector2d gradient(const Distance_field_2& field, const Eigen::Vector2d& uv) const
  {
    int i, j; double s, t;
    field.locate(uv, i, j, s, t);
    auto node_gradient = [&](int a, int b) {
      const int a0 = std::max(a - 1, 0), a1 = std::min(a + 1, grid_.nu() - 1);
      const int b0 = std::max(b - 1, 0), b1 = std::min(b + 1, grid_.nv() - 1);
      return Eigen::Vector2d((field.at(a1, b) - field.at(a0, b)) / ((a1 - a0) * grid_.hu()),
                             (field.at(a, b1) - field.at(a, b0)) / ((b1 - b0) * grid_.hv()));
    };
    return (1 - t) * ((1 - s) * node_gradient(i, j) + s * node_gradient(i + 1, j))
           + t * ((1 - s) * node_gradient(i, j + 1) + s * node_gradient(i + 1, j + 1));
  }

private:
  // Hexagon of the M-reduced basis of node n: offsets and linear shifts (empty if unused).
  struct Hexagon
  {
    bool used = false;
    int offset[6][2];
    std::ptrdiff_t shift[6];
  };

  // The best candidate of a local update among those below `bound`, given the values at the fan
  // offsets (`nd`) and at the hexagon offsets (`hd`, +inf outside the grid) and the metric in index
  // units (m11, m12, m22).  `from` is the fan index, or 16 + the hexagon index, of the neighbour the
  // value is attributed to (-1: none below `bound`); with `Foot`, `foot` is the point of the stencil
  // the value comes from (the foot of the discrete characteristic), as an offset in index units.
  struct Candidate
  {
    double value;
    int from;
    Eigen::Vector2d foot;
  };

  struct Point_source { Eigen::Vector2d uv; int label; };
  struct Node_source { std::vector<std::size_t> nodes; int label; };

  // Chebyshev radius (in cells) of the zone around a point source initialised with the frozen metric.
  // (Clamped to the grid's size: a larger zone covers the same nodes, and the index sums stay small.)
  int source_zone() const
  { return std::clamp(options_.source_initialization_radius, 1, std::max(grid_.nu(), grid_.nv())); }

  // True if `x` is in the initialised zone of the point source its nearest node comes from.
  bool reached_point_source(const Distance_field_2& field, const Eigen::Vector2d& x) const
  {
    const int label = field.nearest_source_at(x);
    if(label < 0 || std::isnan(field.source_points[label].x())) return false;
    const Eigen::Vector2d gap = grid_.to_index(x) - grid_.to_index(field.source_points[label]);
    return std::abs(gap.x()) <= source_zone() && std::abs(gap.y()) <= source_zone();
  }

  // True if the nearest source of `x` is a set source (node mask).
  bool is_set_source(const Distance_field_2& field, const Eigen::Vector2d& x) const
  {
    const int label = field.nearest_source_at(x);
    return label >= 0 && std::isnan(field.source_points[label].x());
  }

  // The local update of the scheme solved at a parameter point `x`, with the stencil of the nearest
  // node shifted to `x`, the interpolated distance and the interpolated metric; foot in index units.
  Candidate update_at(const Distance_field_2& field, const Eigen::Vector2d& x) const
  {
    const double inf = std::numeric_limits<double>::infinity();
    const Eigen::Vector2d c = grid_.to_index(x);
    const int i = std::clamp(int(std::lround(c.x())), 0, grid_.nu() - 1);
    const int j = std::clamp(int(std::lround(c.y())), 0, grid_.nv() - 1);
    auto value = [&](int a, int b) {
      const Eigen::Vector2d y = c + Eigen::Vector2d(a, b);
      if(!(y.x() >= 0. && y.x() <= grid_.nu() - 1 && y.y() >= 0. && y.y() <= grid_.nv() - 1)) return inf;
      return field.interpolate(Eigen::Vector2d(grid_.u_min() + y.x() * grid_.hu(), grid_.v_min() + y.y() * grid_.hv()));
    };
    std::array<double, 16> nd;
    for(std::size_t k = 0; k < offsets_.size(); ++k) nd[k] = value(offsets_[k][0], offsets_[k][1]);
    const Hexagon hex = hexagon_of(grid_.index(i, j));
    double hd[6];
    if(hex.used)
      for(int k = 0; k < 6; ++k) hd[k] = value(hex.offset[k][0], hex.offset[k][1]);
    const std::array<double, 3> m = index_metric(metric_at(x));
    return best_candidate<true>(nd.data(), hd, hex, m[0], m[1], m[2], inf);
  }

  Eigen::Vector2d clamp_to_grid(const Eigen::Vector2d& uv) const
  {
    return {std::clamp(uv.x(), grid_.u_min(), grid_.u_max()), std::clamp(uv.y(), grid_.v_min(), grid_.v_max())};
  }

  void build_stencil()
  {
    // Neighbour offsets in counter-clockwise order; consecutive offsets span unimodular
    // triangles, so the fan tiles a neighbourhood of the node without overlap.
    if(options_.stencil_radius == 1)
      offsets_ = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
    else
      offsets_ = {{1, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 1}, {-1, 2}, {-1, 1}, {-2, 1},
                  {-1, 0}, {-2, -1}, {-1, -1}, {-1, -2}, {0, -1}, {1, -2}, {1, -1}, {2, -1}};
    const int K = int(offsets_.size());
    for(int k = 0; k < K; ++k)
    {
      const int k1 = (k + 1 == K) ? 0 : k + 1;
      const int a = offsets_[k][0], b = offsets_[k][1], c = offsets_[k1][0], e = offsets_[k1][1];
      fan_shift_[k] = a + std::ptrdiff_t(grid_.nu()) * b;
      fan_cc_[k] = {double(a * a), double(2 * a * b), double(b * b)};
      fan_cx_[k] = {double(a * c), double(a * e + b * c), double(b * e)};
    }
  }

  // Lagrange-Gauss reduction of the integer lattice for the scalar product of M in index units,
  // then a sign flip so that e1' M e2 <= 0: (e1, e2, -e1-e2) is then an M-obtuse superbase.
  void build_reduced_bases()
  {
    const double hu = grid_.hu(), hv = grid_.hv();
    reduced_.resize(grid_.size());
    for(std::size_t n = 0; n < grid_.size(); ++n)
    {
      const Eigen::Matrix2d& M = metric_[n];
      // Piecewise constant fields are common: reuse the previous node's reduction.
      if(n > 0 && M == metric_[n - 1]) { reduced_[n] = reduced_[n - 1]; continue; }
      const double m11 = M(0, 0) * hu * hu, m12 = M(0, 1) * hu * hv, m22 = M(1, 1) * hv * hv;
      auto dot = [&](const std::array<long, 2>& a, const std::array<long, 2>& b) {
        return m11 * a[0] * b[0] + m12 * (a[0] * b[1] + a[1] * b[0]) + m22 * a[1] * b[1];
      };
      std::array<long, 2> a{1, 0}, b{0, 1};
      if(dot(a, a) > dot(b, b)) std::swap(a, b);
      for(int iteration = 0; iteration < 64; ++iteration)
      {
        const long q = std::lround(dot(a, b) / dot(a, a));
        b = {b[0] - q * a[0], b[1] - q * a[1]};
        if(dot(b, b) >= dot(a, a)) break;
        std::swap(a, b);
      }
      if(dot(a, b) > 0.) b = {-b[0], -b[1]};
      const int max_offset = 64; // beyond, the metric is too extreme for the grid anyway
      if(std::abs(a[0]) + std::abs(a[1]) + std::abs(b[0]) + std::abs(b[1]) > max_offset)
        reduced_[n] = {0, 0, 0, 0};
      else
        reduced_[n] = {int(a[0]), int(a[1]), int(b[0]), int(b[1])};
    }
  }

  void initialise_sources(Distance_field_2& field) const
  {
    for(const Node_source& s : node_sources_)
      for(std::size_t n : s.nodes)
      {
        field.distance[n] = 0.;
        field.nearest_source[n] = s.label;
      }
    const int k = source_zone();
    for(const Point_source& s : point_sources_)
    {
      const Eigen::Vector2d x = grid_.to_index(s.uv);
      const Eigen::Matrix2d Ms = metric_at(s.uv);
      const int i0 = std::max(0, int(std::ceil(x.x())) - k);
      const int i1 = std::min(grid_.nu() - 1, int(std::floor(x.x())) + k);
      const int j0 = std::max(0, int(std::ceil(x.y())) - k);
      const int j1 = std::min(grid_.nv() - 1, int(std::floor(x.y())) + k);
      for(int j = j0; j <= j1; ++j)
        for(int i = i0; i <= i1; ++i)
        {
          const std::size_t n = grid_.index(i, j);
          // Metric averaged between source and node: exact for constant metrics, and
          // third-order accurate (in the distance to the source) for smooth ones.
          const Eigen::Vector2d delta = grid_.node(i, j) - s.uv;
          const double d = std::sqrt(delta.dot(0.5 * (Ms + metric_[n]) * delta));
          if(d < field.distance[n])
          {
            field.distance[n] = d;
            field.nearest_source[n] = s.label;
          }
        }
    }
  }

  Hexagon hexagon_of(std::size_t n) const
  {
    Hexagon h;
    if(!options_.adaptive_stencil) return h;
    const std::array<int, 4>& r = reduced_[n];
    h.used = (r[0] | r[1]) != 0;
    if(!h.used) return h;
    const int offset[6][2] = {{r[0], r[1]}, {r[0] + r[2], r[1] + r[3]}, {r[2], r[3]},
                              {-r[0], -r[1]}, {-r[0] - r[2], -r[1] - r[3]}, {-r[2], -r[3]}};
    for(int k = 0; k < 6; ++k)
    {
      h.offset[k][0] = offset[k][0];
      h.offset[k][1] = offset[k][1];
      h.shift[k] = offset[k][0] + std::ptrdiff_t(grid_.nu()) * offset[k][1];
    }
    return h;
  }

  bool in_grid(int i, int j) const { return i >= 0 && i < grid_.nu() && j >= 0 && j < grid_.nv(); }

  template <bool Foot>
  Candidate best_candidate(const double* nd, const double* hd, const Hexagon& hex,
                           double m11, double m12, double m22, double bound) const
  {
    const int K = int(offsets_.size());
    const double inf = std::numeric_limits<double>::infinity();
    auto form = [&](const int* a, const int* b) { // a' M' b
      return m11 * a[0] * b[0] + m12 * (a[0] * b[1] + a[1] * b[0]) + m22 * a[1] * b[1];
    };
    auto segment_foot = [](const int* a, const int* b, double l) {
      return Eigen::Vector2d((1. - l) * a[0] + l * b[0], (1. - l) * a[1] + l * b[1]);
    };
    Candidate best{bound, -1, Eigen::Vector2d::Zero()};
    double l = 0.;
    // Vertices, then the segments between consecutive vertices, of a fan given by its offsets,
    // the values there and the squared metric lengths of the offsets.
    auto fan = [&](int count, auto offset, const double* value, const double* C, auto cross, int first) {
      for(int k = 0; k < count; ++k)
      {
        if(!(value[k] < best.value)) continue;
        const double vertex = value[k] + std::sqrt(C[k]);
        if(vertex < best.value)
        {
          best.value = vertex;
          best.from = first + k;
          if constexpr(Foot) best.foot = segment_foot(offset(k), offset(k), 0.);
        }
      }
      for(int k = 0; k < count; ++k)
      {
        const int k1 = (k + 1 == count) ? 0 : k + 1;
        const double d0 = value[k], d1 = value[k1];
        if(!(std::min(d0, d1) < best.value) || !(std::max(d0, d1) < inf)) continue;
        const double X = cross(k, k1); // e_k' M e_{k+1}
        const double v = internal::segment_update(d0, d1, C[k1] - 2. * X + C[k], X - C[k], C[k], Foot ? &l : nullptr);
        if(v < best.value)
        {
          best.value = v;
          best.from = first + (d0 <= d1 ? k : k1);
          if constexpr(Foot) best.foot = segment_foot(offset(k), offset(k1), l);
        }
      }
    };
    std::array<double, 16> C; // e_k' M e_k
    for(int k = 0; k < K; ++k) C[k] = fan_cc_[k][0] * m11 + fan_cc_[k][1] * m12 + fan_cc_[k][2] * m22;
    fan(K, [&](int k) { return offsets_[k].data(); }, nd, C.data(),
        [&](int k, int) { return fan_cx_[k][0] * m11 + fan_cx_[k][1] * m12 + fan_cx_[k][2] * m22; }, 0);
    if(hex.used)
    {
      double hc[6];
      for(int k = 0; k < 6; ++k) hc[k] = form(hex.offset[k], hex.offset[k]);
      fan(6, [&](int k) { return hex.offset[k]; }, hd, hc,
          [&](int k, int k1) { return form(hex.offset[k], hex.offset[k1]); }, 16);
    }
    return best;
  }

  // Metric in index units, M' = diag(h) M diag(h), as (m11, m12, m22).
  std::array<double, 3> index_metric(const Eigen::Matrix2d& M) const
  {
    const double hu = grid_.hu(), hv = grid_.hv();
    return {M(0, 0) * hu * hu, M(0, 1) * hu * hv, M(1, 1) * hv * hv};
  }

  // One Gauss-Seidel pass in one ordering; returns true if some node changed noticeably.
  bool sweep_once(Distance_field_2& field, std::vector<int>& changed_in, int sweep, bool forward_u, bool forward_v) const
  {
    const int nu = grid_.nu(), nv = grid_.nv();
    const int K = int(offsets_.size());
    const int R = options_.stencil_radius;
    const double inf = std::numeric_limits<double>::infinity();
    double* d = field.distance.data();
    int* label = field.nearest_source.data();
    int* stamp = changed_in.data();
    bool changed = false;

    for(int jj = 0; jj < nv; ++jj)
    {
      const int j = forward_v ? jj : nv - 1 - jj;
      const bool interior_j = (j >= R && j < nv - R);
      for(int ii = 0; ii < nu; ++ii)
      {
        const int i = forward_u ? ii : nu - 1 - ii;
        const std::size_t n = grid_.index(i, j);
        const double old = d[n];
        if(old == 0.) continue;
        const bool interior = interior_j && i >= R && i < nu - R;
        const Hexagon hex = hexagon_of(n);
        bool hex_inside[6];
        if(hex.used)
        {
          // The hexagon is symmetric: its reach is that of its first three vertices.
          int reach = 0;
          for(int k = 0; k < 3; ++k) reach = std::max({reach, std::abs(hex.offset[k][0]), std::abs(hex.offset[k][1])});
          const bool hex_interior = i >= reach && i < nu - reach && j >= reach && j < nv - reach;
          for(int k = 0; k < 6; ++k)
            hex_inside[k] = hex_interior || in_grid(i + hex.offset[k][0], j + hex.offset[k][1]);
        }

        // Skip the node if no neighbour changed since the previous sweep.
        const int since = sweep - 1;
        bool recent = false;
        for(int k = 0; k < K; ++k)
          if(interior || in_grid(i + offsets_[k][0], j + offsets_[k][1]))
            recent |= stamp[n + fan_shift_[k]] >= since;
        if(hex.used)
          for(int k = 0; k < 6; ++k)
            if(hex_inside[k]) recent |= stamp[n + hex.shift[k]] >= since;
        if(!recent) continue;

        std::array<double, 16> nd; // neighbour values
        for(int k = 0; k < K; ++k)
          nd[k] = (interior || in_grid(i + offsets_[k][0], j + offsets_[k][1])) ? d[n + fan_shift_[k]] : inf;
        double hd[6];
        if(hex.used)
          for(int k = 0; k < 6; ++k) hd[k] = hex_inside[k] ? d[n + hex.shift[k]] : inf;
        const std::array<double, 3> m = index_metric(metric_[n]);
        const Candidate best = best_candidate<false>(nd.data(), hd, hex, m[0], m[1], m[2], old);
        if(best.value < old)
        {
          d[n] = best.value;
          label[n] = label[n + (best.from < 16 ? fan_shift_[best.from] : hex.shift[best.from - 16])];
          stamp[n] = sweep;
          if(!(old - best.value <= options_.tolerance * best.value)) changed = true;
        }
      }
    }
    return changed;
  }

  Grid_2 grid_;
  std::vector<Eigen::Matrix2d> metric_;
  Fast_sweeping_options options_;
  std::vector<std::array<int, 2>> offsets_;
  // Per fan offset: its linear shift, and the coefficients of (m11, m12, m22) in e_k' M e_k and
  // e_k' M e_{k+1} (the quadratic forms are then 3 products).
  std::array<std::ptrdiff_t, 16> fan_shift_;
  std::array<std::array<double, 3>, 16> fan_cc_, fan_cx_;
  std::vector<std::array<int, 4>> reduced_; // per node: e1 = (r0,r1), e2 = (r2,r3) in index units
  std::vector<Point_source> point_sources_;
  std::vector<Node_source> node_sources_;
  int next_label_ = 0;
};

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_CONTINUOUS_FAST_SWEEPING_2_H
