// `drape assets`: builds (or loads from the cache) everything precomputed for a
// garment template and prints its sizes and what each part cost.
#include "command.hpp"

#include <drape/io/write_failure.hpp>

#include <drape/energy.hpp>
#include <drape/assets/assets.hpp>
#include <drape/garment_dressing.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/geometry/index_locality.hpp>
#include <drape/registry.hpp>

#include <filesystem>
#include <iomanip>
#include <iostream>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape assets");
  opts.add_options()("body", po::value<std::string>()->default_value("parametric"), "body plugin (its mean shape)")(
      "garment", po::value<std::string>()->default_value("tshirt"), "garment template plugin")(
      "size", po::value<std::string>(), "garment size (tshirt: 3xsmall ... small, regular, large ... 6xlarge, auto; `drape plugins --kind garment` lists them)")(
      "resolution", po::value<std::string>(), "garment resolution (tshirt: default | coarse | a vertex count)")(
      "print", "add the front print material region")(
      "garment-param", po::value<std::vector<std::string>>()->composing(),
      "any parameter of the garment plugin, name=value (repeatable), e.g. file=skirt.obj for --garment mesh")(
      "k", po::value<int>()->default_value(1000), "eigenvectors of the spectral basis")(
      "levels", po::value<int>()->default_value(4), "hierarchy levels including the garment")(
      "cache-dir", po::value<std::string>(), "cache folder (default $DRAPE_CACHE_DIR or ~/.cache/drape)")(
      "no-cache", "compute everything, read and write no cache")(
      "write-garment", po::value<std::string>(), "write the template garment (dressed on the mean body) to this mesh file")(
      "dress-on", po::value<std::string>(), "with --write-garment: dress it on this body mesh instead (same model topology)");
  po::variables_map vm;
  if (!parse("drape assets [--garment tshirt] [--size regular] [--resolution default] [--print] [--k 1000]", args, opts,
             {}, vm))
    return 0;
  if (vm["k"].as<int>() < 1) throw UsageError("--k must be at least 1");
  if (vm["levels"].as<int>() < 1) throw UsageError("--levels must be at least 1");
  const Registry& reg = Registry::load_default(plugin_path(vm));
  AssetsSpec spec;
  spec.body_model = vm["body"].as<std::string>();
  spec.garment = vm["garment"].as<std::string>();
  if (vm.count("size")) spec.garment_params["size"] = vm["size"].as<std::string>();
  if (vm.count("resolution")) spec.garment_params["resolution"] = vm["resolution"].as<std::string>();
  if (vm.count("print")) spec.garment_params["print"] = "true";
  if (vm.count("garment-param"))
    for (const auto& item : vm["garment-param"].as<std::vector<std::string>>()) {
      const auto eq = item.find('=');
      if (eq == std::string::npos || eq == 0) throw UsageError("--garment-param wants name=value, got '" + item + "'");
      spec.garment_params[item.substr(0, eq)] = item.substr(eq + 1);
    }
  spec.eigen_k = vm["k"].as<int>();
  spec.levels = vm["levels"].as<int>();
  const std::filesystem::path cache =
      vm.count("no-cache") ? std::filesystem::path() : vm.count("cache-dir") ? std::filesystem::path(vm["cache-dir"].as<std::string>())
                                                                           : default_cache_dir();
  if (!cache.empty()) check_output_folder(cache, vm.count("cache-dir") ? "--cache-dir" : "the cache folder");
  AssetsTimings t;
  const auto a = build_assets(reg, spec, cache, &t);

  const Mesh& g = a->garment->mesh;
  if (vm.count("dress-on") && !vm.count("write-garment")) throw UsageError("--dress-on needs --write-garment");
  if (vm.count("write-garment")) {
    Garment out = *a->garment;
    if (vm.count("dress-on")) {
      const Mesh body = read_mesh(vm["dress-on"].as<std::string>());
      require_vertex_count(body, a->body.num_vertices(), vm["dress-on"].as<std::string>(), "the " + spec.body_model + " body's topology");
      const DressReport r = dress(out, body);
      std::cout << "dressed on " << vm["dress-on"].as<std::string>() << ": " << r.inside_before << " vertices were inside the body\n";
    }
    write_mesh(vm["write-garment"].as<std::string>(), out.mesh);
    std::cout << "wrote " << vm["write-garment"].as<std::string>() << "\n";
  }
  std::cout << std::fixed << std::setprecision(3);
  std::cout << "assets " << a->hash << (t.from_cache ? " (from cache " : " (built") << (t.from_cache ? t.cache_file.string() + ")" : ")")
            << "\n";
  std::cout << "  body     " << spec.body_model << ": " << a->body.num_vertices() << " vertices, " << a->body.num_faces()
            << " faces, consecutive-index neighbours "
            << 100.0 * geometry::index_locality(a->body.faces, a->body.num_vertices()).one_hop << "%\n";
  int print_faces = 0;
  for (int f = 0; f < g.num_faces(); ++f) print_faces += a->garment->material_of(f) != 0;
  std::cout << "  garment  " << spec.garment << ": " << g.num_vertices() << " vertices, " << g.num_faces() << " faces, "
            << g.uv.rows() << " uvs, " << a->garment->materials.size() << " materials, " << print_faces << " print faces\n";
  std::cout << "  hierarchy:";
  for (const auto& level : a->hierarchy.levels) std::cout << " " << level.mesh.num_vertices();
  std::cout << " vertices";
  const auto& levels = a->hierarchy.levels;
  for (std::size_t l = 1; l < levels.size(); ++l)
    if (levels[l].mesh.num_vertices() == levels[l - 1].mesh.num_vertices()) {
      std::cout << " (levels " << l << " on repeat level " << l - 1 << ": the mesh coarsens no further; --levels " << l << ")";
      break;
    }
  std::cout << "\n  spectral: k = " << a->eigenvalues.size() << ", eigenvalues " << a->eigenvalues[0] << " .. "
            << a->eigenvalues[a->eigenvalues.size() - 1] << "\n";
  std::cout << "  time: garment+body " << t.garment << " s, correspondences " << t.correspondence << " s, hierarchy "
            << t.hierarchy << " s, eigenbasis " << t.eigenbasis << " s, cache load " << t.load << " s\n";
  return 0;
}

const RegisterCommand registration{{"assets", "build or load the cached template data (hierarchy, correspondences, eigenbasis)", run}};

}  // namespace
}  // namespace drape::cli
