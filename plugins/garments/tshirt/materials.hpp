#pragma once
// The T-shirt's material presets, in one place until the physics issue moves
// presets to YAML. Index = material id in Garment::face_material.
#include <drape/energy.hpp>

#include <vector>

namespace drape::tshirt {

// ArcSim's gray-interlock knit.
inline Material knit_material() {
  Material m;
  m.name = "knit";
  m.density = 0.187;
  m.stretch = {16.6, -14.7, 34.5, 36.9};
  m.bending = 1e-5;
  return m;
}

// A screen print: the knit plus a layer of plastisol ink, heavier and much stiffer.
inline Material print_material() {
  Material m = knit_material();
  m.name = "print";
  m.density *= 2;
  m.stretch *= 5;
  m.bending *= 10;
  return m;
}

inline constexpr int kKnit = 0;
inline constexpr int kPrint = 1;

}  // namespace drape::tshirt
