#pragma once
// A piece of a MakeHuman outfit as a drape garment: one connected piece of the
// outfit's .obj (MakeHuman outfits put the shirt first, then the trousers),
// triangulated, with its UVs rescaled to meters of material, fitted to a
// MakeHuman body through the outfit's .mhclo binding, so that it follows the
// body's shape.
#include "mhclo.hpp"
#include "model.hpp"

#include <drape/energy.hpp>

#include <string>

namespace drape::makehuman {

// The outfit folder holds <name>.obj and <name>.mhclo. `piece` selects the
// piece: its index among the connected pieces, numbered by their first vertex
// ("0", "1", ...), or the name of an OBJ group (`g`/`o`) whose faces make it.
// The garment keeps the piece's vertices in the .obj's order.
Garment load_clothes(const Model& model, const std::filesystem::path& outfit_dir, const Sliders& body,
                     const std::string& piece);

}  // namespace drape::makehuman
