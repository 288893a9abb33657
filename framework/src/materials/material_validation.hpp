#pragma once
// Checks shared by parsing a preset and resolving one (framework-internal).
#include <drape/errors.hpp>

#include <Eigen/Core>

#include <string>

namespace drape::materials_detail {

// ConfigError at `where` unless the stretch coefficients give a positive
// definite membrane energy: k_uu > 0, k_vv > 0, k_uu k_vv > k_uv^2 (the 2x2
// block on the normal strains) and k_shear > 0. Otherwise some strain would have
// zero or negative energy and the cloth could stretch for free.
void check_stretch(const Eigen::Vector4d& k, const SourceLocation& where, const std::string& owner);

}  // namespace drape::materials_detail
