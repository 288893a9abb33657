#pragma once
// A MakeHuman outfit's T-shirt as a drape garment: the first connected piece of
// the outfit's .obj (MakeHuman outfits put the shirt first), triangulated, with
// its UVs rescaled per chart to meters of material, fitted to a MakeHuman body
// through the outfit's .mhclo binding.
#include "mhclo.hpp"
#include "model.hpp"

#include <drape/energy.hpp>

namespace drape::makehuman {

// The outfit folder holds <name>.obj and <name>.mhclo.
Garment load_tshirt(const Model& model, const std::filesystem::path& outfit_dir, const Sliders& body);

}  // namespace drape::makehuman
