#pragma once
// A parameter's allowed range as a scene writes numbers: "[1, 4096]",
// "[0.5, inf]" (not std::to_string's "[1.000000, 4096.000000]"); what a
// refused value and `drape plugins` print (defined in params.cpp).
#include <drape/params.hpp>

#include <string>

namespace drape {

std::string range_text(const ParamSpec& spec);

}  // namespace drape
