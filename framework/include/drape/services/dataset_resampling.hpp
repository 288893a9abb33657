#pragma once
// `drape dataset resample`: a dataset's bodies carried onto the vertices of
// another body model of the same family (docs/bodies.md, "One encoder for both
// rigs"). Each vertex of the target's template body is attached to its closest
// point on the source's template body (a face and barycentric weights, fixed
// once); every body of the dataset is then read at those points. The garments,
// parameters, split and statistics are kept. A model of the target's topology
// (the shipped mannequin model: every weight, its encoder reading vertices in
// index order included) can then be trained on drapes simulated on the source
// (the human rig), whose own vertex order it has never seen.
#include <drape/registry.hpp>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>

namespace drape {

struct ResampleSummary {
  std::size_t samples = 0;
  int source_vertices = 0, target_vertices = 0;
  // How far the target template's vertices lie from the source template's surface (m).
  double median_distance = 0, p90_distance = 0, max_distance = 0;
};

// Writes `out` (atomically, through DatasetWriter's partial file): `in`'s done
// samples (slim or full) with each body resampled onto the template body of
// the scene file `onto`, stored in full; the scene becomes `onto`'s (its
// template is the one a model of these bodies is built on), the drapes' own
// scene is kept as the root attribute `source_scene`, and `resampled_from`
// says what was done. ConfigError when the two scenes' garments differ in
// vertex count (the drapes would not be the target's garment), for a posed
// dataset (the target body would have to be posed the same way: not done).
ResampleSummary resample_dataset(const Registry& registry, const std::filesystem::path& in,
                                 const std::filesystem::path& onto, const std::filesystem::path& out,
                                 const std::function<void()>& done = {});

}  // namespace drape
