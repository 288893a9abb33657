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

namespace {

bool is_double(const std::string& type) { return type == "double" || type == "float64"; }

// One value of `size` bytes at `at`, in the file's byte order, as its raw bits.
std::uint64_t raw_bits(const std::string& body, std::size_t at, long size, bool big_endian) {
  std::uint64_t bits = 0;
  for (long b = 0; b < size; ++b) {
    const auto byte = static_cast<unsigned char>(body[at + static_cast<std::size_t>(big_endian ? b : size - 1 - b)]);
    bits = (bits << 8) | byte;
  }
  return bits;
}

}  // namespace

std::optional<Eigen::MatrixX3d> read_ply_double_positions(const std::filesystem::path& file) {
  const std::string bytes = read_file_bytes(file);
  PlyHeader header;
  if (!parse_ply_header(bytes, header)) return std::nullopt;
  std::size_t vertex = 0;
  while (vertex < header.elements.size() && header.elements[vertex].name != "vertex") ++vertex;
  if (vertex == header.elements.size()) return std::nullopt;
  const PlyElement& element = header.elements[vertex];
  int column[3] = {-1, -1, -1};  // the properties x, y, z
  for (std::size_t k = 0; k < element.properties.size(); ++k)
    for (int c = 0; c < 3; ++c)
      if (element.properties[k].name == std::string(1, static_cast<char>('x' + c)) && !element.properties[k].is_list() &&
          is_double(element.properties[k].type))
        column[c] = static_cast<int>(k);
  if (column[0] < 0 || column[1] < 0 || column[2] < 0) return std::nullopt;  // float positions: assimp's are exact
  Eigen::MatrixX3d positions(element.count, 3);
  const std::string body = bytes.substr(std::min(header.body_offset, bytes.size()));
  if (header.format == "ascii") {
    // One line an element (ply_completeness.cpp checked the count); blank lines skipped as there.
    std::istringstream lines(body);
    std::string line;
    long skipped = 0, before = 0;
    for (std::size_t e = 0; e < vertex; ++e) before += header.elements[e].count;
    for (long row = 0; row < element.count && std::getline(lines, line);) {
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      if (skipped < before) {
        ++skipped;
        continue;
      }
      std::istringstream words(line);
      std::string word;
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        if (!(words >> word)) return std::nullopt;
        if (element.properties[k].is_list()) {
          const long n = std::strtol(word.c_str(), nullptr, 10);
          for (long i = 0; i < n; ++i) words >> word;
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
  const long start = ply_binary_extent(body, std::vector<PlyElement>(header.elements.begin(), header.elements.begin() + static_cast<long>(vertex)), big_endian);
  if (start < 0) return std::nullopt;
  auto at = static_cast<std::size_t>(start);
  for (long row = 0; row < element.count; ++row)
    for (std::size_t k = 0; k < element.properties.size(); ++k) {
      const PlyProperty& p = element.properties[k];
      const long size = ply_type_size(p.type);
      if (size == 0) return std::nullopt;
      long items = 1;
      if (p.is_list()) {
        const long count_size = ply_type_size(p.count_type);
        if (count_size == 0 || at + static_cast<std::size_t>(count_size) > body.size()) return std::nullopt;
        items = static_cast<long>(raw_bits(body, at, count_size, big_endian));
        at += static_cast<std::size_t>(count_size);
      }
      if (at + static_cast<std::size_t>(items * size) > body.size()) return std::nullopt;
      for (int c = 0; c < 3; ++c)
        if (column[c] == static_cast<int>(k)) {
          const std::uint64_t bits = raw_bits(body, at, 8, big_endian);
          double value;
          std::memcpy(&value, &bits, sizeof value);
          positions(row, c) = value;
        }
      at += static_cast<std::size_t>(items * size);
    }
  return positions;
}

}  // namespace drape::mesh_io
