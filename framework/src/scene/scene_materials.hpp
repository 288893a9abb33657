#pragma once
// Materials of a scene's garment regions (internal to the simulation driver).
#include <drape/energy.hpp>
#include <drape/scene/scene.hpp>

namespace drape::scene_detail {

// Replaces the physical numbers of each region the scene names (a preset or
// an inline spec); regions it does not name keep the template's material.
// ConfigError at the scene's line for a region the garment does not have.
// Afterwards, when every face has the same material, the per-face map is
// dropped: a garment without a print carries no material map at all.
void apply_scene_materials(Garment& garment, const Scene& scene);

}  // namespace drape::scene_detail
