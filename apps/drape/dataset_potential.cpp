// `drape dataset potential`: every effect's energy, L_p and p of the garments a
// dataset stores (simulated, predicted or optimised), under the effects of the
// scene given, so that drapes made by different means are compared under one
// potential: the simulation's drapes, and the optimised ones, under the stiff
// contact scene the optimisation used, say (Table 6.4 of the seed).
#include "dataset_potential.hpp"

#include "command.hpp"

#include <drape/io/shipped_files.hpp>
#include <drape/io/dataset.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/penetration.hpp>
#include <drape/registry.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace drape::cli {

const char* kPotentialUsage = "drape dataset potential FILE --scene S [--split test]";

namespace {
std::string brief(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}
}  // namespace

int dataset_potential(const std::vector<std::string>& args) {
  po::options_description opts("drape dataset potential");
  opts.add_options()("file", po::value<std::string>()->required(), "dataset file")(
      "scene", po::value<std::string>()->required(), "scene whose effects (and materials) define the potential")(
      "split", po::value<std::string>()->default_value("test"), "train, val, test, or a comma list");
  po::positional_options_description positional;
  positional.add("file", 1);
  po::variables_map vm;
  if (!parse(kPotentialUsage, args, opts, positional, vm)) return 0;
  const std::filesystem::path path = vm["file"].as<std::string>();
  // A file or a glob pattern of files; DatasetReader says "no such file" or "no dataset file matches".
  Registry& registry = Registry::load_default(plugin_path(vm));
  // A scene of `size: auto` (a sized dataset's own) measures each drape in
  // the size its body wore (its garment_size statistic): it was refused
  // ("give a size"), and one size named measured every other size's drape
  // against the wrong pattern, 400 times the stretching (an outside check).
  const Scene scene = load_scene(find_input_file(vm["scene"].as<std::string>()));
  const SceneSimulations simulations(registry, scene);
  const Simulation& sim = simulations.design();
  const DatasetReader reader(path);
  const std::vector<std::size_t> samples = reader.indices(vm["split"].as<std::string>());
  if (samples.empty()) throw ConfigError(SourceLocation{path.string(), 0}, "has no finished sample in that split");
  // Each sample's size flag, read once for the split (not a file read per sample).
  const bool sized = reader.layout().has_stat("garment_size");
  const std::vector<double> flags = sized ? reader.stat("garment_size", samples) : std::vector<double>();
  const auto wears = [&](std::size_t k) -> const Simulation& {
    if (!sized) return sim;
    const std::size_t index = samples[k];
    const double flag = flags[k];
    if (simulations.auto_size()) {
      for (const std::string& size : simulations.chart()->sizes())
        if (static_cast<double>(garment_size_flag(size)) == flag) return simulations.chart()->simulation(size);
      throw ConfigError(path.string() + ": sample " + std::to_string(index) + " wore garment_size " + brief(flag) +
                        ", none of the scene's sizes");
    }
    if (static_cast<float>(flag) != garment_size_flag(scene))
      throw ConfigError(path.string() + ": sample " + std::to_string(index) + " wore another garment size (flag " +
                        brief(flag) + ") than the scene dresses (flag " + brief(garment_size_flag(scene)) + "): its energies would be those of another pattern; give a scene of `size: auto` (the "
                        "dataset's own) to measure each drape in its size");
    return sim;
  };
  const int garment = sim.garment().mesh.num_vertices(), body = sim.body_model().num_vertices();
  if (static_cast<int>(reader.layout().garment_vertices) != garment || static_cast<int>(reader.layout().body_vertices) != body)
    throw ConfigError(SourceLocation{path.string(), 0},
                      "holds garments of " + std::to_string(reader.layout().garment_vertices) + " and bodies of " +
                          std::to_string(reader.layout().body_vertices) + " vertices, but the scene's garment has " +
                          std::to_string(garment) + " and its body " + std::to_string(body));

  std::vector<std::string> names;  // the scene's effects, in its order (the same for every sample)
  std::vector<double> sums;        // each effect's energy, summed over the samples
  double total = 0, p_sum = 0, p_max = 0;
  std::size_t clear = 0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const std::size_t index = samples[k];
    const DatasetSample s = reader.sample(index);
    const Eigen::MatrixX3d b = s.body_vertices.cast<double>(), x = s.garment_vertices.cast<double>();
    // A file edited by hand or written by a killed job may hold one: said
    // here with the sample, before an energy refuses it without one.
    if (!x.allFinite() || !b.allFinite())
      throw ConfigError(path.string() + ": sample " + std::to_string(index) + " has a non-finite " +
                        (x.allFinite() ? "body" : "garment") + " coordinate; its energies are not defined");
    const geometry::BodySurface surface(b, sim.body_model().faces());
    const std::vector<NamedEnergy> energies = wears(k).make_energies(&surface);
    if (names.empty()) {
      for (const NamedEnergy& e : energies) names.push_back(e.name);
      sums.assign(energies.size(), 0.0);
    }
    for (std::size_t k = 0; k < energies.size(); ++k) {
      const double value = energies[k].energy->value(x);
      sums[k] += value;
      total += value;
    }
    const double p = geometry::penetration_ratio(surface, x);
    p_sum += p;
    p_max = std::max(p_max, p);
    clear += p == 0;
  }
  const double n = static_cast<double>(samples.size());
  std::printf("%s, split %s: %zu drapes under the effects of %s\n\n| effect | mean energy (J) |\n|---|---|\n",
              path.string().c_str(), vm["split"].as<std::string>().c_str(), samples.size(),
              vm["scene"].as<std::string>().c_str());
  for (std::size_t k = 0; k < names.size(); ++k) std::printf("| %s | %.6g |\n", names[k].c_str(), sums[k] / n);
  std::printf("| L_p (total) | %.6g |\n\npenetration p: mean %.3f %%, max %.3f %%; %zu of %zu drapes with no vertex inside\n",
              total / n, 100 * p_sum / n, 100 * p_max, clear, samples.size());
  return 0;
}

}  // namespace drape::cli
