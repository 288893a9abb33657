#pragma once
// The posed drape tests' scene: the coarse posed scenes' effects (friction
// against the body, the cloth kept off itself) and their morph (the cloth
// within 2-6 cm carried with the skin, docs/poses.md) on a body of this
// shape, pose and garment, as YAML text.
#include <string>

namespace drape::test {

inline std::string posed_scene_text(double bmi, double height, double sex, const std::string& pose,
                                    const std::string& garment_params) {
  return "body:\n  model: parametric\n  shape: {bmi: " + std::to_string(bmi) + ", height: " + std::to_string(height) +
         ", sex: " + std::to_string(sex) + "}\n" + (pose.empty() ? "" : "  pose: {" + pose + "}\n") +
         "garment: {template: tshirt, params: {" + garment_params + "}}\n" + R"(effects:
  gravity: {}
  stretching: {compressive_stiffness: 1.0}
  bending: {potential: product}
  barrier: {friction: 0.3}
  self_contact: {}
solver: {morph_steps: 20, settle_steps: 60, morph_carry: [0.02, 0.06]}
)";
}

}  // namespace drape::test
