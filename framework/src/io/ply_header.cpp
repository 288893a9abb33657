// parse_ply_header, ply_type_size (ply_header.hpp).
#include "ply_header.hpp"

#include <algorithm>
#include <map>
#include <sstream>

namespace drape::mesh_io {

long ply_type_size(const std::string& type) {
  static const std::map<std::string, long> sizes = {
      {"char", 1},  {"int8", 1},   {"uchar", 1},  {"uint8", 1},   {"short", 2},   {"int16", 2},
      {"ushort", 2}, {"uint16", 2}, {"int", 4},    {"int32", 4},   {"uint", 4},    {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

unsigned long long ply_unsigned(const std::string& body, std::size_t at, long size, bool big_endian) {
  unsigned long long n = 0;
  for (long b = 0; b < size; ++b)
    n = (n << 8) | static_cast<unsigned char>(body[at + static_cast<std::size_t>(big_endian ? b : size - 1 - b)]);
  return n;
}

long ply_binary_extent(const std::string& body, const std::vector<PlyElement>& elements, bool big_endian) {
  std::size_t at = 0;
  for (const PlyElement& e : elements)
    for (long i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.properties) {
        const long size = ply_type_size(p.type), count_size = p.is_list() ? ply_type_size(p.count_type) : 0;
        if (size == 0 || (p.is_list() && count_size == 0)) return -1;
        if (!p.is_list()) {
          at += static_cast<std::size_t>(size);
          continue;
        }
        if (at + static_cast<std::size_t>(count_size) > body.size()) return -1;
        const unsigned long long n = ply_unsigned(body, at, count_size, big_endian);
        at += static_cast<std::size_t>(count_size) + n * static_cast<std::size_t>(size);
        if (at > body.size()) return -1;
      }
  return at > body.size() ? -1 : static_cast<long>(at);
}

bool parse_ply_header(const std::string& bytes, PlyHeader& header) {
  std::size_t end = bytes.find("end_header");
  if (end == std::string::npos) return false;
  end = bytes.find('\n', end);
  if (end == std::string::npos) end = bytes.size() - 1;
  PlyHeader out;
  out.body_offset = end + 1;
  std::istringstream lines(bytes.substr(0, end));
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format") {
      words >> out.format;
    } else if (keyword == "element") {
      PlyElement e;
      words >> e.name >> e.count;
      e.count = std::max(e.count, 0L);
      out.elements.push_back(e);
    } else if (keyword == "property" && !out.elements.empty()) {
      PlyProperty p;
      words >> p.type;
      if (p.type == "list") words >> p.count_type >> p.type;
      words >> p.name;
      out.elements.back().properties.push_back(p);
    }
  }
  header = std::move(out);
  return true;
}

}  // namespace drape::mesh_io
