// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// isophotic: the Isophotic_metric package from the command line, for users who do not write C++.
// Reads a triangle mesh (OFF, OBJ, PLY, STL), runs one computation in the isophotic metric
// ds² = w ds² + w' ds*² (distance field, shortest path, morphology of a face selection,
// segmentation, geodesic neighbourhood) and writes the result as PLY (colours and scalar
// properties), CSV, or a PNG picture that looks at the result. `isophotic --help` lists the
// commands, `isophotic <command> --help` their options. `--repair` prepares a mesh straight from a
// scanner with repair_scanned_mesh() first and says what it changed; `--normal-smoothing-scale auto`
// computes normals robust to its noise (estimate_vertex_normals()).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/selection.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>

#include <CGAL/Isophotic_metric/compute_lifted_embedding.h>
#include <CGAL/Isophotic_metric/repair_scanned_mesh.h>
#include <CGAL/Isophotic_metric/suggested_normal_smoothing_scale.h>
#include <CGAL/Isophotic_metric/suggested_weight_length_scale.h>
#include <CGAL/Isophotic_metric/Geodesics/Geodesic_solver.h>
#include <CGAL/Isophotic_metric/Morphology/face_selection_morphology.h>
#include <CGAL/Isophotic_metric/Morphology/geodesic_neighborhoods.h>
#include <CGAL/Isophotic_metric/Morphology/radius_for_area_share.h>
#include <CGAL/Isophotic_metric/Segmentation/region_growing.h>

#include "view_camera.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <queue>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef K::Vector_3 Vector;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef Mesh::Vertex_index vertex_descriptor;
typedef Mesh::Face_index face_descriptor;
typedef CGAL::IO::Color Colour;
namespace IM = CGAL::Isophotic_metric;
namespace PMP = CGAL::Polygon_mesh_processing;
typedef IM::Geodesic_solver<Mesh> Solver;
typedef Solver::Face_location Face_location;

const double infinity = std::numeric_limits<double>::infinity();

// A mistake on the command line (exit code 2, with a hint to --help); errors of the input mesh or of
// the package's checks exit with 1.
struct Usage_error : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

// ---- Command line ---------------------------------------------------------------------------------

struct Option_spec
{
  std::string name, argument, help; // argument empty: a flag
};

struct Command
{
  std::string name, summary, details;
  std::vector<Option_spec> options;
};

const std::vector<Option_spec> metric_options = {
  {"w", "W", "weight of the squared surface arc length (default 0.5)"},
  {"w-prime", "W'", "weight of the squared arc length of the normals' image (default 0.5; 0: Euclidean)"},
  {"length-scale", "L", "length making the weights unit-free (default: the bounding-box diagonal; 1: the paper's raw weights)"},
  {"repair", "", "repair the defects of a scan first (repair_scanned_mesh()) and say what changed"},
  {"normal-smoothing-scale", "S | auto",
   "normals robust to the noise of a scan, filtered at the scale S (a length; 0: the exact normals, the default); "
   "auto: suggested_normal_smoothing_scale(), 0 when no noise is found"},
  {"output", "FILE", "result file: .ply (colours and values), .csv or .png (a picture of the result); repeat for several"},
  {"quiet", "", "no progress bar and no summary"},
  {"help", "", "this help"}};

const std::vector<Option_spec> source_options = {
  {"vertex", "I[,J...]", "source vertices, by index"},
  {"point", "X,Y,Z", "a source at the surface point nearest to X,Y,Z; repeat for several"}};

const std::vector<Option_spec> selection_options = {
  {"faces", "I[,J...]", "the selection, as face indices"},
  {"seed", "X,Y,Z", "the selection: the face nearest to X,Y,Z and its rings"},
  {"rings", "K", "rings of faces around the seed face (default 1)"},
  {"radius", "R", "metric radius"},
  {"area-share", "S", "the radius that dilates the selection to the share S of the area (0 < S <= 1)"},
  {"face-count", "N", "the radius that dilates the selection to N faces"},
  {"area-fraction", "A", "a face joins when the share A of its area is within the radius (default 0.5; 0: when it meets the disc)"}};

std::vector<Option_spec> concat(std::vector<Option_spec> a, const std::vector<Option_spec>& b)
{
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

std::vector<Command> commands()
{
  const auto selection = concat(selection_options, metric_options);
  return {
    {"distance", "exact distance from vertices or surface points to every vertex",
     "Writes the distance per vertex (PLY property `distance`, CSV vertex,x,y,z,distance; inf where\n"
     "unreachable) and colours from near (yellow) to far (dark blue).",
     concat(concat(source_options, {{"max-distance", "D", "stop at distance D (vertices beyond read inf)"}}), metric_options)},
    {"path", "shortest path between two vertices or surface points",
     "Prints the length; writes the path's points (CSV point,x,y,z) or the mesh with the path as a tube (PLY, PNG).",
     concat({{"from", "I | X,Y,Z", "start: a vertex index or the surface point nearest to X,Y,Z"},
             {"to", "I | X,Y,Z", "end: a vertex index or the surface point nearest to X,Y,Z"}},
            metric_options)},
    {"dilate", "dilation of a face selection by a metric radius",
     "Writes per face whether it is selected (PLY property `selected`, CSV face,selected,initial):\n"
     "dark red = initial selection kept, orange = added, light blue = removed.", selection},
    {"erode", "erosion of a face selection (the dual of the dilation)", "Outputs as for dilate.", selection},
    {"open", "opening of a face selection (erosion, then dilation)", "Outputs as for dilate.", selection},
    {"close", "closing of a face selection (dilation, then erosion)", "Outputs as for dilate.", selection},
    {"segment", "segmentation by region growing that stops at features",
     "Writes the patch of every face (PLY property `patch`, CSV face,patch) with one colour per patch.",
     concat({{"radius", "R", "radius of the growing regions (default 0.1 x the bounding-box diagonal)"}}, metric_options)},
    {"neighborhood", "geodesic neighbourhood (disc) of a vertex, a face or a surface point",
     "Writes the faces within the radius (PLY property `min_distance`, inf outside; CSV\n"
     "face,min_distance,covered_fraction), coloured by distance.",
     concat({{"vertex", "I", "centre: a vertex"},
             {"face", "I", "centre: a closed face"},
             {"point", "X,Y,Z", "centre: the surface point nearest to X,Y,Z"},
             {"radius", "R", "metric radius"},
             {"area-fraction", "A", "a face belongs when the share A of its area is within the radius (default 0)"}},
            metric_options)}};
}

void print_overview(std::ostream& out)
{
  out << "usage: isophotic <command> <mesh.off|.obj|.ply|.stl> [options]\n\n"
         "Feature-sensitive distances, paths and morphology on a triangle mesh in the isophotic metric\n"
         "ds^2 = w ds^2 + w' ds*^2 (Pottmann et al., ECCV 2004): paths along features stay short,\n"
         "paths across them become long.\n\ncommands:\n";
  for(const Command& c : commands())
    out << "  " << std::left << std::setw(14) << c.name << c.summary << "\n";
  out << "\n`isophotic <command> --help` lists the options of a command.\n"
         "example: isophotic dilate fandisk.off --seed 0.1,0.2,0.3 --area-share 0.05 -o dilated.png\n";
}

void print_help(const Command& c, std::ostream& out)
{
  out << "usage: isophotic " << c.name << " <mesh> [options]\n\n" << c.summary << ".\n" << c.details << "\n\noptions:\n";
  for(const Option_spec& o : c.options)
  {
    const std::string left = "--" + o.name + (o.argument.empty() ? "" : " " + o.argument);
    if(left.size() >= 24) // (a long option: its help on the next line)
      out << "  " << left << "\n  " << std::string(24, ' ') << o.help << "\n";
    else
      out << "  " << std::left << std::setw(24) << left << o.help << "\n";
  }
}

// The parsed command line: option values by name (repeatable options keep every value) and the mesh.
struct Arguments
{
  std::string mesh_file;
  std::map<std::string, std::vector<std::string>> values;

  bool has(const std::string& name) const { return values.count(name) > 0; }
  const std::string& value(const std::string& name) const { return values.at(name).back(); }

  double number(const std::string& name, double fallback) const
  {
    if(!has(name))
      return fallback;
    return parse_number(name, value(name));
  }

  static double parse_number(const std::string& name, const std::string& text)
  {
    std::size_t used = 0;
    double x = 0;
    try
    {
      x = std::stod(text, &used);
    }
    catch(const std::exception&)
    {
      used = 0;
    }
    if(used == 0 || used != text.size())
      throw Usage_error("--" + name + ": '" + text + "' is not a number");
    return x;
  }

  static std::vector<double> parse_numbers(const std::string& name, const std::string& text)
  {
    std::vector<double> xs;
    std::stringstream in(text);
    std::string piece;
    while(std::getline(in, piece, ','))
      xs.push_back(parse_number(name, piece));
    return xs;
  }

  static std::size_t parse_index(const std::string& name, const std::string& text)
  {
    const double x = parse_number(name, text);
    if(!(x >= 0) || x != std::floor(x) || x > 4e9)
      throw Usage_error("--" + name + ": '" + text + "' is not an index (a whole number >= 0)");
    return static_cast<std::size_t>(x);
  }

  std::vector<std::size_t> indices(const std::string& name) const
  {
    std::vector<std::size_t> ids;
    for(const std::string& v : values.at(name))
    {
      std::stringstream in(v);
      std::string piece;
      while(std::getline(in, piece, ','))
        ids.push_back(parse_index(name, piece));
    }
    return ids;
  }

  static Point parse_point(const std::string& name, const std::string& text)
  {
    const std::vector<double> xs = parse_numbers(name, text);
    if(xs.size() != 3)
      throw Usage_error("--" + name + ": '" + text + "' is not a point X,Y,Z");
    return Point(xs[0], xs[1], xs[2]);
  }
};

Arguments parse(const Command& command, int argc, char* argv[])
{
  Arguments a;
  for(int i = 2; i < argc; ++i)
  {
    std::string word = argv[i];
    if(word == "-o")
      word = "--output";
    if(word.rfind("--", 0) != 0)
    {
      if(!a.mesh_file.empty())
        throw Usage_error("two meshes given ('" + a.mesh_file + "' and '" + word + "'); options start with --");
      a.mesh_file = word;
      continue;
    }
    std::string name = word.substr(2), value;
    const std::size_t equals = name.find('=');
    if(equals != std::string::npos)
    {
      value = name.substr(equals + 1);
      name = name.substr(0, equals);
    }
    const auto spec = std::find_if(command.options.begin(), command.options.end(),
                                   [&](const Option_spec& o) { return o.name == name; });
    if(spec == command.options.end())
      throw Usage_error("'" + command.name + "' has no option --" + name);
    if(!spec->argument.empty() && equals == std::string::npos)
    {
      if(i + 1 >= argc)
        throw Usage_error("--" + name + " needs a value (" + spec->argument + ")");
      value = argv[++i];
    }
    a.values[name].push_back(value);
  }
  return a;
}

// ---- Progress bar ---------------------------------------------------------------------------------

// A bar on standard error, fed by the propagation visitor with the distance the front has reached.
// The full distance is not known in advance: it is estimated by the edge-graph distance (shortest
// paths along lifted edges), an upper bound of the exact distance, so the bar may end short of full.
class Progress_bar
{
public:
  Progress_bar(bool shown, const std::string& label) : shown_(shown), label_(label) {}

  void set_total(double total) { total_ = total; }

  bool operator()(double front)
  {
    if(!shown_ || !(total_ > 0))
      return true;
    const auto now = std::chrono::steady_clock::now();
    if(now - last_ < std::chrono::milliseconds(100))
      return true;
    last_ = now;
    draw(std::min(1., front / total_));
    return true;
  }

  void finish()
  {
    if(shown_ && total_ > 0)
    {
      draw(1.);
      std::cerr << std::endl;
    }
  }

private:
  void draw(double done) const
  {
    const int width = 40, filled = static_cast<int>(std::lround(done * width));
    std::cerr << "\r" << label_ << " [" << std::string(filled, '#') << std::string(width - filled, ' ') << "] "
              << std::setw(3) << static_cast<int>(std::lround(100 * done)) << " %" << std::flush;
  }

  bool shown_;
  std::string label_;
  double total_ = 0;
  std::chrono::steady_clock::time_point last_{};
};

// ---- The job --------------------------------------------------------------------------------------

// What a command produced, ready to be written: values and colours on vertices or faces, a path,
// and where a picture should look (a point of the result and the surface normal there).
struct Result
{
  enum class On { vertices, faces } on = On::faces;
  std::string property;              // PLY property name of the values
  bool integer_values = false;       // values written as int (labels, flags)
  std::vector<double> values;        // per vertex or per face
  std::vector<Colour> colours;       // per vertex or per face
  std::vector<std::string> csv_header;
  std::vector<std::vector<double>> csv_rows;
  std::vector<Point> path;
  std::vector<face_descriptor> focus_faces; // the part of the result a picture looks at
  bool whole_model = false;                 // the picture shows the whole model (from the focus' side)
};

class Job
{
public:
  Job(const Arguments& arguments) : args_(arguments)
  {
    quiet_ = args_.has("quiet");
    read_mesh();
    diagonal_ = IM::suggested_weight_length_scale(mesh_);
    w_ = args_.number("w", 0.5);
    w_prime_ = args_.number("w-prime", 0.5);
    length_scale_ = args_.number("length-scale", diagonal_);
    read_normal_smoothing_scale();
  }

  // The weights, with the exact normals.
  auto unsmoothed_metric() const
  {
    return IM::parameters::euclidean_weight(w_).isophotic_weight(w_prime_).weight_length_scale(length_scale_);
  }

  // The metric of every command. (A smoothing scale of 0 is the exact normals, as when none is given.)
  auto metric() const { return unsmoothed_metric().normal_smoothing_scale(normal_smoothing_scale_); }

  const Mesh& mesh() const { return mesh_; }
  double diagonal() const { return diagonal_; }
  bool quiet() const { return quiet_; }
  const Arguments& args() const { return args_; }

  vertex_descriptor vertex(std::size_t i, const std::string& option) const
  {
    if(i >= num_vertices(mesh_))
      throw Usage_error("--" + option + ": vertex " + std::to_string(i) + " does not exist (the mesh has " +
                        std::to_string(num_vertices(mesh_)) + " vertices, 0 to " + std::to_string(num_vertices(mesh_) - 1) + ")");
    return vertex_descriptor(static_cast<Mesh::size_type>(i));
  }

  face_descriptor face(std::size_t i, const std::string& option) const
  {
    if(i >= num_faces(mesh_))
      throw Usage_error("--" + option + ": face " + std::to_string(i) + " does not exist (the mesh has " +
                        std::to_string(num_faces(mesh_)) + " faces, 0 to " + std::to_string(num_faces(mesh_) - 1) + ")");
    return face_descriptor(static_cast<Mesh::size_type>(i));
  }

  // The surface point nearest to p.
  Face_location locate(const Point& p) const
  {
    if(!tree_)
    {
      tree_ = std::make_unique<Tree>();
      PMP::build_AABB_tree(mesh_, *tree_);
    }
    return PMP::locate_with_AABB_tree(p, *tree_, mesh_);
  }

  // A vertex index, or the surface point nearest to X,Y,Z.
  Face_location location(const std::string& option, const Solver& solver) const
  {
    const std::string& text = args_.value(option);
    if(text.find(',') == std::string::npos)
      return solver.location(vertex(Arguments::parse_index(option, text), option));
    return locate(Arguments::parse_point(option, text));
  }

  // The edge-graph distance from the sources (shortest paths along lifted edges): an upper bound
  // of the exact distance, whose largest finite value sizes the progress bar.
  double edge_graph_extent(const std::vector<vertex_descriptor>& sources) const
  {
    // (with the exact normals: the bar's size does not need the smoothed ones, which cost a filter)
    auto lifted = get(CGAL::dynamic_vertex_property_t<IM::Lifted_point>(), mesh_);
    IM::compute_lifted_embedding(mesh_, lifted, unsmoothed_metric());
    std::vector<double> d(num_vertices(mesh_), infinity);
    typedef std::pair<double, vertex_descriptor> Entry;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    for(vertex_descriptor s : sources)
      queue.emplace(d[s] = 0., s);
    double extent = 0;
    while(!queue.empty())
    {
      const auto [du, u] = queue.top();
      queue.pop();
      if(du > d[u])
        continue;
      extent = du;
      for(vertex_descriptor v : vertices_around_target(halfedge(u, mesh_), mesh_))
      {
        if(v == u)
          continue;
        const IM::Lifted_point &a = get(lifted, u), &b = get(lifted, v);
        double l = 0;
        for(int k = 0; k < 6; ++k)
          l += (a[k] - b[k]) * (a[k] - b[k]);
        if(du + std::sqrt(l) < d[v])
          queue.emplace(d[v] = du + std::sqrt(l), v);
      }
    }
    return extent;
  }

  std::vector<vertex_descriptor> corners(face_descriptor f) const
  {
    std::vector<vertex_descriptor> c;
    for(vertex_descriptor v : vertices_around_face(halfedge(f, mesh_), mesh_))
      c.push_back(v);
    return c;
  }

  void say(const std::string& text) const
  {
    if(!quiet_)
      std::cout << text << std::endl;
  }

private:
  typedef CGAL::AABB_face_graph_triangle_primitive<Mesh> Primitive;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> Tree;

  // --normal-smoothing-scale S | auto; says what auto chose and why.
  void read_normal_smoothing_scale()
  {
    if(!args_.has("normal-smoothing-scale"))
      return;
    if(args_.value("normal-smoothing-scale") != "auto")
    {
      normal_smoothing_scale_ = args_.number("normal-smoothing-scale", 0);
      return;
    }
    const IM::Mesh_noise_estimate noise = IM::estimate_mesh_noise(mesh_);
    normal_smoothing_scale_ = IM::suggested_normal_smoothing_scale(mesh_);
    std::ostringstream text;
    text << "normals: estimated noise " << std::setprecision(2) << noise.noise / noise.mean_edge_length
         << " mean edge lengths; "
         << (normal_smoothing_scale_ > 0 ? "smoothed at the scale " : "below 0.05, the exact normals (scale ")
         << std::setprecision(6) << normal_smoothing_scale_ << (normal_smoothing_scale_ > 0 ? "" : ")");
    say(text.str());
  }

  void read_mesh()
  {
    const std::string& file = args_.mesh_file;
    if(file.empty())
      throw Usage_error("no mesh given");
    if(!std::ifstream(file))
      throw std::runtime_error("cannot open '" + file + "'");
    if(!CGAL::IO::read_polygon_mesh(file, mesh_) || is_empty(mesh_))
      throw std::runtime_error("cannot read a polygon mesh from '" + file +
                               "' (OFF, OBJ, PLY or STL, with faces; a non-manifold or badly oriented soup is refused)");
    if(args_.has("repair"))
    {
      std::ostringstream report;
      report << IM::repair_scanned_mesh(mesh_);
      say("repair: " + report.str());
    }
    // polygons are split into triangles, so that any polygon mesh can be used
    else if(!CGAL::is_triangle_mesh(mesh_))
      PMP::triangulate_faces(mesh_);
  }

  const Arguments& args_;
  Mesh mesh_;
  double diagonal_ = 0, w_ = 0.5, w_prime_ = 0.5, length_scale_ = 1, normal_smoothing_scale_ = 0;
  bool quiet_ = false;
  mutable std::unique_ptr<Tree> tree_;
};

// ---- Colours --------------------------------------------------------------------------------------

const Colour grey(205, 207, 212), kept_colour(165, 15, 25), added_colour(245, 150, 35), removed_colour(130, 185, 235),
  path_colour(200, 20, 30);

// Near (light yellow) to far (dark blue), t in [0,1]; grey where unreachable.
Colour distance_colour(double t)
{
  if(!std::isfinite(t))
    return grey;
  t = std::clamp(t, 0., 1.);
  const double r = 250 - 230 * t, g = 235 - 170 * std::pow(t, 0.7), b = 120 + 40 * std::sin(3.14159 * t) - 10 * t;
  return Colour(static_cast<unsigned char>(r), static_cast<unsigned char>(g), static_cast<unsigned char>(b));
}

// Distinct colours for neighbouring patch numbers (hues spread by the golden ratio).
Colour patch_colour(std::size_t patch)
{
  const double hue = std::fmod(patch * 0.381966, 1.);
  auto channel = [&](double offset) {
    const double x = std::abs(std::fmod(hue * 6 + offset, 6.) - 3) - 1;
    return static_cast<unsigned char>(60 + 170 * std::clamp(x, 0., 1.));
  };
  return Colour(channel(0), channel(4), channel(2));
}

// ---- Commands -------------------------------------------------------------------------------------

Result distance_command(const Job& job)
{
  const Mesh& m = job.mesh();
  const Arguments& args = job.args();
  if(!args.has("vertex") && !args.has("point"))
    throw Usage_error("give the sources with --vertex or --point");
  Solver solver(m, job.metric().store_windows(false));
  std::vector<vertex_descriptor> graph_sources;
  std::vector<face_descriptor> source_faces;
  if(args.has("vertex"))
    for(std::size_t i : args.indices("vertex"))
    {
      graph_sources.push_back(job.vertex(i, "vertex"));
      solver.add_source(graph_sources.back());
      if(halfedge(graph_sources.back(), m) != Mesh::null_halfedge())
        source_faces.push_back(face(halfedge(graph_sources.back(), m), m));
    }
  if(args.has("point"))
    for(const std::string& text : args.values.at("point"))
    {
      const Face_location p = job.locate(Arguments::parse_point("point", text));
      solver.add_source(p);
      source_faces.push_back(p.first);
      for(vertex_descriptor v : job.corners(p.first))
        graph_sources.push_back(v);
    }
  Progress_bar bar(!job.quiet() && isatty(2), "distance");
  if(!job.quiet() && isatty(2))
    bar.set_total(job.edge_graph_extent(graph_sources));
  solver.propagate(args.number("max-distance", infinity), std::ref(bar));
  bar.finish();

  Result r;
  r.on = Result::On::vertices;
  r.property = "distance";
  r.csv_header = {"vertex", "x", "y", "z", "distance"};
  double farthest = 0;
  for(vertex_descriptor v : vertices(m))
  {
    const double d = solver.distance(v);
    r.values.push_back(d);
    if(std::isfinite(d))
      farthest = std::max(farthest, d);
    const Point& p = m.point(v);
    r.csv_rows.push_back({double(std::size_t(v)), p.x(), p.y(), p.z(), d});
  }
  for(double d : r.values)
    r.colours.push_back(distance_colour(farthest > 0 ? d / farthest : 0.));
  r.focus_faces = source_faces;
  r.whole_model = true; // the whole field, seen from the side of the sources
  job.say("largest finite distance " + std::to_string(farthest));
  return r;
}

Result path_command(const Job& job)
{
  const Mesh& m = job.mesh();
  const Arguments& args = job.args();
  if(!args.has("from") || !args.has("to"))
    throw Usage_error("give both ends with --from and --to");
  Solver solver(m, job.metric());
  const Face_location from = job.location("from", solver), to = job.location("to", solver);
  solver.add_source(from);
  const bool shown = !job.quiet() && isatty(2);
  Progress_bar bar(shown, "path");
  if(shown)
    bar.set_total(job.edge_graph_extent(job.corners(from.first)));
  solver.propagate(infinity, std::ref(bar));
  bar.finish();
  const double length = solver.distance(to);
  if(!std::isfinite(length))
    throw std::runtime_error("--to is not reachable from --from (they lie on different connected components)");
  Result r;
  std::vector<Face_location> path;
  solver.trace_path(to, std::back_inserter(path));
  std::reverse(path.begin(), path.end()); // traced from the end back to the source
  for(const Face_location& p : path)
  {
    r.path.push_back(PMP::construct_point(p, m));
    r.focus_faces.push_back(p.first);
  }
  r.csv_header = {"point", "x", "y", "z"};
  for(std::size_t i = 0; i < r.path.size(); ++i)
    r.csv_rows.push_back({double(i), r.path[i].x(), r.path[i].y(), r.path[i].z()});
  r.colours.assign(num_faces(m), grey);
  job.say("path length " + std::to_string(length) + ", " + std::to_string(r.path.size()) + " points");
  return r;
}

// The selection of a morphology command: --faces, or --seed with its rings.
std::vector<face_descriptor> read_selection(const Job& job)
{
  const Arguments& args = job.args();
  std::vector<face_descriptor> selection;
  if(args.has("faces") == args.has("seed"))
    throw Usage_error("give the selection with either --faces or --seed");
  if(args.has("faces"))
  {
    for(std::size_t i : args.indices("faces"))
      selection.push_back(job.face(i, "faces"));
    return selection;
  }
  const face_descriptor seed = job.locate(Arguments::parse_point("seed", args.value("seed"))).first;
  const double rings = args.number("rings", 1);
  if(!(rings >= 0) || rings != std::floor(rings))
    throw Usage_error("--rings: '" + args.value("rings") + "' is not a whole number >= 0");
  Mesh& m = const_cast<Mesh&>(job.mesh()); // a scratch property, removed below
  auto is_selected = get(CGAL::dynamic_face_property_t<bool>(), m);
  for(face_descriptor f : faces(m))
    put(is_selected, f, f == seed);
  selection.push_back(seed);
  CGAL::expand_face_selection(std::vector<face_descriptor>{seed}, m, static_cast<unsigned>(rings), is_selected,
                              std::back_inserter(selection));
  return selection;
}

Result morphology_command(const Job& job, const std::string& operation)
{
  const Mesh& m = job.mesh();
  const Arguments& args = job.args();
  const std::vector<face_descriptor> selection = read_selection(job);
  const auto rule = job.metric().area_fraction(args.number("area-fraction", 0.5));
  IM::Face_band_solver<Mesh> band(m, rule);
  const auto with_band = rule.face_band_solver(&band);
  const int radius_options = args.has("radius") + args.has("area-share") + args.has("face-count");
  if(radius_options != 1)
    throw Usage_error("give the radius with one of --radius, --area-share, --face-count");
  double radius = 0;
  if(args.has("radius"))
    radius = args.number("radius", 0);
  else if(args.has("area-share"))
    radius = IM::radius_for_area_share(selection, m, args.number("area-share", 0), with_band);
  else
    radius = IM::radius_for_face_count(selection, m, Arguments::parse_index("face-count", args.value("face-count")), with_band);

  Mesh& scratch = const_cast<Mesh&>(m); // a selection map, removed when the function returns
  auto is_selected = get(CGAL::dynamic_face_property_t<bool>(), scratch);
  std::vector<char> initial(num_faces(m), 0);
  for(face_descriptor f : faces(m))
    put(is_selected, f, false);
  for(face_descriptor f : selection)
  {
    put(is_selected, f, true);
    initial[f] = 1;
  }
  auto discard = CGAL::Emptyset_iterator();
  if(operation == "dilate")
    IM::dilate_face_selection(selection, m, radius, is_selected, discard, with_band);
  else if(operation == "erode")
    IM::erode_face_selection(selection, m, radius, is_selected, discard, with_band);
  else if(operation == "open")
    IM::open_face_selection(m, radius, is_selected, with_band);
  else
    IM::close_face_selection(m, radius, is_selected, with_band);

  Result r;
  r.property = "selected";
  r.integer_values = true;
  r.csv_header = {"face", "selected", "initial"};
  std::size_t selected = 0;
  for(face_descriptor f : faces(m))
  {
    const bool now = get(is_selected, f), before = initial[f] != 0;
    selected += now;
    r.values.push_back(now);
    r.colours.push_back(now ? (before ? kept_colour : added_colour) : (before ? removed_colour : grey));
    r.csv_rows.push_back({double(std::size_t(f)), double(now), double(before)});
    if(now)
      r.focus_faces.push_back(f);
  }
  if(r.focus_faces.empty())
    r.focus_faces = selection;
  job.say(operation + " by radius " + std::to_string(radius) + ": " + std::to_string(selection.size()) + " -> " +
          std::to_string(selected) + " faces of " + std::to_string(num_faces(m)));
  return r;
}

Result segment_command(const Job& job)
{
  const Mesh& m = job.mesh();
  const double radius = job.args().number("radius", 0.1 * job.diagonal());
  Mesh& scratch = const_cast<Mesh&>(m); // the patch map, removed when the function returns
  auto patch = get(CGAL::dynamic_face_property_t<std::size_t>(), scratch);
  const std::size_t patches = IM::segment_by_region_growing(m, radius, patch, job.metric().area_fraction(0));
  Result r;
  r.property = "patch";
  r.integer_values = true;
  r.csv_header = {"face", "patch"};
  for(face_descriptor f : faces(m))
  {
    r.values.push_back(double(get(patch, f)));
    r.colours.push_back(patch_colour(get(patch, f)));
    r.csv_rows.push_back({double(std::size_t(f)), double(get(patch, f))});
  }
  r.whole_model = true;
  job.say(std::to_string(patches) + " patches (region radius " + std::to_string(radius) + ")");
  return r;
}

Result neighborhood_command(const Job& job)
{
  const Mesh& m = job.mesh();
  const Arguments& args = job.args();
  if(args.has("vertex") + args.has("face") + args.has("point") != 1)
    throw Usage_error("give the centre with one of --vertex, --face, --point");
  if(!args.has("radius"))
    throw Usage_error("give the radius with --radius");
  const double radius = args.number("radius", 0);
  const auto np = job.metric().area_fraction(args.number("area-fraction", 0));
  std::vector<IM::Neighborhood_face<face_descriptor>> found;
  auto out = std::back_inserter(found);
  face_descriptor centre_face;
  if(args.has("vertex"))
  {
    const vertex_descriptor v = job.vertex(Arguments::parse_index("vertex", args.value("vertex")), "vertex");
    IM::geodesic_neighborhood(v, m, radius, out, np);
    if(halfedge(v, m) != Mesh::null_halfedge())
      centre_face = face(halfedge(v, m), m);
  }
  else if(args.has("face"))
  {
    centre_face = job.face(Arguments::parse_index("face", args.value("face")), "face");
    IM::geodesic_neighborhood(centre_face, m, radius, out, np);
  }
  else
  {
    const Face_location p = job.locate(Arguments::parse_point("point", args.value("point")));
    IM::geodesic_neighborhood(p, m, radius, out, np);
    centre_face = p.first;
  }
  Result r;
  r.property = "min_distance";
  r.values.assign(num_faces(m), infinity);
  r.colours.assign(num_faces(m), grey);
  r.csv_header = {"face", "min_distance", "covered_fraction"};
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.face < b.face; });
  for(const auto& n : found)
  {
    r.values[n.face] = n.min_distance;
    r.colours[n.face] = distance_colour(radius > 0 ? n.min_distance / radius : 0.);
    r.csv_rows.push_back({double(std::size_t(n.face)), n.min_distance, n.covered_fraction});
    r.focus_faces.push_back(n.face);
  }
  if(r.focus_faces.empty() && centre_face != Mesh::null_face())
    r.focus_faces.push_back(centre_face);
  job.say(std::to_string(found.size()) + " faces within radius " + std::to_string(radius));
  return r;
}

// ---- Output ---------------------------------------------------------------------------------------

std::string extension(const std::string& file)
{
  const std::size_t dot = file.find_last_of('.');
  std::string e = dot == std::string::npos ? "" : file.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

void write_csv(const Result& r, const std::string& file)
{
  std::ofstream out(file);
  if(!out)
    throw std::runtime_error("cannot write '" + file + "'");
  out << std::setprecision(17);
  for(std::size_t i = 0; i < r.csv_header.size(); ++i)
    out << (i ? "," : "") << r.csv_header[i];
  out << "\n";
  for(const auto& row : r.csv_rows)
  {
    for(std::size_t i = 0; i < row.size(); ++i)
      out << (i ? "," : "") << row[i];
    out << "\n";
  }
}

// Adds a tube of radius `radius` around the polyline to `m`, with faces coloured `colour`.
void add_tube(Mesh& m, Mesh::Property_map<face_descriptor, Colour> colour, const std::vector<Point>& line,
              double radius, const Colour& c)
{
  const int sides = 8;
  for(std::size_t k = 0; k + 1 < line.size(); ++k)
  {
    const Vector axis = line[k + 1] - line[k];
    const double length = std::sqrt(axis.squared_length());
    if(length < 1e-12 * radius)
      continue;
    const Vector t = axis / length;
    Vector u = CGAL::cross_product(t, std::abs(t.z()) < 0.9 ? Vector(0, 0, 1) : Vector(1, 0, 0));
    u = u / std::sqrt(u.squared_length());
    const Vector v = CGAL::cross_product(t, u);
    std::vector<vertex_descriptor> ring[2];
    for(int end = 0; end < 2; ++end)
      for(int s = 0; s < sides; ++s)
      {
        const double a = 2 * 3.14159265358979 * s / sides;
        // a little longer than the segment, so that consecutive pieces overlap at the joints
        const Point centre = end ? line[k + 1] + 0.5 * radius * t : line[k] - 0.5 * radius * t;
        ring[end].push_back(m.add_vertex(centre + radius * (std::cos(a) * u + std::sin(a) * v)));
      }
    for(int s = 0; s < sides; ++s)
    {
      const int n = (s + 1) % sides;
      for(face_descriptor f : {m.add_face(ring[0][s], ring[0][n], ring[1][n]), m.add_face(ring[0][s], ring[1][n], ring[1][s])})
        if(f != Mesh::null_face())
          colour[f] = c;
    }
  }
}

// The mesh with the result's colours and values as PLY properties (and the path as a tube).
Mesh coloured_copy(const Job& job, const Result& r)
{
  Mesh out;
  CGAL::copy_face_graph(job.mesh(), out);
  if(r.on == Result::On::vertices)
  {
    auto colour = out.add_property_map<vertex_descriptor, Colour>("v:color").first;
    auto value = out.add_property_map<vertex_descriptor, double>("v:" + r.property).first;
    for(vertex_descriptor v : vertices(out))
    {
      colour[v] = r.colours[v];
      value[v] = r.values[v];
    }
    return out;
  }
  auto colour = out.add_property_map<face_descriptor, Colour>("f:color").first;
  for(face_descriptor f : faces(out))
    colour[f] = r.colours[f];
  if(!r.property.empty())
  {
    if(r.integer_values)
    {
      auto value = out.add_property_map<face_descriptor, std::int32_t>("f:" + r.property).first;
      for(face_descriptor f : faces(out))
        value[f] = static_cast<std::int32_t>(r.values[f]);
    }
    else
    {
      auto value = out.add_property_map<face_descriptor, double>("f:" + r.property).first;
      for(face_descriptor f : faces(out))
        value[f] = r.values[f];
    }
  }
  add_tube(out, colour, r.path, 0.004 * job.diagonal(), path_colour);
  return out;
}

void write_ply(const Mesh& coloured, const std::string& file)
{
  if(!CGAL::IO::write_PLY(file, coloured, CGAL::parameters::use_binary_mode(true)))
    throw std::runtime_error("cannot write '" + file + "'");
}

bool program_exists(const std::string& name)
{
  return std::system(("command -v " + name + " > /dev/null 2>&1").c_str()) == 0;
}

// A picture of the result through f3d (headless with xvfb-run when there is no display).
void write_png(const Job& job, const Result& r, const Mesh& coloured, const std::string& file)
{
  if(!program_exists("f3d"))
    throw std::runtime_error("cannot write '" + file + "': the program f3d is not installed (Debian: apt install f3d xvfb)");
  const std::string ply = file + ".tmp.ply";
  write_ply(coloured, ply);
  std::string command;
  if(!std::getenv("DISPLAY") && program_exists("xvfb-run"))
    command = "xvfb-run -a -s '-screen 0 1280x1024x24' ";
  command += "f3d '" + ply + "' '--output=" + file + "' --resolution=1000,750 --scalars=RGBA --comp=-2 -a -t --bg-color=1,1,1";
  if(r.on == Result::On::faces)
    command += " --cells";
  for(const std::string& a : view_camera::view_of(job.mesh(), r.focus_faces, r.whole_model).f3d_arguments())
    command += " " + a;
  command += " > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  std::remove(ply.c_str());
  if(status != 0 || !std::ifstream(file))
    throw std::runtime_error("f3d could not render '" + file + "' (command: " + command + ")");
}

void write_outputs(const Job& job, const Result& r)
{
  if(!job.args().has("output"))
  {
    job.say("no --output given: nothing written");
    return;
  }
  const Mesh coloured = coloured_copy(job, r);
  for(const std::string& file : job.args().values.at("output"))
  {
    const std::string e = extension(file);
    if(e == "ply")
      write_ply(coloured, file);
    else if(e == "csv")
      write_csv(r, file);
    else if(e == "png")
      write_png(job, r, coloured, file);
    else
      throw Usage_error("--output '" + file + "': the file must end in .ply, .csv or .png");
    job.say("wrote " + file);
  }
}

int run(int argc, char* argv[])
{
  const std::vector<Command> all = commands();
  if(argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")
  {
    print_overview(argc < 2 ? std::cerr : std::cout);
    return argc < 2 ? 2 : 0;
  }
  const auto command = std::find_if(all.begin(), all.end(), [&](const Command& c) { return c.name == argv[1]; });
  if(command == all.end())
    throw Usage_error(std::string("unknown command '") + argv[1] + "'");
  const Arguments args = parse(*command, argc, argv);
  if(args.has("help"))
  {
    print_help(*command, std::cout);
    return 0;
  }
  const Job job(args);
  Result result;
  if(command->name == "distance")
    result = distance_command(job);
  else if(command->name == "path")
    result = path_command(job);
  else if(command->name == "segment")
    result = segment_command(job);
  else if(command->name == "neighborhood")
    result = neighborhood_command(job);
  else
    result = morphology_command(job, command->name);
  write_outputs(job, result);
  return 0;
}

} // namespace

int main(int argc, char* argv[])
{
  try
  {
    return run(argc, argv);
  }
  catch(const Usage_error& e)
  {
    std::cerr << "isophotic: " << e.what() << "\n(see isophotic --help, or isophotic <command> --help)" << std::endl;
    return 2;
  }
  catch(const IM::Error& e) // the package's checks: the message names the offending element
  {
    std::cerr << "isophotic: " << e.what() << std::endl;
    return 1;
  }
  catch(const std::exception& e)
  {
    std::cerr << "isophotic: " << e.what() << std::endl;
    return 1;
  }
}
