// ArcSim's measured tables in a preset or material file: `stretching` (6 rows
// of [k_uu, k_uv, k_vv, k_shear]) and `bending` (3 directions x 5 curvatures).
// Shapes and values are checked here so that every error names the row or the
// sample at fault; what the rows mean: docs/materials.md.
#include "material_validation.hpp"
#include "../yaml_util.hpp"

#include <sstream>

namespace drape::materials_detail {
namespace {

using yaml::at;

std::string kind_of(const YAML::Node& n) {
  if (n.IsSequence()) return "a list of " + std::to_string(n.size());
  if (n.IsMap()) return "a map";
  if (n.IsNull()) return "nothing";
  return "'" + n.Scalar() + "'";
}

// The rows of an R x C table of numbers; `shape` ("6x4 ...") goes into every message.
template <std::size_t R, std::size_t C>
std::array<std::array<double, C>, R> table(const std::string& file, const YAML::Node& n, const std::string& owner,
                                           const std::string& key, const std::string& shape, double limit,
                                           const char* unit) {
  const std::string expected = " (expected " + std::to_string(R) + "x" + std::to_string(C) + ": " + shape + ")";
  if (!n.IsSequence())
    throw ConfigError(at(file, n), owner + ": `" + key + "` must be a list of " + std::to_string(R) + " rows of " +
                                       std::to_string(C) + " numbers" + expected + ", got " + kind_of(n));
  if (n.size() != R)
    throw ConfigError(at(file, n), owner + ": `" + key + "` has " + std::to_string(n.size()) + " rows" + expected);
  std::array<std::array<double, C>, R> out{};
  for (std::size_t r = 0; r < R; ++r) {
    const YAML::Node row = n[r];
    const std::string row_key = key + "[" + std::to_string(r) + "]";
    if (!row.IsSequence())
      throw ConfigError(at(file, row), owner + ": `" + row_key + "` must be a list of " + std::to_string(C) +
                                           " numbers" + expected + ", got " + kind_of(row));
    if (row.size() != C)
      throw ConfigError(at(file, row), owner + ": `" + row_key + "` has " + std::to_string(row.size()) + " numbers" +
                                           expected);
    for (std::size_t c = 0; c < C; ++c) {
      const std::string cell = row_key + "[" + std::to_string(c) + "]";
      out[r][c] = number(file, row[c], owner, cell);
      check_cloth_range(out[r][c], limit, file, row[c], owner, cell, unit);
    }
  }
  return out;
}

}  // namespace

std::array<Eigen::Vector4d, 6> stretching_table(const std::string& file, const YAML::Node& n, const std::string& owner) {
  const auto rows = table<6, 4>(file, n, owner, "stretching",
                                "[k_uu, k_uv, k_vv, k_shear] in N/m at zero strain, then at 5 stretch directions",
                                kMaxStretch, "N/m");
  std::array<Eigen::Vector4d, 6> out;
  for (std::size_t r = 0; r < 6; ++r) out[r] = Eigen::Vector4d(rows[r][0], rows[r][1], rows[r][2], rows[r][3]);
  check_zero_strain_row(out[0], at(file, n[0]), owner);
  return out;
}

std::array<std::array<double, 5>, 3> bending_table(const std::string& file, const YAML::Node& n, const std::string& owner) {
  const auto rows = table<3, 5>(file, n, owner, "bending",
                                "N*m at 3 edge directions (0, 45, 90 degrees) x 5 curvatures (0 to 40 1/m)",
                                kMaxBending, "N*m");
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 5; ++c)
      if (rows[r][c] < 0) {
        const YAML::Node value = n[r][c];
        throw ConfigError(at(file, value), owner + ": `bending[" + std::to_string(r) + "][" + std::to_string(c) +
                                               "]` must be >= 0 N*m, got " + value.Scalar());
      }
  return rows;
}

void check_zero_strain_row(const Eigen::Vector4d& row, const SourceLocation& where, const std::string& owner) {
  if (row[0] > 0 && row[2] > 0) return;
  std::ostringstream s;
  s << owner << ": `stretching[0]` (zero strain) has k_uu = " << row[0] << " and k_vv = " << row[2]
    << " N/m; ArcSim clamps negative values to 0, so the cloth would have no stiffness along "
    << (row[0] <= 0 && row[2] <= 0 ? "u and v" : row[0] <= 0 ? "u" : "v") << " at rest (both must be > 0)";
  throw ConfigError(where, s.str());
}

}  // namespace drape::materials_detail
