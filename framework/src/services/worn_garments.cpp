// worn_garments (services/worn_garments.hpp).
#include <drape/services/worn_garments.hpp>

#include <drape/assets/assets.hpp>
#include <drape/errors.hpp>
#include <drape/garment_grading.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/scene/scene.hpp>
#include <drape/training/metrics.hpp>
#include <drape/training/model.hpp>

#include <algorithm>
#include <map>
#include <string>
#include <utility>

namespace drape {

WornGarments worn_garments(const Registry& registry, const DatasetReader& data, const std::vector<std::size_t>& indices) {
  const DatasetLayout& layout = data.layout();
  if (!layout.has_stat("garment_size") || layout.scene.empty()) return {};
  const Scene scene = parse_scene(layout.scene, data.name() + " (scene attribute)");
  const std::vector<double> flags = data.stat("garment_size", indices);
  // (With size: auto the template is the design size's: no sample of the design size is graded.)
  const float design_flag = garment_size_is_auto(scene) ? garment_size_flag(default_garment_size(registry, scene))
                                                        : garment_size_flag(scene);
  bool one_garment = !scene.garment_grade_auto;
  for (double f : flags) one_garment = one_garment && static_cast<float>(f) == design_flag;
  if (one_garment) return {};

  // Only the garments' material spaces are needed: the template builds each
  // size (garment_materials), as the scene's simulations did before dressing
  // them; grade: auto's grades are the template's pattern graded.
  const AssetsSpec spec = assets_spec_for(scene, 0);
  std::vector<std::string> sizes;
  for (const ParamSpec& p : registry.get(scene.garment).params)
    if (p.name == "size") sizes = p.choices;
  const auto size_of = [&](double flag, std::size_t k) {
    for (const std::string& size : sizes)
      if (size != "auto" && static_cast<double>(garment_size_flag(size)) == flag) return size;
    throw ConfigError("sample " + std::to_string(indices[k]) + ": its garment_size " + std::to_string(flag) +
                      " is none of garment '" + scene.garment + "''s sizes");
  };
  const std::vector<double> grades =
      scene.garment_grade_auto ? data.stat("garment_grade", indices) : std::vector<double>(indices.size(), 1.0);

  WornGarments worn;
  worn.of_sample.assign(indices.size(), -1);
  std::map<std::pair<double, double>, int> listed;  // (flag, grade) -> rest_lengths
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const auto key = std::make_pair(flags[k], grades[k]);
    auto it = listed.find(key);
    if (it == listed.end()) {
      int which = -1;
      if (scene.garment_grade_auto ? grades[k] != 1.0 : static_cast<float>(flags[k]) != design_flag) {
        const std::string size = scene.garment_grade_auto ? std::string() : size_of(flags[k], k);
        Mesh material = garment_materials(registry, spec, {{size, grades[k]}}).front().second;
        if (!scene.garment_grade_auto) grade_material(material, scene.garment_grade);  // a scene's `grade: g` on every size
        worn.rest_lengths.push_back(face_edge_rest_lengths(material));
        which = static_cast<int>(worn.rest_lengths.size()) - 1;
      }
      it = listed.emplace(key, which).first;
    }
    worn.of_sample[k] = it->second;
  }
  return worn;
}

}  // namespace drape
