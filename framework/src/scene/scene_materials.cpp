#include "scene_materials.hpp"

#include <drape/energy.hpp>
#include <drape/materials/materials.hpp>

#include <algorithm>

namespace drape::scene_detail {

void apply_scene_materials(Garment& garment, const Scene& scene) {
  const MaterialTable table = MaterialTable::builtin();
  std::vector<std::string> regions;
  for (const Material& m : garment.materials) regions.push_back(m.name);
  for (const SceneMaterial& sm : scene.materials) {
    const auto it = std::find(regions.begin(), regions.end(), sm.region);
    if (it == regions.end()) {
      std::string list;
      for (const auto& r : regions) list += (list.empty() ? "" : ", ") + r;
      throw ConfigError(sm.where, "materials: the garment '" + scene.garment + "' has no region '" + sm.region + "'" +
                                      did_you_mean(sm.region, regions) + " (its regions: " + list + ")");
    }
    // The region keeps its name; the physics comes from the preset.
    Material m = table.resolve(sm.spec, sm.file);
    m.name = sm.region;
    garment.materials[static_cast<std::size_t>(it - regions.begin())] = m;
  }
  // One material for every face: no per-face map.
  if (garment.face_material.size() > 0) {
    const int first = garment.face_material[0];
    if ((garment.face_material.array() == first).all()) {
      garment.materials = {garment.materials[static_cast<std::size_t>(first)]};
      garment.face_material.resize(0);
    }
  }
}

}  // namespace drape::scene_detail
