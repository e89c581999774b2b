// Feature-sensitive morphology on noisy, scan-like meshes. The normals of a scan are noisy at the scale
// of a triangle, and the normal part of the isophotic metric then measures the noise. Robust vertex
// normals (named parameter normal_smoothing_scale of the lift) bring back the behaviour of the clean mesh.
//
// Figure of merit: the central face of the largest planar face of a CAD mesh is dilated, in the
// Euclidean metric and in the isophotic one (w = w' = 0.5, L = bounding-box diagonal), until most of
// that planar face is covered (80 %; mean over its three largest planar faces); "leakage" is the area of the dilation beyond the planar face's border,
// "ratio" the isophotic leakage over the Euclidean one, "radius" the isophotic radius. Noise: Gaussian
// along the normal, standard deviation in mean edge lengths, seeded (the same numbers everywhere).
//
// Default run (a test): fandisk with noise 0.35; prints the figure of merit of the clean mesh and of the
// noisy one with raw and with robust normals (the defaults of estimate_vertex_normals()), and writes the paper's Fig. 6 (w = w' = 0.5) and Fig. 7
// (w = 0.2, w' = 0.8) on the noisy mesh: seed | Euclidean | isophotic, raw normals | isophotic, robust
// normals, dilated to 5 % of the area from the seed of isophotic_demo (scan_fig6.ply, scan_fig7.ply;
// orange: growth on the seed's feature patch, blue: beyond a sharp edge).
//
// Usage: scan_morphology [--table [mesh ...]]   the figure of merit at noise 0, 0.1, 0.2, 0.35 of CGAL's
//        fandisk, anchor_dense, rotor and couplingdown (or of the meshes given: .off, or generated CAD
//        parts .ply whose B-rep faces are the ground truth), with raw normals, robust
//        normals and, for comparison, the normals of CGAL's point-set estimators (jet and PCA fitting over
//        the same neighbourhood) and the clean mesh's own normals on the noisy positions (the limit of any
//        estimator), and the angular error of each to the normals of the clean mesh. Options: --range r
//        and --patch (robust normals with one guidance for all faces, the Gaussian or with --patch the
//        patch guidance, and normal_range r, instead of the guidance chosen per face), --iterations k
//        (number_of_iterations), --vertex-updates k (number_of_vertex_updates; 0: the filter alone), --scale s,
//        --noise x, --inside f, --estimators robust,jet,pca,clean (a subset; also gaussian-R and patch-R: the
//        Gaussian or the patch guidance with normal_range R).
#include "scan_helpers.h"

#include <CGAL/Isophotic_metric/suggested_normal_smoothing_scale.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/selection.h>
#include <CGAL/jet_estimate_normals.h>
#include <CGAL/pca_estimate_normals.h>

#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>

using namespace scan_helpers;

namespace {

typedef decltype(get(CGAL::dynamic_vertex_property_t<Vector>(), std::declval<Mesh&>())) Normal_map;

// Angular error in degrees of `normals` to the normals of the clean mesh: mean over the vertices away
// from sharp edges (more than 3 rings from a vertex of an edge bending by more than 30 degrees), and
// over the vertices near them (1 to 3 rings), where an estimator that rounds the edges errs.
std::array<double, 2> angular_error(const Mesh& clean, const Normal_map& normals)
{
  auto truth = get(CGAL::dynamic_vertex_property_t<Vector>(), clean);
  PMP::compute_vertex_normals(clean, truth);
  std::vector<int> rings(clean.number_of_vertices(), 4);
  std::vector<vertex_descriptor> front;
  for(auto e : edges(clean))
  {
    const auto h = halfedge(e, clean);
    if(is_border_edge(h, clean))
      continue;
    const Vector n1 = PMP::compute_face_normal(face(h, clean), clean), n2 = PMP::compute_face_normal(face(opposite(h, clean), clean), clean);
    if(n1 * n2 < std::cos(30 * CGAL_PI / 180))
      for(vertex_descriptor v : {source(h, clean), target(h, clean)})
        if(rings[v] != 0)
        {
          rings[v] = 0;
          front.push_back(v);
        }
  }
  for(int ring = 1; ring <= 3; ++ring)
  {
    std::vector<vertex_descriptor> next;
    for(vertex_descriptor v : front)
      for(vertex_descriptor w : CGAL::vertices_around_target(halfedge(v, clean), clean))
        if(rings[w] > ring)
        {
          rings[w] = ring;
          next.push_back(w);
        }
    front.swap(next);
  }
  std::array<double, 2> sum{0, 0}, count{0, 0};
  for(vertex_descriptor v : vertices(clean))
  {
    if(rings[v] == 0)
      continue;
    const int near = rings[v] <= 3 ? 1 : 0;
    sum[near] += std::acos(std::clamp(get(truth, v) * get(normals, v), -1., 1.)) * 180 / CGAL_PI;
    count[near] += 1;
  }
  return {count[0] > 0 ? sum[0] / count[0] : 0., count[1] > 0 ? sum[1] / count[1] : 0.};
}

// Normals of CGAL's point-set estimators over the mesh's vertices, with the neighbours within `radius`,
// oriented as the mesh's own normals.
template <bool jet>
Normal_map point_set_normals(const Mesh& m, double radius)
{
  std::vector<std::pair<Point, Vector>> points;
  for(vertex_descriptor v : vertices(m))
    points.emplace_back(m.point(v), Vector(0, 0, 0));
  const auto np = CGAL::parameters::point_map(CGAL::First_of_pair_property_map<std::pair<Point, Vector>>())
                    .normal_map(CGAL::Second_of_pair_property_map<std::pair<Point, Vector>>())
                    .neighbor_radius(radius);
  if constexpr(jet)
    CGAL::jet_estimate_normals<CGAL::Sequential_tag>(points, 0, np);
  else
    CGAL::pca_estimate_normals<CGAL::Sequential_tag>(points, 0, np);
  Normal_map normals = get(CGAL::dynamic_vertex_property_t<Vector>(), const_cast<Mesh&>(m));
  Normal_map mesh_normals = get(CGAL::dynamic_vertex_property_t<Vector>(), const_cast<Mesh&>(m));
  PMP::compute_vertex_normals(m, mesh_normals);
  std::size_t i = 0;
  for(vertex_descriptor v : vertices(m))
  {
    const Vector n = points[i++].second;
    put(normals, v, n * get(mesh_normals, v) < 0 ? -n : n);
  }
  return normals;
}

// The normals of the lift's default (PMP's weights differ), read from the lift's normal part.
Normal_map lift_normals(const Mesh& m)
{
  auto lifted = get(CGAL::dynamic_vertex_property_t<IM::Lifted_point>(), m);
  IM::compute_lifted_embedding(m, lifted, IM::parameters::euclidean_weight(1).isophotic_weight(1).weight_length_scale(1));
  Normal_map normals = get(CGAL::dynamic_vertex_property_t<Vector>(), const_cast<Mesh&>(m));
  for(vertex_descriptor v : vertices(m))
  {
    const IM::Lifted_point x = get(lifted, v);
    put(normals, v, Vector(x[3], x[4], x[5]));
  }
  return normals;
}

Normal_map raw_normals(const Mesh& m)
{
  Normal_map normals = get(CGAL::dynamic_vertex_property_t<Vector>(), const_cast<Mesh&>(m));
  PMP::compute_vertex_normals(m, normals);
  return normals;
}

// The options of the robust normals: the defaults of estimate_vertex_normals() (the guidance chosen
// per face), or one guidance for all faces (`guidance_for_all`: the patch or the Gaussian guidance)
// with the range `range`.
struct Filter
{
  bool guidance_for_all = false;
  bool patch_guidance = false;
  double range = 0.6;
  unsigned iterations = 5;
  int vertex_updates = -1; // number_of_vertex_updates; -1: the default of estimate_vertex_normals()
};

// Calls use(named parameters of the filter, with normal_smoothing_scale(scale)).
template <typename Use>
void with_filter_parameters(const Filter& filter, double scale, const Use& use)
{
  const auto chosen_per_face = IM::parameters::normal_smoothing_scale(scale).number_of_iterations(filter.iterations);
  const auto with_updates = [&](const auto& np) {
    if(filter.vertex_updates >= 0)
      use(np.number_of_vertex_updates(unsigned(filter.vertex_updates)));
    else
      use(np);
  };
  if(filter.guidance_for_all)
    with_updates(chosen_per_face.normal_range(filter.range).use_patch_guidance(filter.patch_guidance));
  else
    with_updates(chosen_per_face);
}

Normal_map robust_normals(const Mesh& m, double scale, const Filter& filter)
{
  Normal_map normals = get(CGAL::dynamic_vertex_property_t<Vector>(), const_cast<Mesh&>(m));
  with_filter_parameters(filter, scale, [&](const auto& np) { IM::estimate_vertex_normals(m, scale, normals, np); });
  return normals;
}

void print_leakage(const Leakage& l, double clean_radius)
{
  std::cout << " | " << std::setprecision(3) << l.beyond << " | " << l.radius << " (" << std::setprecision(2)
            << l.radius / clean_radius << "x)";
}


// The table of the figure of merit for one mesh (see the top of the file).
int figure_of_merit_table(const std::string& filename, const std::vector<double>& levels, double forced_scale,
                          double inside, const Filter& filter, const std::vector<std::string>& estimators)
{
  Part part;
  if(!read_part(filename, part))
  {
    std::cerr << "Cannot read " << filename << std::endl;
    return 1;
  }
  const Mesh& clean = part.mesh;
  const double L = IM::suggested_weight_length_scale(clean), h = mean_edge_length(clean);
  const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);
  double clean_ratio = 0, clean_radius = 0;
  for(double level : levels)
  {
    const Mesh noisy = noisy_copy(clean, level, 1);
    const IM::Mesh_noise_estimate estimate = IM::estimate_mesh_noise(noisy);
    const double suggested = IM::suggested_normal_smoothing_scale(noisy);
    const double scale = forced_scale > 0 ? forced_scale * h : suggested;
    const Figure_of_merit raw = figure_of_merit(noisy, part, metric, inside);
    if(level == 0.)
    {
      clean_ratio = raw.ratio();
      clean_radius = raw.isophotic.radius;
    }
    std::cout << part.name << " | " << num_faces(clean) << " | " << std::setprecision(2) << level << " | "
              << estimate.noise / estimate.mean_edge_length << " | " << suggested / h << " | " << std::setprecision(3)
              << raw.euclidean.beyond << " | raw " << raw.ratio() << " (" << std::setprecision(2)
              << raw.ratio() / clean_ratio << "x)";
    print_leakage(raw.isophotic, clean_radius);
    std::array<double, 2> error = angular_error(clean, raw_normals(noisy));
    std::cout << " | " << std::fixed << std::setprecision(1) << error[0] << " / " << error[1] << std::defaultfloat;
    if(scale > 0)
    {
      for(const std::string& estimator : estimators)
      {
        // "robust": the filter of the options; "gaussian-r" and "patch-r": the Gaussian or the patch
        // guidance with normal_range r; "clean": the clean mesh's normals on the noisy positions, the
        // best any estimator can do
        const bool patch = estimator.rfind("patch-", 0) == 0, gaussian = estimator.rfind("gaussian-", 0) == 0;
        const bool filtered = estimator == "robust" || patch || gaussian;
        const Filter chosen = patch || gaussian
          ? Filter{true, patch, std::stod(estimator.substr(estimator.find('-') + 1)), filter.iterations, filter.vertex_updates}
          : filter;
        const Normal_map normals = filtered           ? robust_normals(noisy, scale, chosen)
                                   : estimator == "jet" ? point_set_normals<true>(noisy, 2 * scale)
                                   : estimator == "pca" ? point_set_normals<false>(noisy, 2 * scale)
                                                        : lift_normals(clean);
        Figure_of_merit f;
        if(filtered)
          with_filter_parameters(chosen, scale, [&](const auto& np) {
            f = figure_of_merit(noisy, part, IM::parameters::combine(metric, np), inside);
          });
        else
          f = figure_of_merit(noisy, part, IM::parameters::combine(metric, IM::parameters::vertex_normal_map(normals)), inside);
        std::cout << " | " << estimator << " " << std::setprecision(3) << f.ratio() << " (" << std::setprecision(2)
                  << f.ratio() / clean_ratio << "x)";
        print_leakage(f.isophotic, clean_radius);
        error = angular_error(clean, normals);
        std::cout << " | " << std::fixed << std::setprecision(1) << error[0] << " / " << error[1] << std::defaultfloat;
      }
    }
    std::cout << std::endl;
  }
  return 0;
}

// Fig. 6 or 7 of the paper on a noisy mesh: seed | Euclidean | isophotic with raw normals | isophotic
// with robust normals, each dilated to `share` of the surface. The seed is the one of isophotic_demo (a
// face on fandisk's curved band and its neighbours); its feature patch is the set of faces of the clean
// mesh connected to it without crossing a sharp edge (dihedral angle above 30 degrees).
bool write_figure(const std::string& filename, const Mesh& clean, const Mesh& noisy, double w, double w_iso, double share)
{
  std::size_t number_of_patches = 0;
  const std::vector<std::size_t> patch = feature_patches(clean, 30, number_of_patches);
  const face_descriptor centre = face_near(clean, {0.5, 0.25, 0.75});
  std::set<face_descriptor> seed{centre};
  for(face_descriptor f : CGAL::faces_around_face(halfedge(centre, noisy), noisy))
    if(f != Mesh::null_face())
      seed.insert(f);
  /// [robust normals]
  const double L = IM::suggested_weight_length_scale(noisy);
  const auto metric = IM::parameters::euclidean_weight(w).isophotic_weight(w_iso).weight_length_scale(L);
  // the scale of the robust normals, from the mesh's edge lengths and its estimated noise; the filter
  // chooses per face how to keep sharp edges and fillets
  const double scale = IM::suggested_normal_smoothing_scale(noisy);
  IM::Face_band_solver<Mesh> robust(noisy, IM::parameters::combine(metric, IM::parameters::normal_smoothing_scale(scale)));
  /// [robust normals]
  IM::Face_band_solver<Mesh> euclidean(noisy, IM::parameters::isophotic_weight(0));
  IM::Face_band_solver<Mesh> raw(noisy, metric);
  const double h = mean_edge_length(noisy);
  std::vector<std::set<face_descriptor>> grown{seed};
  for(IM::Face_band_solver<Mesh>* band : {&euclidean, &raw, &robust})
    grown.push_back(dilate(noisy, seed, radius_for_share(seed, share, *band), *band));
  std::cout << filename << " (w = " << w << ", w' = " << w_iso << ", robust normals at scale " << scale / h
            << " mean edge lengths): share of the grown area beyond a sharp edge, Euclidean / raw / robust:";
  std::vector<std::function<Colour(face_descriptor)>> colours;
  for(const std::set<face_descriptor>& g : grown)
  {
    if(&g != &grown.front())
      std::cout << " " << 100 * share_beyond_features(noisy, seed, g, patch) << " %";
    colours.push_back([&, g](face_descriptor f) {
      if(seed.count(f)) return seed_colour;
      if(!g.count(f)) return background;
      return patch[f] == patch[centre] ? inside_colour : beyond_colour;
    });
  }
  std::cout << std::endl;
  const Vector shift = side_by_side_shift(noisy, Vector(0, 1, 0), 1.1);
  return write_face_coloured_meshes(filename, {&noisy, &noisy, &noisy, &noisy},
                                    {Vector(0, 0, 0), shift, 2 * shift, 3 * shift}, colours);
}

} // namespace

int main(int argc, char* argv[])
{
  try
  {
    if(argc > 1 && std::string(argv[1]) == "--table")
    {
      std::vector<std::string> names;
      std::vector<double> levels{0., 0.1, 0.2, 0.35}; // --noise x: the clean mesh and the noise x only
      Filter filter; // --range r, --patch (one guidance for all faces), --iterations k, --vertex-updates k
      std::vector<std::string> estimators{"robust", "jet", "pca", "clean"}; // --estimators robust,clean: a subset
      double inside = 0.8; // --inside f: dilate until the fraction f of the planar face is covered
      double forced_scale = 0; // --scale s: robust normals at s mean edge lengths instead of the suggested scale
      for(int i = 2; i < argc; ++i)
      {
        if(std::string(argv[i]) == "--scale" && i + 1 < argc)
          forced_scale = std::stod(argv[++i]);
        else if(std::string(argv[i]) == "--inside" && i + 1 < argc)
          inside = std::stod(argv[++i]);
        else if(std::string(argv[i]) == "--noise" && i + 1 < argc)
          levels = {0., std::stod(argv[++i])};
        else if(std::string(argv[i]) == "--estimators" && i + 1 < argc)
        {
          estimators.clear();
          std::istringstream list(argv[++i]);
          for(std::string name; std::getline(list, name, ',');)
            estimators.push_back(name);
        }
        else if(std::string(argv[i]) == "--range" && i + 1 < argc)
        {
          filter.guidance_for_all = true;
          filter.range = std::stod(argv[++i]);
        }
        else if(std::string(argv[i]) == "--patch")
          filter.guidance_for_all = filter.patch_guidance = true;
        else if(std::string(argv[i]) == "--iterations" && i + 1 < argc)
          filter.iterations = unsigned(std::stoi(argv[++i]));
        else if(std::string(argv[i]) == "--vertex-updates" && i + 1 < argc)
          filter.vertex_updates = std::stoi(argv[++i]);
        else
          names.push_back(argv[i]);
      }
      if(names.empty())
        for(const char* name : {"fandisk", "anchor_dense", "rotor", "couplingdown"})
          names.push_back(CGAL::data_file_path(std::string("meshes/") + name + ".off"));
      std::cout << "mesh | faces | noise | estimated noise | suggested scale | Euclidean leakage | raw: ratio | leakage | "
                   "radius | angle error away / near sharp edges | robust: ... | jet: ... | pca: ...\n";
      for(const std::string& name : names)
        if(figure_of_merit_table(name, levels, forced_scale, inside, filter, estimators) != 0)
          return 1;
      return 0;
    }

    Part part;
    const std::string filename = CGAL::data_file_path("meshes/fandisk.off");
    if(!read_part(filename, part))
    {
      std::cerr << "Cannot read " << filename << std::endl;
      return 1;
    }
    const Mesh noisy = noisy_copy(part.mesh, 0.35, 1);
    const double L = IM::suggested_weight_length_scale(part.mesh);
    const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);
    const Figure_of_merit clean_merit = figure_of_merit(part.mesh, part, metric);
    const Figure_of_merit raw = figure_of_merit(noisy, part, metric);
    const Figure_of_merit robust = figure_of_merit(
      noisy, part,
      IM::parameters::combine(metric, IM::parameters::normal_smoothing_scale(IM::suggested_normal_smoothing_scale(noisy))));
    std::cout << "fandisk, noise 0.35 mean edge length; isophotic / Euclidean leakage, isophotic radius:\n"
              << "  clean " << clean_merit.ratio() << ", " << clean_merit.isophotic.radius << "\n"
              << "  noisy, raw normals " << raw.ratio() << ", " << raw.isophotic.radius << "\n"
              << "  noisy, robust normals " << robust.ratio() << ", " << robust.isophotic.radius << std::endl;
    if(!write_figure("scan_fig6.ply", part.mesh, noisy, 0.5, 0.5, 0.05) ||
       !write_figure("scan_fig7.ply", part.mesh, noisy, 0.2, 0.8, 0.05))
    {
      std::cerr << "Cannot write the PLY files" << std::endl;
      return 1;
    }
  }
  catch(const IM::Error& e) // bad input: the message names the element
  {
    std::cerr << e.what() << std::endl;
    return 1;
  }
  return 0;
}
