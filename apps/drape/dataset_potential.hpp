#pragma once
// `drape dataset potential FILE --scene S [--split test]`: the potential of a
// dataset's stored drapes under any scene's effects (docs/optimization.md).
#include <string>
#include <vector>

namespace drape::cli {

extern const char* kPotentialUsage;
int dataset_potential(const std::vector<std::string>& args);

}  // namespace drape::cli
