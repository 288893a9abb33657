#pragma once
// `drape dataset unpose`: a posed dataset's drapes brought back into each
// body's rest pose (TailorNet's unposing, docs/poses.md): each garment vertex
// through the inverse of its blended joint transform, by the garment's
// skinning weights from the body surface (the skin node's, Assets::
// garment_skinning), each body replaced by its rest mesh. What a network
// predicting in canonical space learns, and how much of a posed drape
// skinning explains: the canonical drapes of one body in many poses lie
// close together where skinning is right (docs/poses.md measures it).
#include <drape/registry.hpp>

#include <cstddef>
#include <filesystem>
#include <functional>

namespace drape {

// Writes `out` (atomically: through DatasetWriter's partial file, finished at
// the end): `in`'s done samples with garments and bodies at rest, the split
// and statistics kept, each joint angle kept as a statistic pose_<name>
// (degrees), no /bodies/pose (the bodies are at rest) and the root attribute
// `unposed` saying so. ConfigError for an A-pose dataset or a body model
// without a skeleton. `done` is called after each sample. Returns the count.
std::size_t unpose_dataset(const Registry& registry, const std::filesystem::path& in, const std::filesystem::path& out,
                           const std::function<void()>& done = {});

}  // namespace drape
