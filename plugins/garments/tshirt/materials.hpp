#pragma once
// The T-shirt's two regions and their cloth. The physical numbers come from
// drape's built-in material presets (graphs/materials/presets.yaml); the region
// names "knit" and "print" stay the T-shirt's own (Material::name is the region
// name here). Index = material id in Garment::face_material.
#include <drape/energy.hpp>
#include <drape/materials/materials.hpp>

#include <string>

namespace drape::tshirt {

inline Material region_material(const std::string& region, const std::string& preset) {
  Material m = MaterialTable::builtin().get(preset);
  m.name = region;
  return m;
}

// The template's own cloth: ArcSim's measured gray-interlock knit (strain- and
// direction-dependent, docs/materials.md) and its print. The constant-stiffness
// knit the project used before is preset gray-interlock-linear (scenes
// tshirt_penalty*.yaml reproduce the old drapes).
inline Material knit_material() { return region_material("knit", "gray-interlock"); }

// A screen print: the knit plus a layer of plastisol ink, heavier and much stiffer.
inline Material print_material() { return region_material("print", "screen-print"); }

inline constexpr int kKnit = 0;
inline constexpr int kPrint = 1;

}  // namespace drape::tshirt
