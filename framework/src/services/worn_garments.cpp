// worn_garments (services/worn_garments.hpp).
#include <drape/services/worn_garments.hpp>

#include <drape/errors.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/training/metrics.hpp>
#include <drape/training/model.hpp>

#include <map>
#include <memory>
#include <string>
#include <utility>

namespace drape {

WornGarments worn_garments(const Registry& registry, const DatasetReader& data, const std::vector<std::size_t>& indices) {
  const DatasetLayout& layout = data.layout();
  if (!layout.has_stat("garment_size") || layout.scene.empty()) return {};
  const Scene scene = parse_scene(layout.scene, "the dataset's stored scene");
  const std::vector<double> flags = data.stat("garment_size", indices);
  const bool auto_size = garment_size_is_auto(scene);
  // (With size: auto the template is the design size's: no sample of the design size is graded.)
  const float design_flag = auto_size ? garment_size_flag(default_garment_size(registry, scene)) : garment_size_flag(scene);
  bool one_garment = !scene.garment_grade_auto;
  for (double f : flags) one_garment = one_garment && static_cast<float>(f) == design_flag;
  if (one_garment) return {};

  // size: auto's chart, or (sizes merged into one dataset) the scene's sizes.
  const SceneSimulations simulations(registry, scene);
  std::unique_ptr<SizeChart> merged_sizes;
  const auto sized = [&](double flag, std::size_t k) -> const Simulation& {
    if (!simulations.auto_size() && !merged_sizes) merged_sizes = std::make_unique<SizeChart>(registry, scene);
    const SizeChart& chart = simulations.auto_size() ? *simulations.chart() : *merged_sizes;
    for (const std::string& size : chart.sizes())
      if (static_cast<double>(garment_size_flag(size)) == flag) return chart.simulation(size);
    throw ConfigError("sample " + std::to_string(indices[k]) + ": its garment_size " + std::to_string(flag) +
                      " is none of garment '" + scene.garment + "''s sizes");
  };
  const std::vector<double> grades =
      scene.garment_grade_auto ? data.stat("garment_grade", indices) : std::vector<double>(indices.size(), 0.0);

  WornGarments worn;
  worn.of_sample.assign(indices.size(), -1);
  std::map<std::pair<double, double>, int> listed;  // (flag, grade) -> rest_lengths
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const auto key = std::make_pair(flags[k], grades[k]);
    auto it = listed.find(key);
    if (it == listed.end()) {
      const Simulation& wore = scene.garment_grade_auto                   ? simulations.grades()->simulation(grades[k])
                               : static_cast<float>(flags[k]) == design_flag ? simulations.design()
                                                                            : sized(flags[k], k);
      int which = -1;
      if (&wore != &simulations.design()) {
        worn.rest_lengths.push_back(face_edge_rest_lengths(wore.garment().mesh));
        which = static_cast<int>(worn.rest_lengths.size()) - 1;
      }
      it = listed.emplace(key, which).first;
    }
    worn.of_sample[k] = it->second;
  }
  return worn;
}

}  // namespace drape
