// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Python bindings of the typed segmentation: segment_fundamental_surfaces() and
// fit_fundamental_surface(). Surfaces reach Python as dicts holding the parameters that carry meaning
// for their type.
#include "module.h"

#include <CGAL/Isophotic_metric/Segmentation/fit_fundamental_surface.h>
#include <CGAL/Isophotic_metric/Segmentation/segment_fundamental_surfaces.h>

#include <pybind11/stl.h>

#include <iterator>
#include <optional>

namespace isophotic_metric_python {

namespace {

// Segment ids written into a numpy array, by face index.
struct Segment_id_map
{
  typedef Face key_type;
  typedef std::int64_t value_type;
  typedef std::int64_t& reference;
  typedef boost::writable_property_map_tag category;
  std::int64_t* ids;
  friend void put(const Segment_id_map& m, Face f, std::int64_t id) { m.ids[std::size_t(f)] = id; }
};

py::array_t<double> vector3(double x, double y, double z)
{
  py::array_t<double> a(3);
  a.mutable_data()[0] = x;
  a.mutable_data()[1] = y;
  a.mutable_data()[2] = z;
  return a;
}

// The surface as a dict: "type", the parameters of that type (see Fundamental_surface), "outward"
// and "residual".
py::dict surface_dict(const IM::Fundamental_surface& s)
{
  typedef IM::Surface_type T;
  py::dict d;
  d["type"] = IM::surface_type_name(s.type);
  if(s.type != T::free_form)
    d["center"] = vector3(s.center.x(), s.center.y(), s.center.z());
  if(s.type == T::plane || s.type == T::cylinder || s.type == T::cone || s.type == T::torus)
    d["axis"] = vector3(s.axis.x(), s.axis.y(), s.axis.z());
  if(s.type == T::cylinder || s.type == T::sphere || s.type == T::torus)
    d["radius"] = s.radius;
  if(s.type == T::torus)
    d["minor_radius"] = s.minor_radius;
  if(s.type == T::cone)
    d["half_angle"] = s.half_angle;
  if(s.type != T::free_form)
    d["outward"] = s.outward;
  d["residual"] = s.residual;
  return d;
}

IM::Surface_type surface_type_of(const std::string& name)
{
  for(int t = 0; t <= int(IM::Surface_type::free_form); ++t)
    if(name == IM::surface_type_name(IM::Surface_type(t)))
      return IM::Surface_type(t);
  throw py::value_error("unknown surface type '" + name +
                        "'; use 'plane', 'cylinder', 'cone', 'sphere' or 'torus'");
}

// The options whose C++ default is computed from the mesh (None from Python: not given). Each given
// one is added to the named parameters `np` by its setter before `run(np)`.
template <class NP, class Run>
void with_given(const NP& np, Run&& run)
{
  run(np);
}

template <class NP, class Run, class Setter, class... Rest>
void with_given(const NP& np, Run&& run, const std::optional<double>& value, Setter set, Rest&&... rest)
{
  if(value)
    with_given(set(np, *value), run, rest...);
  else
    with_given(np, run, rest...);
}

} // namespace

void bind_segmentation(py::module_& m)
{
  m.def("segment_fundamental_surfaces",
        [](const Mesh& mesh, std::optional<double> distance_tolerance, std::optional<double> angle_tolerance,
           std::optional<double> seed_spacing, long long minimum_segment_faces, double w, double wp,
           std::optional<double> L, py::object progress) {
          if(minimum_segment_faces < 0)
            throw IM::Invalid_parameter_error("segment_fundamental_surfaces: minimum_segment_faces must be 0 or more (got " +
                                              std::to_string(minimum_segment_faces) + ")");
          py::array_t<std::int64_t> ids(py::ssize_t(mesh.number_of_faces()));
          std::vector<IM::Fundamental_surface_segment> segments;
          run_interruptible([&](const Callback& callback) {
            const auto np = IM::parameters::minimum_segment_faces(std::size_t(minimum_segment_faces))
                              .euclidean_weight(w)
                              .isophotic_weight(wp)
                              .callback(callback);
            with_given(
              np,
              [&](const auto& given) {
                IM::segment_fundamental_surfaces(mesh, Segment_id_map{ids.mutable_data()}, std::back_inserter(segments),
                                                 given);
              },
              distance_tolerance, [](const auto& p, double v) { return p.distance_tolerance(v); },
              angle_tolerance, [](const auto& p, double v) { return p.angle_tolerance(v); },
              seed_spacing, [](const auto& p, double v) { return p.seed_spacing(v); },
              L, [](const auto& p, double v) { return p.weight_length_scale(v); });
          }, progress);
          py::list descriptions;
          for(const IM::Fundamental_surface_segment& s : segments)
          {
            py::dict d = surface_dict(s.surface);
            d["area"] = s.area;
            d["number_of_faces"] = s.number_of_faces;
            descriptions.append(d);
          }
          return py::make_tuple(ids, descriptions);
        },
        py::arg("mesh"), py::kw_only(), py::arg("distance_tolerance") = py::none(),
        py::arg("angle_tolerance") = py::none(), py::arg("seed_spacing") = py::none(),
        py::arg("minimum_segment_faces") = 8, py::arg("euclidean_weight") = 0.5, py::arg("isophotic_weight") = 0.5,
        py::arg("weight_length_scale") = py::none(), py::arg("progress") = py::none(),
        "segment_fundamental_surfaces(mesh, *, distance_tolerance=None, angle_tolerance=None,\n"
        "    seed_spacing=None, minimum_segment_faces=8, euclidean_weight=0.5, isophotic_weight=0.5,\n"
        "    weight_length_scale=None, progress=None) -> ((m,) int64 segment id of every face, list of segments)\n\n"
        "Segments a triangle mesh into fundamental surfaces of CAD (plane, cylinder, cone, sphere,\n"
        "torus, or free-form): geodesic Voronoi patches in the isophotic metric, split by surface\n"
        "growth where one surface does not fit, merged where one does, borders settled. Segment ids\n"
        "start at 0; segment i is described by the i-th dict of the list: 'type', the parameters of\n"
        "its type ('center', 'axis', 'radius', 'minor_radius', 'half_angle' as for\n"
        "fit_fundamental_surface), 'outward', 'residual' (RMS distance), 'area', 'number_of_faces'.\n\n"
        "distance_tolerance: largest distance of a face's centroid to its surface (default: 0.3\n"
        "    times each face's mean edge length).\n"
        "angle_tolerance: largest angle in degrees between a face's smoothed normal and its surface's\n"
        "    (default: 10, or 2.5 times the noise of the normals when larger).\n"
        "seed_spacing: largest distance between the seeds of the patches (default: 0.05 times the\n"
        "    bounding-box diagonal).\n"
        "minimum_segment_faces: smaller segments are dissolved into their neighbours.\n"
        "euclidean_weight, isophotic_weight, weight_length_scale: the metric of the patches (default\n"
        "    L: the bounding-box diagonal).\n"
        "progress: None, or a callable progress(advancement in [0, 1]) -> bool, called during the\n"
        "    patches' propagation and after each step; False cancels (CancelledError). Ctrl-C\n"
        "    interrupts the call (KeyboardInterrupt).");

  m.def("fit_fundamental_surface",
        [](const std::string& type, py::object points, py::object normals, py::object weights) {
          const IM::Surface_type t = surface_type_of(type);
          const Double_array P = as_doubles(points, "points", -1, 3);
          const py::ssize_t n = P.shape(0);
          const Double_array N = as_doubles(normals, "normals", n, 3);
          std::vector<double> W(std::size_t(n), 1.0);
          if(!weights.is_none())
          {
            const Double_array given = as_doubles(weights, "weights", n, 0);
            std::copy(given.data(), given.data() + n, W.begin());
          }
          std::vector<IM::Fundamental_surface::Point_3> p;
          std::vector<IM::Fundamental_surface::Vector_3> v;
          for(py::ssize_t i = 0; i < n; ++i)
          {
            p.emplace_back(P.at(i, 0), P.at(i, 1), P.at(i, 2));
            v.emplace_back(N.at(i, 0), N.at(i, 1), N.at(i, 2));
          }
          IM::Fundamental_surface s;
          {
            py::gil_scoped_release release;
            s = IM::fit_fundamental_surface(t, p, v, W);
          }
          return surface_dict(s);
        },
        py::arg("type"), py::arg("points"), py::arg("normals"), py::arg("weights") = py::none(),
        "fit_fundamental_surface(type, points, normals, weights=None) -> dict\n\n"
        "Least-squares fit of a surface of the given type ('plane', 'cylinder', 'cone', 'sphere',\n"
        "'torus') to oriented samples: points (n, 3), unit normals (n, 3) all to one side of the\n"
        "surface, weights (n,) such as face areas (default 1). The dict holds 'type' and the\n"
        "parameters of that type: plane 'center' (a point of it), 'axis' (its normal); cylinder\n"
        "'center' (a point of the axis), 'axis', 'radius'; cone 'center' (the apex), 'axis' (into the\n"
        "cone), 'half_angle' (radians); sphere 'center', 'radius'; torus 'center', 'axis' (normal of the\n"
        "spine circle), 'radius' (spine), 'minor_radius' (tube); then 'outward' (normals point away\n"
        "from the axis or centre) and 'residual' (weighted RMS distance). A type that cannot be fitted\n"
        "(fewer than 3 samples, zero weight, no cone) gives type 'free-form' and an infinite residual.");
}

} // namespace isophotic_metric_python
