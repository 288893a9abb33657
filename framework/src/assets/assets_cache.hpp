#pragma once
// The HDF5 file behind the assets cache (layout in docs/formats.md).
#include <drape/assets/assets.hpp>

namespace drape::assets_cache {

void save(const std::filesystem::path& file, const Assets& assets);
// Fills every cached field of `assets` (garment, body and hash are already set).
void load(const std::filesystem::path& file, Assets& assets);

}  // namespace drape::assets_cache
