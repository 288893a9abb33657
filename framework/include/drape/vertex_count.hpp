#pragma once
// The one wrong-size error: "<what> has N vertices, expected M (<why>)",
// written here once for every array or mesh whose vertex count is fixed by a
// body model, a garment template or a model.
#include <Eigen/Core>

#include <string>

namespace drape {

// Throws drape::ConfigError (the caller's input) unless got == expected.
// `why` (optional) says what fixes the count ("the model's body model 'parametric'").
void require_vertex_count(Eigen::Index got, Eigen::Index expected, const std::string& what, const std::string& why = "");

}  // namespace drape
