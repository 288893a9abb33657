#pragma once
// Precomputed data of one garment template that nodes ask for: the garment
// itself (rest shape, material space, materials). Later layers add the
// hierarchy, correspondences and eigenbasis here (and bump DRAPE_ABI_VERSION).
#include <drape/energy.hpp>

#include <memory>

namespace drape {

class Assets {
 public:
  std::shared_ptr<const Garment> garment;
};

}  // namespace drape
