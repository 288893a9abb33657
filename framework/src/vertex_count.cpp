// require_vertex_count (vertex_count.hpp).
#include <drape/errors.hpp>
#include <drape/vertex_count.hpp>

namespace drape {

void require_vertex_count(Eigen::Index got, Eigen::Index expected, const std::string& what, const std::string& why) {
  if (got == expected) return;
  throw ConfigError(what + " has " + std::to_string(got) + " vertices, expected " + std::to_string(expected) +
                    (why.empty() ? "" : " (" + why + ")"));
}

}  // namespace drape
