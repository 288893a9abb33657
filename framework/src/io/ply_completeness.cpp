// A PLY file copied only in part still has its whole header, and assimp then
// fills the missing vertices and faces with garbage instead of failing. The
// header says how many elements follow, which gives a lower bound on the size
// of the body (binary) or on its number of lines (ASCII, one element a line).
#include <drape/errors.hpp>

#include "mesh_io_internal.hpp"

#include <algorithm>
#include <map>
#include <sstream>

namespace drape::mesh_io {
namespace {

long type_size(const std::string& type) {
  static const std::map<std::string, long> sizes = {
      {"char", 1},  {"int8", 1},   {"uchar", 1},  {"uint8", 1},   {"short", 2},   {"int16", 2},
      {"ushort", 2}, {"uint16", 2}, {"int", 4},    {"int32", 4},   {"uint", 4},    {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

}  // namespace

void require_complete_ply(const std::filesystem::path& file) {
  const std::string bytes = read_file_bytes(file);
  const SourceLocation where{file.string(), 0};
  std::size_t header_end = bytes.find("end_header");
  if (header_end == std::string::npos) return;  // not a PLY header assimp accepted; nothing to check
  header_end = bytes.find('\n', header_end);
  if (header_end == std::string::npos) header_end = bytes.size() - 1;

  std::istringstream header(bytes.substr(0, header_end));
  std::string line, format;
  long elements = 0, min_bytes = 0, element_count = 0;
  std::string element;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format") {
      words >> format;
    } else if (keyword == "element") {
      words >> element >> element_count;
      elements += std::max(element_count, 0L);
    } else if (keyword == "property") {
      std::string type, count_type, item_type, name;
      words >> type;
      if (type == "list") {
        words >> count_type >> item_type >> name;
        // A face has at least three corners; other lists may be empty.
        const long items = (element == "face" && (name == "vertex_indices" || name == "vertex_index")) ? 3 : 0;
        min_bytes += element_count * (type_size(count_type) + items * type_size(item_type));
      } else {
        min_bytes += element_count * type_size(type);
      }
    }
  }
  const std::string body = bytes.substr(header_end + 1);
  if (format == "ascii") {
    long lines = 0;
    std::istringstream text(body);
    while (std::getline(text, line))
      if (line.find_first_not_of(" \t\r") != std::string::npos) ++lines;
    if (lines < elements)
      throw ConfigError(where, "the header declares " + std::to_string(elements) + " elements but only " +
                                   std::to_string(lines) + " lines follow (is the file cut short?)");
  } else if (static_cast<long>(body.size()) < min_bytes) {
    throw ConfigError(where, "the header declares at least " + std::to_string(min_bytes) + " bytes of data but only " +
                                 std::to_string(body.size()) + " follow (is the file cut short?)");
  }
}

}  // namespace drape::mesh_io
