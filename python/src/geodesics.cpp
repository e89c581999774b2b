// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Python bindings of the geodesic side: Geodesic_solver (sources, bounded propagation, distances,
// labels, paths) and the one-shot distance field and path.
#include "module.h"

#include <CGAL/Isophotic_metric/Geodesics/Geodesic_solver.h>

#include <algorithm>
#include <iterator>

namespace isophotic_metric_python {

namespace {

typedef IM::Geodesic_solver<Mesh> Solver;
typedef Solver::Face_location Face_location;

Solver make_solver(const py::handle& mesh, const Metric_arguments& metric, bool store_windows,
                   int full_window_every = IM::internal::Window_propagation::default_full_record_every)
{
  return Solver(prepared_mesh(mesh, metric),
                IM::parameters::store_windows(store_windows).full_window_every(full_window_every));
}

// Surface points from Python: one face and (3,) coordinates, or (k,) faces and (k, 3) coordinates.
std::vector<Face_location> locations(const Mesh& mesh, const py::object& faces, const py::object& barycentric,
                                     bool& single)
{
  const py::array f = py::array::ensure(faces);
  single = f && f.ndim() == 0;
  const std::vector<std::uint32_t> ids = as_indices(faces, "face", "face", mesh.number_of_faces());
  const Double_array b = single ? as_doubles(py::array::ensure(barycentric).reshape({1, 3}), "barycentric", 1, 3)
                                : as_doubles(barycentric, "barycentric", py::ssize_t(ids.size()), 3);
  std::vector<Face_location> result;
  result.reserve(ids.size());
  for(std::size_t i = 0; i < ids.size(); ++i)
    result.push_back(Face_location(Face(Mesh::size_type(ids[i])), to_cpp_barycentric(b.at(i, 0), b.at(i, 1), b.at(i, 2))));
  return result;
}

// Applies `query` (no GIL) to every surface point; a float for one point, an array for several.
template <class Value, class Query>
py::object per_location(const Mesh& mesh, const py::object& faces, const py::object& barycentric, Query&& query)
{
  bool single = false;
  const std::vector<Face_location> points = locations(mesh, faces, barycentric, single);
  py::array_t<Value> result(py::ssize_t(points.size()));
  Value* out = result.mutable_data();
  {
    py::gil_scoped_release release;
    for(const Face_location& p : points)
      *out++ = query(p);
  }
  if(single)
    return py::cast(result.at(0));
  return std::move(result);
}

std::int64_t label(std::size_t l) { return l == Solver::no_source ? -1 : std::int64_t(l); }

// Writes the distance of every vertex straight into a numpy array.
struct Distance_writer
{
  typedef Vertex key_type;
  typedef double value_type;
  typedef double& reference;
  typedef boost::writable_property_map_tag category;
  double* distances;
  friend void put(const Distance_writer& m, Vertex v, double d) { m.distances[std::size_t(v)] = d; }
};

py::array_t<double> vertex_distances(const Solver& solver, const Mesh& mesh)
{
  py::array_t<double> d(py::ssize_t(mesh.number_of_vertices()));
  const Distance_writer out{d.mutable_data()};
  py::gil_scoped_release release;
  solver.copy_distances(out);
  return d;
}

void propagate(Solver& solver, double max_distance, const py::object& progress)
{
  try
  {
    run_interruptible([&](const auto& visitor) { solver.propagate(max_distance, visitor); }, progress);
  }
  catch(const IM::Cancelled_error&)
  {
    solver.clear_sources(); // a cancelled propagation leaves partial results
    throw;
  }
  catch(const py::error_already_set&)
  {
    solver.clear_sources();
    throw;
  }
}

py::tuple path_as_locations(const Solver& solver, const Face_location& start)
{
  std::vector<Face_location> path;
  {
    py::gil_scoped_release release;
    solver.trace_path(start, std::back_inserter(path));
  }
  py::array_t<std::int64_t> faces(py::ssize_t(path.size()));
  py::array_t<double> barycentric({py::ssize_t(path.size()), py::ssize_t(3)});
  for(std::size_t i = 0; i < path.size(); ++i)
  {
    faces.mutable_at(i) = std::int64_t(std::size_t(path[i].first));
    const std::array<double, 3> b = to_python_barycentric(path[i].second);
    for(int c = 0; c < 3; ++c)
      barycentric.mutable_at(i, c) = b[c];
  }
  return py::make_tuple(faces, barycentric);
}

py::array_t<double> points_array(const std::vector<Kernel::Point_3>& points)
{
  py::array_t<double> xyz({py::ssize_t(points.size()), py::ssize_t(3)});
  for(std::size_t i = 0; i < points.size(); ++i)
    for(int c = 0; c < 3; ++c)
      xyz.mutable_at(i, c) = points[i][c];
  return xyz;
}

py::array_t<double> path_as_points(const Solver& solver, const Face_location& start)
{
  std::vector<Kernel::Point_3> path;
  {
    py::gil_scoped_release release;
    solver.trace_path_points(start, std::back_inserter(path));
  }
  return points_array(path);
}

Face_location one_location(const Mesh& mesh, const py::object& face, const py::object& barycentric)
{
  bool single = false;
  const std::vector<Face_location> p = locations(mesh, face, barycentric, single);
  if(!single)
    throw py::type_error("face must be a single face index");
  return p[0];
}

// The solver with its mesh, whose sizes check the indices given from Python.
struct Bound_solver
{
  const Mesh* mesh;
  Solver solver;
};

} // namespace

void bind_geodesics(py::module_& m)
{
  const double infinity = std::numeric_limits<double>::infinity();
  typedef Bound_solver S;

  py::class_<S>(m, "Geodesic_solver",
                "Exact geodesic distances on a triangle mesh in the isophotic metric, by exact window\n"
                "propagation on the lifted mesh. Add sources (vertices, surface points, face regions),\n"
                "propagate() (optionally up to a bound), then query distances at vertices or surface\n"
                "points, the nearest source, and shortest paths back to it. Sources are labelled\n"
                "0, 1, ... in the order they are added. The solver keeps its mesh alive.\n"
                "Surface points are a face index and barycentric coordinates w.r.t. the face's vertices\n"
                "in the order of mesh.faces; methods taking one (face, barycentric) pair also take arrays\n"
                "faces (k,) and barycentric (k, 3) and then return arrays.")
    .def(py::init([](py::object mesh, py::object w, py::object wp, py::object L, py::object normals,
                     bool store_windows, int full_window_every) {
           return S{&mesh_of(mesh), make_solver(mesh, Metric_arguments{w, wp, L, normals}, store_windows, full_window_every)};
         }),
         py::arg("mesh"), py::kw_only(), ISOPHOTIC_METRIC_PY_METRIC_ARGS, py::arg("store_windows") = true,
         py::arg("full_window_every") = int(IM::internal::Window_propagation::default_full_record_every),
         py::keep_alive<1, 2>(),
         "Geodesic_solver(mesh, *, euclidean_weight=1, isophotic_weight=1, weight_length_scale=None,\n"
         "                normals=None, store_windows=True, full_window_every=16)\n\n"
         "Validates the mesh, computes the lift and the edge lengths.\n" ISOPHOTIC_METRIC_PY_METRIC_DOC
         "store_windows: keep the propagation's windows for point queries and paths (about 5 bytes\n"
         "    per window); False keeps vertex distances and labels only, with memory following the front.\n"
         "full_window_every: with stored windows, one window in k of each line of descent is kept in\n"
         "    full, the others as a link rebuilt when a query needs it; 1 keeps all in full (fastest\n"
         "    point queries, about 5x the memory). Same answers, bit for bit, for every k in [1, 255].")
    .def("clear_sources", [](S& s) { s.solver.clear_sources(); },
         "Removes every source and result; the mesh and metric are kept.")
    .def("add_source",
         [](S& s, py::object vertex) {
           const auto v = as_indices(vertex, "vertex", "vertex", s.mesh->number_of_vertices());
           if(v.size() != 1)
             throw py::type_error("add_source takes one vertex; use add_sources for several");
           return s.solver.add_source(Vertex(Mesh::size_type(v[0])));
         },
         py::arg("vertex"), "add_source(vertex) -> int: adds a vertex source and returns its label.")
    .def("add_sources",
         [](S& s, py::object vertices) {
           const auto v = as_indices(vertices, "vertices", "vertex", s.mesh->number_of_vertices());
           py::array_t<std::int64_t> labels(py::ssize_t(v.size()));
           for(std::size_t i = 0; i < v.size(); ++i)
             labels.mutable_at(i) = std::int64_t(s.solver.add_source(Vertex(Mesh::size_type(v[i]))));
           return labels;
         },
         py::arg("vertices"), "add_sources(vertices) -> (k,) int64: adds one source per vertex; their labels.")
    .def("add_source_point",
         [](S& s, py::object face, py::object barycentric) -> py::object {
           bool single = false;
           const std::vector<Face_location> p = locations(*s.mesh, face, barycentric, single);
           py::array_t<std::int64_t> labels(py::ssize_t(p.size()));
           for(std::size_t i = 0; i < p.size(); ++i)
             labels.mutable_at(i) = std::int64_t(s.solver.add_source(p[i]));
           if(single)
             return py::int_(labels.at(0));
           return std::move(labels);
         },
         py::arg("face"), py::arg("barycentric"),
         "add_source_point(face, barycentric) -> int (or (k,) int64 for arrays): adds surface-point sources.")
    .def("add_source_region",
         [](S& s, py::object faces) {
           const auto f = as_indices(faces, "faces", "face", s.mesh->number_of_faces(), true);
           std::vector<Face> region;
           for(std::uint32_t i : f)
             region.push_back(Face(Mesh::size_type(i)));
           return s.solver.add_source_region(region);
         },
         py::arg("faces"),
         "add_source_region(faces) -> int: adds the union of the closed faces (indices or a boolean\n"
         "mask over the faces) as one source: distance 0 on it.")
    .def_property_readonly("number_of_sources", [](const S& s) { return s.solver.number_of_sources(); },
                           "Number of sources added since the last clear_sources().")
    .def("propagate",
         [](S& s, double max_distance, py::object progress) { propagate(s.solver, max_distance, progress); },
         py::arg("max_distance") = infinity, py::arg("progress") = py::none(),
         "propagate(max_distance=inf, progress=None)\n\n"
         "Computes the exact distances from the sources up to max_distance (beyond it: +inf). A\n"
         "second call with a larger bound continues where the first stopped. Runs without the GIL;\n"
         "Ctrl-C (KeyboardInterrupt) stops it. progress(front_distance) is called now and then and\n"
         "cancels the propagation by returning False (CancelledError). After a cancellation the\n"
         "sources are cleared.")
    .def("distances", [](const S& s) { return vertex_distances(s.solver, *s.mesh); },
         "distances() -> (n,) float64: the distance of every vertex (+inf where unreachable or\n"
         "beyond the bound), written straight into the returned array.")
    .def("distance_at",
         [](const S& s, py::object face, py::object barycentric) {
           return per_location<double>(*s.mesh, face, barycentric,
                                       [&](const Face_location& p) { return s.solver.distance(p); });
         },
         py::arg("face"), py::arg("barycentric"),
         "distance_at(face, barycentric) -> float or (k,) float64: exact distance at surface points\n"
         "(needs store_windows=True).")
    .def("nearest_sources",
         [](const S& s) {
           py::array_t<std::int64_t> labels(py::ssize_t(s.mesh->number_of_vertices()));
           std::int64_t* out = labels.mutable_data();
           py::gil_scoped_release release;
           for(Vertex v : s.mesh->vertices())
             *out++ = label(s.solver.nearest_source(v));
           return labels;
         },
         "nearest_sources() -> (n,) int64: label of the nearest source of every vertex, -1 where none\n"
         "is reached (a geodesic Voronoi partition for several sources).")
    .def("nearest_source_at",
         [](const S& s, py::object face, py::object barycentric) {
           return per_location<std::int64_t>(*s.mesh, face, barycentric,
                                             [&](const Face_location& p) { return label(s.solver.nearest_source(p)); });
         },
         py::arg("face"), py::arg("barycentric"),
         "nearest_source_at(face, barycentric) -> int or (k,) int64: label of the nearest source at\n"
         "surface points, -1 where none (needs store_windows=True).")
    .def("location",
         [](const S& s, py::object vertex) {
           const auto v = as_indices(vertex, "vertex", "vertex", s.mesh->number_of_vertices());
           const Face_location p = s.solver.location(Vertex(Mesh::size_type(v.at(0))));
           const std::array<double, 3> python = to_python_barycentric(p.second);
           py::array_t<double> b(3);
           for(int c = 0; c < 3; ++c)
             b.mutable_at(c) = python[c];
           return py::make_tuple(std::int64_t(std::size_t(p.first)), b);
         },
         py::arg("vertex"),
         "location(vertex) -> (face, barycentric): the vertex as a surface point, to query or trace from.")
    .def("trace_path",
         [](const S& s, py::object face, py::object barycentric) {
           return path_as_locations(s.solver, one_location(*s.mesh, face, barycentric));
         },
         py::arg("face"), py::arg("barycentric"),
         "trace_path(face, barycentric) -> (faces (k,) int64, barycentric (k, 3) float64)\n\n"
         "The shortest path from the point to its nearest source, the point first and the source last;\n"
         "consecutive points lie in a common face. Empty when the point is unreachable. Needs\n"
         "store_windows=True.")
    .def("trace_path_points",
         [](const S& s, py::object face, py::object barycentric) {
           return path_as_points(s.solver, one_location(*s.mesh, face, barycentric));
         },
         py::arg("face"), py::arg("barycentric"),
         "trace_path_points(face, barycentric) -> (k, 3) float64: the path of trace_path() as a 3D polyline.")
    .def("minimum_distance_on_segment",
         [](const S& s, py::object face, py::object a, py::object b) {
           const Face_location pa = one_location(*s.mesh, face, a), pb = one_location(*s.mesh, face, b);
           double t = 0;
           const double d = s.solver.minimum_distance_on_segment(pa, pb, &t);
           return py::make_tuple(d, t);
         },
         py::arg("face"), py::arg("barycentric_a"), py::arg("barycentric_b"),
         "minimum_distance_on_segment(face, barycentric_a, barycentric_b) -> (distance, t)\n\n"
         "Exact minimum of the distance over the segment between two points of one face, and where\n"
         "it is reached (fraction t of the way from a to b).")
    .def_property_readonly("number_of_windows_created", [](const S& s) { return s.solver.number_of_windows_created(); },
                           "Windows created by the last propagation (statistics).")
    .def_property_readonly("number_of_windows_propagated",
                           [](const S& s) { return s.solver.number_of_windows_propagated(); },
                           "Windows propagated by the last propagation (statistics).");

  m.def("compute_geodesic_distances",
        [](py::object mesh, py::object sources, double max_distance, py::object w, py::object wp, py::object L,
           py::object normals) {
          const auto v = as_indices(sources, "sources", "vertex", mesh_of(mesh).number_of_vertices());
          // As the C++ function: a solver without windows, one source per vertex, one propagation.
          Solver solver = make_solver(mesh, Metric_arguments{w, wp, L, normals}, false);
          for(std::uint32_t i : v)
            solver.add_source(Vertex(Mesh::size_type(i)));
          propagate(solver, max_distance, py::none());
          return vertex_distances(solver, mesh_of(mesh));
        },
        py::arg("mesh"), py::arg("sources"), py::kw_only(), py::arg("max_distance") = infinity,
        ISOPHOTIC_METRIC_PY_METRIC_ARGS,
        "compute_geodesic_distances(mesh, sources, *, max_distance=inf, **metric) -> (n,) float64\n\n"
        "Exact geodesic distance from the nearest source vertex to every vertex (+inf where\n"
        "unreachable or beyond max_distance). Interruptible with Ctrl-C.\n" ISOPHOTIC_METRIC_PY_METRIC_DOC);

  m.def("compute_geodesic_path",
        [](py::object mesh, py::object source, py::object target, py::object w, py::object wp, py::object L,
           py::object normals) {
          const auto from = as_indices(source, "source", "vertex", mesh_of(mesh).number_of_vertices());
          const auto to = as_indices(target, "target", "vertex", mesh_of(mesh).number_of_vertices());
          // As the C++ function: propagate from the source, trace back from the target, reverse.
          Solver solver = make_solver(mesh, Metric_arguments{w, wp, L, normals}, true);
          solver.add_source(Vertex(Mesh::size_type(from.at(0))));
          const Face_location end = solver.location(Vertex(Mesh::size_type(to.at(0))));
          propagate(solver, std::numeric_limits<double>::infinity(), py::none());
          const double length = solver.distance(Vertex(Mesh::size_type(to.at(0))));
          std::vector<Kernel::Point_3> path;
          if(length != std::numeric_limits<double>::infinity())
            solver.trace_path_points(end, std::back_inserter(path));
          std::reverse(path.begin(), path.end());
          return py::make_tuple(length, points_array(path));
        },
        py::arg("mesh"), py::arg("source"), py::arg("target"), py::kw_only(), ISOPHOTIC_METRIC_PY_METRIC_ARGS,
        "compute_geodesic_path(mesh, source, target, **metric) -> (length, (k, 3) float64)\n\n"
        "The exact shortest path between two vertices as 3D points (source first) and its isophotic\n"
        "length; (inf, empty) when the target is unreachable.\n" ISOPHOTIC_METRIC_PY_METRIC_DOC);
}

} // namespace isophotic_metric_python
