// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Segmentation of a triangle mesh into fundamental surfaces (plane, cylinder, cone, sphere, torus,
// free-form), each with its fitted parameters: isophotic region growing for the patches, primitive
// fitting to split and merge them, settled borders.
#ifndef CGAL_ISOPHOTIC_METRIC_SEGMENTATION_SEGMENT_FUNDAMENTAL_SURFACES_H
#define CGAL_ISOPHOTIC_METRIC_SEGMENTATION_SEGMENT_FUNDAMENTAL_SURFACES_H

#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/Segmentation/fit_fundamental_surface.h>
#include <CGAL/Isophotic_metric/Segmentation/region_growing.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/internal/Progress_callback.h>
#include <CGAL/Isophotic_metric/internal/for_each_index.h>
#include <CGAL/Isophotic_metric/suggested_normal_smoothing_scale.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricSegmentation
/// One segment of `segment_fundamental_surfaces()`: its fitted surface (type, parameters, residual),
/// its area and its number of faces.
struct Fundamental_surface_segment
{
  Fundamental_surface surface;
  double area = 0;
  std::size_t number_of_faces = 0;
};

namespace internal {

// The faces as samples (centroid, normal, area) and their edge adjacency, by face index.
struct Segmentation_faces
{
  std::vector<Surface_sample> sample;                  // normals smoothed (smooth_normals())
  std::vector<Vec3> facet_normal;                      // the faces' own normals
  std::vector<std::array<std::uint32_t, 3>> neighbour; // -1 across a border edge
  static constexpr std::uint32_t none = std::uint32_t(-1);
  std::size_t size() const { return sample.size(); }
};

// Bilateral smoothing of the face normals across edges: a neighbour counts with its area and a Gaussian
// of the normals' difference, so noise is averaged and sharp edges (large differences) are kept.
inline void smooth_normals(Segmentation_faces& F, int iterations, double sigma)
{
  for(int it = 0; it < iterations; ++it)
  {
    std::vector<Vec3> next(F.size());
    for(std::size_t f = 0; f < F.size(); ++f)
    {
      Vec3 sum = F.sample[f].w * F.sample[f].n;
      for(std::uint32_t g : F.neighbour[f])
        if(g != Segmentation_faces::none)
        {
          const double d = (F.sample[g].n - F.sample[f].n).squaredNorm();
          sum += F.sample[g].w * std::exp(-d / (sigma * sigma)) * F.sample[g].n;
        }
      next[f] = sum.norm() > 0 ? Vec3(sum.normalized()) : F.sample[f].n;
    }
    for(std::size_t f = 0; f < F.size(); ++f)
      F.sample[f].n = next[f];
  }
}

// Tolerances of a fit: a face fits a surface when its centroid is within its sample's `tolerance` and
// its normal within `angle` (radians) of the surface's; a surface fits a set of faces when its residual
// is at most `rms_factor` times their mean tolerance and the faces that fit hold `inlier_fraction` of
// the area.
struct Fit_tolerance
{
  explicit Fit_tolerance(double angle_radians) : angle(angle_radians), cos_angle(std::cos(angle_radians)) {}
  double angle, cos_angle;
  double rms_factor = 0.6, inlier_fraction = 0.9;
};

struct Fitted
{
  Surface_model model;
  double residual = std::numeric_limits<double>::infinity();
  bool accepted = false;
};

inline bool face_fits(const Surface_model& m, const Surface_sample& s, const Fit_tolerance& tol)
{
  return m.distance(s.p) <= s.tolerance && s.n.dot(m.normal(s.p)) >= tol.cos_angle;
}

// cost of a face on a surface: distance and angle in units of their tolerances; a free-form surface
// costs a constant, so a face stays on it unless a fitted surface explains it well
inline double face_cost(const Surface_model& m, const Surface_sample& s, const Fit_tolerance& tol)
{
  if(m.type == Surface_type::free_form)
    return 1.5;
  const double c = std::max(-1.0, std::min(1.0, s.n.dot(m.normal(s.p))));
  return m.distance(s.p) / s.tolerance + std::acos(c) / tol.angle;
}

inline Fitted evaluate(const Surface_model& m, const std::vector<Surface_sample>& s, const Fit_tolerance& tol)
{
  Fitted r;
  r.model = m;
  if(m.type == Surface_type::free_form)
    return r;
  r.residual = rms_distance(m, s);
  double inliers = 0, total = 0, tolerance = 0;
  for(const Surface_sample& x : s)
  {
    total += x.w;
    tolerance += x.w * x.tolerance;
    if(face_fits(m, x, tol))
      inliers += x.w;
  }
  r.accepted = std::isfinite(r.residual) && r.residual <= tol.rms_factor * tolerance / total &&
               inliers >= tol.inlier_fraction * total;
  return r;
}

// The simplest type that fits: a plane first, then the better of cylinder and sphere, then the better of
// cone and torus. Free-form (not accepted) when none fits. Each type is fitted to at most 500 of the
// samples (evenly taken: enough to settle five to seven parameters) and evaluated on up to
// `max_fit_samples`.
inline Fitted fit_simplest(const std::vector<Surface_sample>& all, const Fit_tolerance& tol)
{
  const std::vector<Surface_sample> s = subsample(all, max_fit_samples);
  const std::vector<Surface_sample> few = subsample(s, 500);
  static const std::vector<std::vector<Surface_type>> classes = {
    {Surface_type::plane}, {Surface_type::cylinder, Surface_type::sphere}, {Surface_type::cone, Surface_type::torus}};
  Fitted best_rejected;
  for(const auto& types : classes)
  {
    Fitted best;
    for(Surface_type t : types)
    {
      const Fitted f = evaluate(fit_model(t, few), s, tol);
      if(f.accepted && (!best.accepted || f.residual < best.residual))
        best = f;
      if(f.residual < best_rejected.residual)
        best_rejected = f;
    }
    if(best.accepted)
      return best;
  }
  Fitted free_form;
  free_form.residual = best_rejected.residual;
  return free_form;
}

// the class of a type in fit_simplest()'s order: plane 0, cylinder and sphere 1, cone and torus 2
inline int type_class(Surface_type t)
{
  switch(t)
  {
  case Surface_type::plane: return 0;
  case Surface_type::cylinder:
  case Surface_type::sphere: return 1;
  case Surface_type::cone:
  case Surface_type::torus: return 2;
  default: return 3;
  }
}

inline std::vector<Surface_sample> samples_of(const Segmentation_faces& F, const std::vector<std::uint32_t>& faces,
                                              std::size_t at_most = std::numeric_limits<std::size_t>::max())
{
  // evenly taken, as subsample() does, without copying the others
  const std::size_t n = std::min(faces.size(), at_most);
  const double step = n > 0 ? double(faces.size()) / double(n) : 1;
  std::vector<Surface_sample> s;
  s.reserve(n);
  for(std::size_t i = 0; i < n; ++i)
    s.push_back(F.sample[faces[std::size_t(i * step)]]);
  return s;
}

// Faces reached from `seed` across edges through faces with `allowed(f)`, at most `rings` rings away.
template <class Allowed>
std::vector<std::uint32_t> flood(const Segmentation_faces& F, std::uint32_t seed, std::size_t rings, Allowed&& allowed,
                                 std::vector<std::uint32_t>& mark, std::uint32_t stamp)
{
  std::vector<std::uint32_t> out{seed};
  mark[seed] = stamp;
  std::size_t begin = 0;
  for(std::size_t ring = 0; ring < rings && begin < out.size(); ++ring)
  {
    const std::size_t end = out.size();
    for(std::size_t i = begin; i < end; ++i)
      for(std::uint32_t g : F.neighbour[out[i]])
        if(g != Segmentation_faces::none && mark[g] != stamp && allowed(g))
        {
          mark[g] = stamp;
          out.push_back(g);
        }
    begin = end;
  }
  return out;
}

// The segmentation's state: a label per face (`none` for no segment yet) and the surface of each label.
class Fundamental_segmentation
{
public:
  static constexpr std::uint32_t none = std::uint32_t(-1);

  Fundamental_segmentation(const Segmentation_faces& faces, const Fit_tolerance& tolerance)
    : F(faces), tol(tolerance), label(faces.size(), none), mark(faces.size(), 0)
  {}

  // 1. One segment per patch that one surface fits; the other patches are split by growing surfaces
  // from seeds inside them.
  void split_patches(const std::vector<std::size_t>& patch)
  {
    std::map<std::size_t, std::vector<std::uint32_t>> members;
    for(std::uint32_t f = 0; f < F.size(); ++f)
      members[patch[f]].push_back(f);
    for(const auto& m : members)
    {
      const Fitted whole = fit_simplest(samples_of(F, m.second, max_fit_samples), tol);
      if(whole.accepted)
        add_segment(m.second, whole.model);
      else
        extract_surfaces(m.second);
    }
  }

  // 2. Adjacent segments whose union one surface fits become one, most similar first, in rounds (each
  // segment merged at most once per round). A pair is first tried with the surface of either part
  // (the simpler type first, then the smaller residual; no fit, evaluations only: most pairs are
  // pieces of one surface), then, when neither fits the union, with a fit of the union. An accepted
  // pair is redone when one of the two changes; a refused one only when one of the two has doubled its
  // faces since: a union that no surface fits rarely becomes one that does by growing, and refitting
  // every refused pair whenever a neighbour grew was most of the work. The pairs of a round are
  // independent and tried in parallel with `ConcurrencyTag`; a merged segment's surface is refitted
  // to its faces, with its type.
  template <class ConcurrencyTag>
  void merge_segments()
  {
    typedef std::pair<std::uint32_t, std::uint32_t> Pair;
    struct Pair_fit
    {
      Pair versions, sizes;
      Fitted fit;
    };
    std::vector<std::vector<std::uint32_t>> members = segment_members();
    std::vector<std::uint32_t> version(surface.size(), 0);
    std::map<Pair, Pair_fit> known;
    auto is_free_form = [&](std::uint32_t a) { return surface[a].type == Surface_type::free_form; };
    for(bool merged = true; merged;)
    {
      merged = false;
      const std::vector<Pair> pairs = adjacent_segment_pairs();
      std::vector<Pair> to_fit;
      for(const Pair& pair : pairs)
      {
        const auto k = known.find(pair);
        if(k == known.end())
          to_fit.push_back(pair);
        else if(k->second.fit.accepted ? k->second.versions != Pair(version[pair.first], version[pair.second])
                                       : members[pair.first].size() >= 2 * k->second.sizes.first ||
                                           members[pair.second].size() >= 2 * k->second.sizes.second)
          to_fit.push_back(pair);
      }
      std::vector<Pair_fit> fitted(to_fit.size());
      for_each_index<ConcurrencyTag>(to_fit.size(), 1, [] { return 0; }, [&](int, std::size_t i) {
        const std::uint32_t a = to_fit[i].first, b = to_fit[i].second;
        std::vector<std::uint32_t> both = members[a];
        both.insert(both.end(), members[b].begin(), members[b].end());
        const std::vector<Surface_sample> union_samples = samples_of(F, both, max_fit_samples),
                                          samples_a = samples_of(F, members[a], max_fit_samples),
                                          samples_b = samples_of(F, members[b], max_fit_samples);
        // each part must fit on its own: a small corner blend would pass in the union's statistics
        auto fits_both_parts = [&](const Fitted& f) {
          return f.accepted && evaluate(f.model, samples_a, tol).accepted && evaluate(f.model, samples_b, tol).accepted;
        };
        Pair_fit& r = fitted[i];
        r.versions = {version[a], version[b]};
        r.sizes = {std::uint32_t(members[a].size()), std::uint32_t(members[b].size())};
        for(std::uint32_t part : {a, b})
          if(!is_free_form(part))
          {
            const Fitted f = evaluate(surface[part], union_samples, tol);
            const bool better = !r.fit.accepted || type_class(f.model.type) < type_class(r.fit.model.type) ||
                                (type_class(f.model.type) == type_class(r.fit.model.type) && f.residual < r.fit.residual);
            if(better && fits_both_parts(f))
              r.fit = f;
          }
        if(!r.fit.accepted)
        {
          r.fit = fit_simplest(union_samples, tol);
          r.fit.accepted = fits_both_parts(r.fit);
        }
      });
      for(std::size_t i = 0; i < to_fit.size(); ++i)
        known[to_fit[i]] = fitted[i];
      // accepted fits (all of the current versions), and pairs of free-form segments
      std::vector<std::tuple<double, std::uint32_t, std::uint32_t, Surface_model>> candidates;
      for(const Pair& pair : pairs)
      {
        const Pair_fit& k = known[pair];
        if(k.fit.accepted)
          candidates.emplace_back(k.fit.residual, pair.first, pair.second, k.fit.model);
        else if(is_free_form(pair.first) && is_free_form(pair.second))
          candidates.emplace_back(std::numeric_limits<double>::infinity(), pair.first, pair.second, Surface_model());
      }
      std::sort(candidates.begin(), candidates.end(),
                [](const auto& x, const auto& y) { return std::get<0>(x) < std::get<0>(y); });
      std::vector<char> touched(surface.size(), 0);
      std::vector<std::uint32_t> grown;
      for(const auto& c : candidates)
      {
        const std::uint32_t a = std::get<1>(c), b = std::get<2>(c);
        if(touched[a] || touched[b])
          continue;
        touched[a] = touched[b] = 1;
        for(std::uint32_t f : members[b])
          label[f] = a;
        members[a].insert(members[a].end(), members[b].begin(), members[b].end());
        members[b].clear();
        surface[a] = std::get<3>(c);
        ++version[a];
        grown.push_back(a);
        merged = true;
      }
      for_each_index<ConcurrencyTag>(grown.size(), 1, [] { return 0; }, [&](int, std::size_t i) {
        refit_segment(grown[i], members[grown[i]]);
      });
    }
    compact();
  }

  // 3. Border faces move to the adjacent segment whose surface fits them best; faces of no segment join
  // their best neighbour; segments refitted after each round.
  void settle_borders(int rounds)
  {
    for(int round = 0; round < rounds; ++round)
    {
      bool moved = false;
      std::vector<std::uint32_t> next(label);
      for(std::uint32_t f = 0; f < F.size(); ++f)
      {
        std::uint32_t best = label[f];
        double best_cost = label[f] == none ? std::numeric_limits<double>::infinity() : face_cost(surface[label[f]], F.sample[f], tol);
        for(std::uint32_t g : F.neighbour[f])
        {
          if(g == Segmentation_faces::none || label[g] == none || label[g] == label[f])
            continue;
          const double c = face_cost(surface[label[g]], F.sample[f], tol);
          if(c < best_cost - 1e-9)
          {
            best_cost = c;
            best = label[g];
          }
        }
        if(best != label[f])
        {
          next[f] = best;
          moved = true;
        }
      }
      label.swap(next);
      if(!moved && std::find(label.begin(), label.end(), none) == label.end())
        break;
      refit();
    }
  }

  // 4. Segments of fewer than `minimum_faces` faces are dissolved into their neighbours.
  void dissolve_small_segments(std::size_t minimum_faces)
  {
    const std::vector<std::vector<std::uint32_t>> members = segment_members();
    bool dissolved = false;
    for(std::size_t s = 0; s < members.size(); ++s)
      if(members[s].size() < minimum_faces && members[s].size() < F.size())
      {
        for(std::uint32_t f : members[s])
          label[f] = none;
        dissolved = true;
      }
    if(!dissolved)
      return;
    // faces of no segment take the label of a labelled neighbour (best fit), front by front
    for(bool changed = true; changed;)
    {
      changed = false;
      for(std::uint32_t f = 0; f < F.size(); ++f)
        if(label[f] == none)
        {
          double best_cost = std::numeric_limits<double>::infinity();
          for(std::uint32_t g : F.neighbour[f])
            if(g != Segmentation_faces::none && label[g] != none)
            {
              const double c = face_cost(surface[label[g]], F.sample[f], tol);
              if(c < best_cost)
              {
                best_cost = c;
                label[f] = label[g];
                changed = true;
              }
            }
        }
    }
    for(std::uint32_t& l : label) // isolated faces with no labelled neighbour
      if(l == none)
        l = add_surface(Surface_model());
    compact();
    refit();
  }

  // 5. Adjacent fitted segments whose surfaces' normal derivatives jump at their border while the
  // faces' do not are bands of one smooth surface: one free-form segment (segment_fundamental_surfaces(),
  // step 5). `rings` rings of faces on each side of the border are measured.
  void merge_smooth_continuations(std::size_t rings)
  {
    typedef std::pair<std::uint32_t, std::uint32_t> Pair;
    std::map<Pair, std::vector<Pair>> border; // the face pairs across the border of two segments
    for(std::uint32_t f = 0; f < F.size(); ++f)
      for(std::uint32_t g : F.neighbour[f])
        if(g != Segmentation_faces::none && label[f] != none && label[g] != none && label[f] < label[g])
          border[{label[f], label[g]}].push_back({f, g});
    std::vector<std::uint32_t> parent(surface.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::function<std::uint32_t(std::uint32_t)> root = [&](std::uint32_t s) { return parent[s] == s ? s : parent[s] = root(parent[s]); };
    bool merged = false;
    for(const auto& b : border)
    {
      const std::uint32_t a = b.first.first, c = b.first.second;
      if(surface[a].type == Surface_type::free_form || surface[c].type == Surface_type::free_form)
        continue;
      double turn = 0;
      for(const Pair& fg : b.second)
        turn += std::acos(std::max(-1.0, std::min(1.0, F.facet_normal[fg.first].dot(F.facet_normal[fg.second]))));
      if(turn > tol.angle * double(b.second.size())) // a crease
        continue;
      std::vector<std::uint32_t> start_a, start_c;
      for(const Pair& fg : b.second)
      {
        start_a.push_back(fg.first);
        start_c.push_back(fg.second);
      }
      const std::vector<std::uint32_t> side_a = near(start_a, rings), side_c = near(start_c, rings);
      // twice the 12 unknowns of a regression on each side (a fragment of a few faces, fitted by
      // anything, says nothing of the surface)
      if(side_a.size() < 24 || side_c.size() < 24)
        continue;
      Vec3 origin = Vec3::Zero();
      for(std::uint32_t f : start_a)
        origin += F.sample[f].p / double(start_a.size());
      const Eigen::Matrix3d data_a = normal_derivative(side_a, origin, nullptr), data_c = normal_derivative(side_c, origin, nullptr),
                            fit_a = normal_derivative(side_a, origin, &surface[a]), fit_c = normal_derivative(side_c, origin, &surface[c]);
      const double fit_jump = (fit_c - fit_a).norm(), data_jump = (data_c - data_a).norm();
      if(fit_jump > std::max(fit_a.norm(), fit_c.norm()) / 3 && data_jump < 0.5 * fit_jump)
      {
        parent[root(a)] = root(c);
        merged = true;
      }
    }
    if(!merged)
      return;
    for(std::uint32_t s = 0; s < surface.size(); ++s)
      if(root(s) != s)
        surface[root(s)] = Surface_model();
    for(std::uint32_t& l : label)
      if(l != none)
        l = root(l);
    compact();
  }

  // Segments renumbered in the order of their first face.
  void compact()
  {
    std::vector<std::uint32_t> renumber(surface.size(), none);
    std::vector<Surface_model> kept;
    for(std::uint32_t& l : label)
      if(l != none)
      {
        if(renumber[l] == none)
        {
          renumber[l] = std::uint32_t(kept.size());
          kept.push_back(surface[l]);
        }
        l = renumber[l];
      }
    surface.swap(kept);
  }

  std::vector<std::vector<std::uint32_t>> segment_members() const
  {
    std::vector<std::vector<std::uint32_t>> members(surface.size());
    for(std::uint32_t f = 0; f < F.size(); ++f)
      if(label[f] != none)
        members[label[f]].push_back(f);
    return members;
  }

  // Each segment's surface refitted to its faces with its type (free-form when that fails).
  void refit()
  {
    const std::vector<std::vector<std::uint32_t>> members = segment_members();
    for(std::size_t s = 0; s < members.size(); ++s)
      refit_segment(std::uint32_t(s), members[s]);
  }

  void refit_segment(std::uint32_t s, const std::vector<std::uint32_t>& members)
  {
    if(surface[s].type == Surface_type::free_form || members.empty())
      return;
    const std::vector<Surface_sample> samples = samples_of(F, members);
    const Surface_model m = fit_model(surface[s].type, samples);
    if(m.type != Surface_type::free_form && std::isfinite(rms_distance(m, samples)))
      surface[s] = m;
  }

  const std::vector<std::uint32_t>& labels() const { return label; }
  const std::vector<Surface_model>& surfaces() const { return surface; }

private:
  std::uint32_t add_surface(const Surface_model& m)
  {
    surface.push_back(m);
    return std::uint32_t(surface.size() - 1);
  }

  void add_segment(const std::vector<std::uint32_t>& faces, const Surface_model& m)
  {
    const std::uint32_t s = add_surface(m);
    for(std::uint32_t f : faces)
      label[f] = s;
  }

  std::vector<std::pair<std::uint32_t, std::uint32_t>> adjacent_segment_pairs() const
  {
    std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for(std::uint32_t f = 0; f < F.size(); ++f)
      for(std::uint32_t g : F.neighbour[f])
        if(g != Segmentation_faces::none && label[f] != none && label[g] != none && label[f] < label[g])
          pairs.insert({label[f], label[g]});
    return {pairs.begin(), pairs.end()};
  }

  // Greedy extraction in a patch no single surface fits: the free face deepest inside the free part
  // (most rings from its border) seeds a surface fitted to its neighbourhood, grown across edges
  // through the faces that fit it and refitted until it no longer changes. Seeds whose neighbourhood
  // fits nothing are skipped; what no surface takes becomes free-form segments (its connected parts).
  void extract_surfaces(const std::vector<std::uint32_t>& faces)
  {
    const std::uint32_t inside = ++stamp;
    scope.resize(F.size(), 0);
    for(std::uint32_t f : faces)
      scope[f] = inside;
    std::vector<char> tried(F.size(), 0);
    std::vector<std::uint32_t> free_faces(faces);
    auto is_free = [&](std::uint32_t g) { return scope[g] == inside && label[g] == none; };
    while(true)
    {
      free_faces.erase(std::remove_if(free_faces.begin(), free_faces.end(), [&](std::uint32_t f) { return label[f] != none; }),
                       free_faces.end());
      const std::vector<std::uint32_t> depth = ring_depth(free_faces, is_free);
      std::uint32_t seed = none;
      for(std::uint32_t f : free_faces)
        if(!tried[f] && (seed == none || depth[f] > depth[seed]))
          seed = f;
      if(seed == none)
        break;
      const std::size_t rings = std::max<std::size_t>(2, std::min<std::size_t>(depth[seed], 4));
      const std::vector<std::uint32_t> start = flood(F, seed, rings, is_free, mark, ++stamp);
      for(std::uint32_t f : start)
        tried[f] = 1;
      if(start.size() < 6)
        continue;
      Fitted fit = fit_simplest(samples_of(F, start), tol);
      if(!fit.accepted)
        continue;
      std::vector<std::uint32_t> region;
      for(int iteration = 0; iteration < 4; ++iteration)
      {
        std::vector<std::uint32_t> grown = flood(F, seed, F.size(), [&](std::uint32_t g) {
          return is_free(g) && face_fits(fit.model, F.sample[g], tol);
        }, mark, ++stamp);
        const bool same = grown.size() == region.size();
        region.swap(grown);
        if(same || region.size() < 3)
          break;
        const Surface_model m = fit_model(fit.model.type, samples_of(F, region));
        if(m.type == Surface_type::free_form)
          break;
        fit.model = m;
      }
      if(region.size() < 3)
        continue;
      add_segment(region, fit.model);
    }
    // the rest: connected free parts, free-form
    for(std::uint32_t f : free_faces)
      if(label[f] == none)
        add_segment(flood(F, f, F.size(), is_free, mark, ++stamp), Surface_model());
  }

  // rings of free faces between each free face and the border of the free part (0 on the border)
  template <class Free>
  std::vector<std::uint32_t> ring_depth(const std::vector<std::uint32_t>& free_faces, Free&& is_free) const
  {
    std::vector<std::uint32_t> depth(F.size(), none), queue;
    for(std::uint32_t f : free_faces)
      for(std::uint32_t g : F.neighbour[f])
        if(g == Segmentation_faces::none || !is_free(g))
        {
          depth[f] = 0;
          queue.push_back(f);
          break;
        }
    for(std::size_t i = 0; i < queue.size(); ++i)
      for(std::uint32_t g : F.neighbour[queue[i]])
        if(g != Segmentation_faces::none && is_free(g) && depth[g] == none)
        {
          depth[g] = depth[queue[i]] + 1;
          queue.push_back(g);
        }
    for(std::uint32_t f : free_faces) // a closed free part with no border: all equally deep
      if(depth[f] == none)
        depth[f] = 0;
    return depth;
  }

  // the faces of the segments of `start` at most `rings` rings from them, within their own segment
  std::vector<std::uint32_t> near(const std::vector<std::uint32_t>& start, std::size_t rings)
  {
    const std::uint32_t visit = ++stamp;
    std::vector<std::uint32_t> out;
    for(std::uint32_t f : start)
      if(mark[f] != visit)
      {
        mark[f] = visit;
        out.push_back(f);
      }
    std::size_t begin = 0;
    for(std::size_t ring = 0; ring < rings; ++ring)
    {
      const std::size_t end = out.size();
      for(std::size_t i = begin; i < end; ++i)
        for(std::uint32_t g : F.neighbour[out[i]])
          if(g != Segmentation_faces::none && mark[g] != visit && label[g] == label[out[i]])
          {
            mark[g] = visit;
            out.push_back(g);
          }
      begin = end;
    }
    return out;
  }

  // d(normal)/d(position) by weighted least squares of n = n0 + J (p - origin) over the faces: their
  // normals, or those of the surface `m` at their centroids. A small ridge settles the directions the
  // positions do not span (a strip along a border is nearly flat).
  Eigen::Matrix3d normal_derivative(const std::vector<std::uint32_t>& faces, const Vec3& origin, const Surface_model* m) const
  {
    Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
    Eigen::Matrix<double, 4, 3> B = Eigen::Matrix<double, 4, 3>::Zero();
    for(std::uint32_t f : faces)
    {
      const Surface_sample& x = F.sample[f];
      Eigen::Vector4d row;
      row << 1, x.p - origin;
      const Vec3 n = m ? m->normal(x.p) : F.facet_normal[f];
      A += x.w * row * row.transpose();
      B += x.w * row * n.transpose();
    }
    A.bottomRightCorner<3, 3>() += 1e-6 * A.bottomRightCorner<3, 3>().trace() * Eigen::Matrix3d::Identity();
    const Eigen::Matrix<double, 4, 3> X = A.ldlt().solve(B);
    return X.bottomRows<3>().transpose();
  }

  const Segmentation_faces& F;
  Fit_tolerance tol;
  std::vector<std::uint32_t> label;
  std::vector<Surface_model> surface;
  std::vector<std::uint32_t> mark, scope;
  std::uint32_t stamp = 0;
};

// Seeds spread over the surface, denser where it is curved: face f wants no other seed within
// min(spacing, 1 / curvature) (an arc of one radian; curvature from the turn of the normals across its
// edges), but not under 4 of its edge lengths. Faces are taken in order of that radius (the most curved
// first) and kept when no kept seed lies within the smaller of the two radii; a hash grid finds them.
inline std::vector<std::uint32_t> spread_seeds(const Segmentation_faces& F, double spacing)
{
  std::vector<double> radius(F.size(), spacing);
  for(std::uint32_t f = 0; f < F.size(); ++f)
  {
    double curvature = 0;
    for(std::uint32_t g : F.neighbour[f])
      if(g != Segmentation_faces::none)
      {
        const double d = (F.sample[g].p - F.sample[f].p).norm();
        const double angle = std::acos(std::max(-1.0, std::min(1.0, F.sample[g].n.dot(F.sample[f].n))));
        if(d > 0)
          curvature = std::max(curvature, angle / d);
      }
    if(curvature > 0)
      radius[f] = std::min(spacing, 1 / curvature);
    radius[f] = std::max(radius[f], std::min(spacing, 4 * F.sample[f].tolerance / 0.3));
  }
  std::vector<std::uint32_t> order(F.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return radius[a] < radius[b]; });
  std::map<std::array<long, 3>, std::vector<std::uint32_t>> grid;
  auto cell = [&](const Vec3& p) {
    return std::array<long, 3>{{long(std::floor(p(0) / spacing)), long(std::floor(p(1) / spacing)), long(std::floor(p(2) / spacing))}};
  };
  std::vector<std::uint32_t> seeds;
  for(std::uint32_t f : order)
  {
    const Vec3& p = F.sample[f].p;
    const std::array<long, 3> c = cell(p);
    bool near = false;
    for(long dx = -1; dx <= 1 && !near; ++dx)
      for(long dy = -1; dy <= 1 && !near; ++dy)
        for(long dz = -1; dz <= 1 && !near; ++dz)
        {
          const auto it = grid.find({{c[0] + dx, c[1] + dy, c[2] + dz}});
          if(it != grid.end())
            for(std::uint32_t g : it->second)
              near = near || (F.sample[g].p - p).norm() < std::min(radius[f], radius[g]);
        }
    if(!near)
    {
      grid[c].push_back(f);
      seeds.push_back(f);
    }
  }
  return seeds;
}

template <class TriangleMesh, class VertexPointMap, class FaceIndexMap>
Segmentation_faces segmentation_faces(const TriangleMesh& tm, VertexPointMap vpm, FaceIndexMap fim, double& mean_edge)
{
  Segmentation_faces F;
  F.sample.resize(num_faces(tm));
  F.neighbour.resize(num_faces(tm));
  double edge_sum = 0;
  std::size_t edge_count = 0;
  for(auto f : faces(tm))
  {
    const std::size_t i = get(fim, f);
    std::array<Vec3, 3> p;
    int k = 0;
    for(auto h : CGAL::halfedges_around_face(halfedge(f, tm), tm))
    {
      const auto& q = get(vpm, target(h, tm));
      if(k < 3)
        p[k] = Vec3(CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z()));
      const auto o = opposite(h, tm);
      F.neighbour[i][k % 3] = is_border(o, tm) ? Segmentation_faces::none : std::uint32_t(get(fim, face(o, tm)));
      ++k;
    }
    if(k != 3)
      throw Invalid_mesh_error("segment_fundamental_surfaces: face " + std::to_string(i) + " has " + std::to_string(k) +
                               " sides; triangulate the mesh first (PMP::triangulate_faces)");
    const Vec3 cross = (p[1] - p[0]).cross(p[2] - p[0]);
    const double area = 0.5 * cross.norm();
    double perimeter = 0;
    for(int j = 0; j < 3; ++j)
      perimeter += (p[(j + 1) % 3] - p[j]).norm();
    F.sample[i] = {(p[0] + p[1] + p[2]) / 3, area > 0 ? Vec3(cross.normalized()) : Vec3::UnitZ(), area, perimeter / 3};
    edge_sum += perimeter;
    edge_count += 3;
  }
  mean_edge = edge_count ? edge_sum / edge_count : 0;
  return F;
}

} // namespace internal

/// \ingroup PkgIsophoticMetricSegmentation
///
/// \brief segments a triangle mesh into fundamental surfaces: every segment gets a type (plane,
/// cylinder, cone, sphere, torus or free-form) with its fitted parameters and residual.
///
/// 1. *Patches*: the geodesic Voronoi cells (`partition_by_nearest_seed()`, one propagation) in the
///    isophotic metric of seeds spread over the surface, closer together where it is curved (see
///    `seed_spacing`). Crossing a fillet or a sharp edge is long in this metric, so the cells stop at
///    features and stretch along blends.
/// 2. *Split*: a cell that one surface fits (the simplest type, see below) is a segment. Otherwise
///    (equal-radius fillets meeting at a spherical corner blend, a pipe and its bend: the metric sees no
///    feature between tangent surfaces of the same curvature) surfaces are grown inside the patch: the
///    face deepest inside the unclaimed part seeds a surface fitted to its neighbourhood, which grows
///    across edges through the faces it fits and is refitted until it stops changing. What fits no
///    surface becomes free-form segments.
/// 3. *Merge*: adjacent segments whose union one surface fits become one (pieces of one plane that the
///    growth cut, a cylinder seen as facets).
/// 4. *Borders*: each face along a border goes to the adjacent segment whose surface fits it best
///    (distance and normal angle, each in units of its tolerance); surfaces are refitted; repeated.
///    Segments of fewer than `minimum_segment_faces` faces are dissolved into their neighbours (again
///    at the very end, after the last borders are settled).
/// 5. *Free-form*: a smooth surface that no fundamental surface fits (a spline surface of revolution)
///    is cut by the fits into bands, each within the tolerances, whose parameters jump at their
///    borders where the surface's curvature does not. Near the border of two fitted segments (3 rings
///    of faces on each side, at least 24), the derivative of the normal (normals regressed linearly on
///    positions) is measured on each side, on the faces' own normals and on the two fitted surfaces at
///    the same points. Where the surfaces' derivative jumps (by a third of the larger) and the faces'
///    by less than half as much, and the facet normals do not turn across the border by more than
///    `angle_tolerance` on average (no crease), the two segments become one free-form segment. A true
///    border (a fillet meeting a plane, a pipe its bend) shows the same jump on the faces as on the
///    surfaces; on noisy meshes the faces' derivatives are too noisy for the test to pass.
///
/// A face fits a surface when its centroid lies within `distance_tolerance` and its normal (face
/// normals smoothed across edges by a bilateral filter, which averages noise and keeps sharp edges;
/// 3 iterations, and about \f$ 400 s^2 \f$ more for noise of \f$ s \f$ mean edge lengths, since the
/// noise of the averaged normals falls as one over the square root of the iterations) within
/// `angle_tolerance` of the surface's. A surface fits a set of faces when its residual (RMS
/// distance) is at most 0.6 `distance_tolerance` and the faces that fit hold 90 % of the area. The
/// simplest type is tried first: plane; then the better of cylinder and sphere; then cone and torus.
///
/// \tparam ConcurrencyTag `CGAL::Parallel_tag` (what the default `CGAL::Parallel_if_available_tag` is when
///   TBB is linked) fits the candidate merges of step 3 on TBB's threads; `CGAL::Sequential_tag` on the
///   calling thread. The result is the same.
/// \tparam TriangleMesh a model of `FaceListGraph` (triangles)
/// \tparam FaceSegmentMap a writable property map from faces to an integer type
/// \tparam OutputIterator accepts `Fundamental_surface_segment`, one per segment in the order of the ids
///
/// \param tm the mesh (closed or open, one or several components)
/// \param segment receives the segment id of every face, from 0
/// \param out receives the segment descriptions
/// \param np named parameters:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{distance_tolerance} \cgalParamDescription{largest distance of a face's centroid
///     to its surface} \cgalParamDefault{for each face, 0.3 times its mean edge length, and at least 1.5
///     times the noise of the mesh (`estimate_mesh_noise()`; a centroid averages three vertices, so this
///     is 2.6 deviations of its noise)} \cgalParamNEnd
///   \cgalParamNBegin{angle_tolerance} \cgalParamDescription{largest angle (degrees) between a face's
///     smoothed normal and its surface's normal} \cgalParamDefault{10, or 2.5 times the noise of the
///     normals when larger (the median angle between a face's normal and its smoothed normal: 0.3 to
///     2.5 degrees on the clean CAD parts, 10.5 with noise of 0.2 edge lengths)} \cgalParamNEnd
///   \cgalParamNBegin{seed_spacing} \cgalParamDescription{largest distance in space between the seeds of
///     step 1; around a face the spacing is at most one radius of curvature (an arc of one radian, from the
///     turn of the smoothed normals across its edges), and at least 4 of its edge lengths}
///     \cgalParamDefault{0.05 times the bounding-box diagonal} \cgalParamNEnd
///   \cgalParamNBegin{minimum_segment_faces} \cgalParamDescription{smaller segments are dissolved}
///     \cgalParamDefault{8} \cgalParamNEnd
///   \cgalParamNBegin{euclidean_weight, isophotic_weight, weight_length_scale} \cgalParamDescription{the
///     metric of step 1} \cgalParamDefault{0.5, 0.5, the bounding-box diagonal} \cgalParamNEnd
///   \cgalParamNBegin{vertex_point_map} \cgalParamDefault{`boost::get(CGAL::vertex_point, tm)`} \cgalParamNEnd
///   \cgalParamNBegin{face_index_map} \cgalParamDefault{the mesh's face index map} \cgalParamNEnd
///   \cgalParamNBegin{callback} \cgalParamDescription{told of the advancement in [0,1]: during the
///     propagation of step 1 (its first half), then after each step; returning `false` stops the
///     segmentation with a `Cancelled_error`} \cgalParamType{a callable `bool(double)`} \cgalParamDefault{none} \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \returns the number of segments
/// \throws Invalid_parameter_error for a non-positive or non-finite tolerance or radius
/// \throws Invalid_mesh_error for a face that is not a triangle (and what `segment_by_region_growing()` throws)
/// \throws Cancelled_error when the callback asks to stop
template <class ConcurrencyTag = CGAL::Parallel_if_available_tag, class TriangleMesh, class FaceSegmentMap,
          class OutputIterator, class NamedParameters = parameters::Default_named_parameters>
std::size_t segment_fundamental_surfaces(const TriangleMesh& tm, FaceSegmentMap segment, OutputIterator out,
                                         const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  if(num_faces(tm) == 0)
    return 0;
  const internal::Progress_callback progress = internal::Progress_callback::of(np);
  const auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_const_property_map(CGAL::vertex_point, tm));
  const auto fim = CGAL::get_initialized_face_index_map(tm, np);
  const CGAL::Bbox_3 box = CGAL::Polygon_mesh_processing::bbox(tm, CGAL::parameters::vertex_point_map(vpm));
  const double diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                    CGAL::square(box.zmax() - box.zmin()));
  double mean_edge = 0;
  internal::Segmentation_faces F = internal::segmentation_faces(tm, vpm, fim, mean_edge);

  auto positive = [](double v, const char* name) {
    if(!(v > 0) || !std::isfinite(v))
      throw Invalid_parameter_error(std::string("segment_fundamental_surfaces: ") + name + " must be positive and finite (got " +
                                    std::to_string(v) + ")");
    return v;
  };
  // the noise of the mesh along its normals (a length; of the order of h^2 curvature on a clean mesh)
  const double noise = estimate_mesh_noise(tm, CGAL::parameters::vertex_point_map(vpm)).noise;
  // each face's distance tolerance: the given one, or 0.3 times the face's mean edge length (the
  // faceting error scales with the local edge length), and at least 1.5 times the noise: a centroid
  // averages three vertices, its noise is noise / sqrt(3), and 1.5 noise is 2.6 of its deviations
  const bool relative = parameters::is_default_parameter<NamedParameters, internal_np::distance_tolerance_t>::value;
  const double distance = relative ? 0.3 : positive(choose_parameter(get_parameter(np, internal_np::distance_tolerance), 1.0),
                                                   "distance_tolerance");
  for(internal::Surface_sample& x : F.sample)
    x.tolerance = relative ? std::max({distance * x.tolerance, 1.5 * noise, 1e-9 * mean_edge}) : distance;
  const double radius = positive(choose_parameter(get_parameter(np, internal_np::seed_spacing), 0.05 * diagonal), "seed_spacing");
  const std::size_t minimum_faces = choose_parameter(get_parameter(np, internal_np::minimum_segment_faces), std::size_t(8));

  // the noise of the normals: median angle between a face's normal and its normal smoothed by three
  // iterations. Then more iterations on a noisy mesh: each widens the averaged disc, whose number of
  // faces grows with the iterations, so the noise of the normals falls as one over the square root of
  // the iterations, and bringing noise s (in edge lengths) to that of a clean mesh takes some 400 s^2
  // (16 at s = 0.2; at most 4 on the clean parts, whose estimate, from their curvature, stays under 0.11).
  std::vector<double> turn(F.size());
  {
    F.facet_normal.resize(F.size());
    for(std::size_t f = 0; f < F.size(); ++f)
      F.facet_normal[f] = F.sample[f].n;
    const double relative_noise = mean_edge > 0 ? noise / mean_edge : 0;
    internal::smooth_normals(F, 3, 0.5);
    for(std::size_t f = 0; f < F.size(); ++f)
      turn[f] = std::acos(std::max(-1.0, std::min(1.0, F.facet_normal[f].dot(F.sample[f].n))));
    std::nth_element(turn.begin(), turn.begin() + turn.size() / 2, turn.end());
    internal::smooth_normals(F, int(std::min(60.0, 400 * relative_noise * relative_noise)), 0.5);
  }
  const double normal_noise = turn[turn.size() / 2];
  internal::Fit_tolerance tol{
    parameters::is_default_parameter<NamedParameters, internal_np::angle_tolerance_t>::value
      ? std::max(10 * CGAL_PI / 180, 2.5 * normal_noise)
      : positive(choose_parameter(get_parameter(np, internal_np::angle_tolerance), 10.0), "angle_tolerance") * CGAL_PI / 180};

  // 1. isophotic patches: the geodesic Voronoi cells of seeds spread over the surface
  std::vector<std::size_t> patch(F.size());
  {
    typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;
    std::vector<face_descriptor> face_of(F.size());
    for(auto f : faces(tm))
      face_of[get(fim, f)] = f;
    std::vector<std::vector<face_descriptor>> seeds;
    for(std::uint32_t f : internal::spread_seeds(F, radius))
      seeds.push_back({face_of[f]});
    auto patch_map = get(CGAL::dynamic_face_property_t<std::size_t>(), tm);
    std::function<bool(double)> partition_progress; // the first half of the advancement
    if(progress)
      partition_progress = [&progress](double a) {
        progress.report(0.5 * a, "segment_fundamental_surfaces");
        return true;
      };
    partition_by_nearest_seed(seeds, tm, patch_map,
                              parameters::euclidean_weight(choose_parameter(get_parameter(np, internal_np::euclidean_weight), 0.5))
                                .isophotic_weight(choose_parameter(get_parameter(np, internal_np::isophotic_weight), 0.5))
                                .weight_length_scale(choose_parameter(get_parameter(np, internal_np::weight_length_scale), diagonal))
                                .vertex_point_map(vpm)
                                .callback(partition_progress));
    for(auto f : faces(tm))
      patch[get(fim, f)] = get(patch_map, f);
  }
  internal::Fundamental_segmentation s(F, tol);
  auto stage_done = [&progress](double a) { progress.report(a, "segment_fundamental_surfaces"); };
  stage_done(0.5);
  s.split_patches(patch);                    // 2.
  stage_done(0.6);
  s.merge_segments<ConcurrencyTag>();        // 3.
  stage_done(0.75);
  s.settle_borders(4);                       // 4.
  s.dissolve_small_segments(minimum_faces);
  stage_done(0.8);
  s.merge_segments<ConcurrencyTag>();
  stage_done(0.95);
  s.merge_smooth_continuations(3);           // 5.
  s.settle_borders(2);
  s.dissolve_small_segments(minimum_faces);  // what the last borders left too small
  s.compact();

  // output: ids, and each segment's surface refitted to its final faces
  const std::vector<std::vector<std::uint32_t>> members = s.segment_members();
  for(auto f : faces(tm))
    put(segment, f, s.labels()[get(fim, f)]);
  for(std::size_t i = 0; i < members.size(); ++i)
  {
    const std::vector<internal::Surface_sample> samples = internal::samples_of(F, members[i]);
    Fundamental_surface_segment d;
    d.surface = internal::to_fundamental_surface(s.surfaces()[i], internal::rms_distance(s.surfaces()[i], samples));
    d.number_of_faces = members[i].size();
    for(const auto& x : samples)
      d.area += x.w;
    *out++ = d;
  }
  return members.size();
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_SEGMENTATION_SEGMENT_FUNDAMENTAL_SURFACES_H
