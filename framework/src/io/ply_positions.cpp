// read_ply_double_positions (mesh_io_internal.hpp): assimp keeps a mesh's
// positions in float (ai_real), so a PLY written in double lost its last
// digits on the way in (an outside check: a body written in double, read
// rounded by 6e-8 m, moved a simulated drape by up to 7.5 mm). The vertex
// element's x, y and z are read here in double, ASCII or binary.
#include "mesh_io_internal.hpp"
#include "ply_header.hpp"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace drape::mesh_io {

std::optional<Eigen::MatrixX3d> read_ply_double_positions(const std::string& bytes) {
  PlyHeader header;
  // (require_complete_ply refused a file whose vertices are not its first data.)
  if (!parse_ply_header(bytes, header) || header.elements.empty() || header.elements.front().name != "vertex")
    return std::nullopt;
  const PlyElement& element = header.elements.front();
  int column[3] = {-1, -1, -1};  // the properties x, y, z
  for (std::size_t k = 0; k < element.properties.size(); ++k) {
    const PlyProperty& p = element.properties[k];
    for (int c = 0; c < 3; ++c)
      if (p.name == std::string(1, static_cast<char>('x' + c)) && !p.is_list() && (p.type == "double" || p.type == "float64"))
        column[c] = static_cast<int>(k);
  }
  if (column[0] < 0 || column[1] < 0 || column[2] < 0) return std::nullopt;  // float positions: assimp's are exact
  Eigen::MatrixX3d positions(element.count, 3);
  const std::string body = bytes.substr(std::min(header.body_offset, bytes.size()));
  if (header.format == "ascii") {
    // One line a vertex, blank lines skipped (as ply_completeness.cpp counts them).
    std::istringstream lines(body);
    std::string line, word;
    for (long row = 0; row < element.count && std::getline(lines, line);) {
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      std::istringstream words(line);
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        if (!(words >> word)) return std::nullopt;
        if (element.properties[k].is_list()) {
          for (long i = std::strtol(word.c_str(), nullptr, 10); i > 0; --i) words >> word;
          continue;
        }
        for (int c = 0; c < 3; ++c)
          if (column[c] == static_cast<int>(k)) {
            char* end = nullptr;
            positions(row, c) = std::strtod(word.c_str(), &end);
            if (end == word.c_str()) return std::nullopt;  // (assimp says what is wrong with it)
          }
      }
      ++row;
    }
    return positions;
  }
  const bool big_endian = header.format == "binary_big_endian";
  std::size_t at = 0;
  for (long row = 0; row < element.count; ++row)
    for (std::size_t k = 0; k < element.properties.size(); ++k) {
      const PlyProperty& p = element.properties[k];
      const long size = ply_type_size(p.type);
      if (size == 0) return std::nullopt;
      unsigned long long items = 1;
      if (p.is_list()) {
        const long count_size = ply_type_size(p.count_type);
        if (count_size == 0 || at + static_cast<std::size_t>(count_size) > body.size()) return std::nullopt;
        items = ply_unsigned(body, at, count_size, big_endian);
        at += static_cast<std::size_t>(count_size);
      }
      if (at + items * static_cast<std::size_t>(size) > body.size()) return std::nullopt;
      for (int c = 0; c < 3; ++c)
        if (column[c] == static_cast<int>(k)) {
          const std::uint64_t bits = ply_unsigned(body, at, 8, big_endian);
          std::memcpy(&positions(row, c), &bits, sizeof(double));
        }
      at += items * static_cast<std::size_t>(size);
    }
  return positions;
}

}  // namespace drape::mesh_io
