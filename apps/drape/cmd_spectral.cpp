// `drape spectral`: the spectral basis of a garment and how well its first k
// vectors reconstruct shapes (the seed's Fig. 6.4), with the eigensolve time.
#include "command.hpp"

#include <drape/errors.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/spectral/spectral.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

// "16,64,all": 'all' stands for every vertex.
std::vector<int> parse_k_list(const std::string& text, int n) {
  std::vector<int> ks;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item == "all") {
      ks.push_back(n);
      continue;
    }
    try {
      std::size_t used = 0;
      const int k = std::stoi(item, &used);
      if (used != item.size() || k < 1) throw std::invalid_argument(item);
      ks.push_back(k);
    } catch (const std::exception&) {
      throw UsageError("--k: '" + item + "' is not a positive integer (expected a list like 16,64,256)");
    }
  }
  if (ks.empty()) throw UsageError("--k: empty list");
  return ks;
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape spectral");
  opts.add_options()("mesh", po::value<std::string>()->required(), "the garment (any mesh format drape reads)")(
      "k", po::value<std::string>()->default_value("16,64,256,1000"), "numbers of eigenvectors, comma separated ('all' = every vertex)")(
      "drape", po::value<std::vector<std::string>>()->composing(),
      "shapes of the same garment (same vertex order) to reconstruct; default: the garment itself")(
      "operator", po::value<std::string>()->default_value("cotangent"), "cotangent or combinatorial")(
      "solver", po::value<std::string>()->default_value("automatic"), "automatic, shift-invert or dense")(
      "unit", po::value<double>()->default_value(1.0), "metres per mesh unit (0.1 for MakeHuman's decimetres)");
  po::variables_map vm;
  if (!parse("drape spectral --mesh garment.obj [--k 16,64,256,1000] [--drape shape.obj ...]", args, opts, {}, vm)) return 0;

  const Mesh mesh = read_mesh(vm["mesh"].as<std::string>());
  const int n = mesh.num_vertices();
  const std::string k_text = vm["k"].as<std::string>();
  std::vector<int> ks = parse_k_list(k_text, n);
  for (int& k : ks) k = std::min(k, n);

  EigenbasisOptions options;
  const std::string op = vm["operator"].as<std::string>();
  if (op == "cotangent") options.op = SpectralOperator::cotangent;
  else if (op == "combinatorial") options.op = SpectralOperator::combinatorial;
  else throw UsageError("--operator: '" + op + "' is not one of cotangent, combinatorial");
  const std::string solver = vm["solver"].as<std::string>();
  if (solver == "automatic") options.solver = EigenSolver::automatic;
  else if (solver == "shift-invert") options.solver = EigenSolver::shift_invert;
  else if (solver == "dense") options.solver = EigenSolver::dense;
  else throw UsageError("--solver: '" + solver + "' is not one of automatic, shift-invert, dense");
  const double unit = vm["unit"].as<double>();
  if (!(unit > 0)) throw UsageError("--unit must be positive");

  const int k_max = *std::max_element(ks.begin(), ks.end());
  const Eigenbasis basis = compute_eigenbasis(mesh, k_max, options);
  std::printf("mesh %s: %d vertices, %d faces\n", vm["mesh"].as<std::string>().c_str(), n, mesh.num_faces());
  std::printf("eigenbasis: %s operator, k = %d, %s solver, %.3f s; eigenvalues %.3g .. %.3g\n", op.c_str(), k_max,
              to_string(basis.solver).c_str(), basis.seconds, basis.values[0], basis.values[k_max - 1]);

  std::vector<std::string> shapes = {vm["mesh"].as<std::string>()};
  if (vm.count("drape")) shapes = vm["drape"].as<std::vector<std::string>>();
  for (const std::string& file : shapes) {
    const Mesh shape = file == vm["mesh"].as<std::string>() ? mesh : read_mesh(file);
    require_vertex_count(shape, n, file, "it must be a shape of the garment --mesh");
    const std::vector<ReconstructionError> errors = reconstruction_error(basis.vectors, shape.vertices, ks);
    std::printf("\n%s\n%8s %12s %12s\n", file.c_str(), "k", "mean (mm)", "max (mm)");
    for (const auto& e : errors) std::printf("%8d %12.3f %12.3f\n", e.k, 1e3 * unit * e.mean, 1e3 * unit * e.max);
  }
  return 0;
}

const RegisterCommand registration{
    {"spectral", "eigenbasis of a garment's Laplacian and its reconstruction error for several k", run}};

}  // namespace
}  // namespace drape::cli
