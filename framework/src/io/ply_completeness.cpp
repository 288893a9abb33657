// A PLY file copied only in part still has its whole header, and assimp then
// fills the missing vertices and faces with garbage instead of failing. The
// header says how many elements follow, which gives a lower bound on the size
// of the body (binary) or on its number of lines (ASCII, one element a line).
#include <drape/errors.hpp>

#include "mesh_io_internal.hpp"

#include <algorithm>
#include <map>
#include <sstream>
#include <string>
#include <vector>

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
  if (header_end == std::string::npos) {
    // A header cut before its end sends assimp's PLY reader into an endless
    // loop (libassimp 5.2); refused before assimp sees it.
    if (bytes.rfind("ply", 0) == 0)
      throw ConfigError(where, "the PLY header has no end_header line (is the file cut short?)");
    return;  // not a PLY file: assimp says what it is
  }
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

void require_complete_off(const std::filesystem::path& file) {
  const std::string bytes = read_file_bytes(file);
  const SourceLocation where{file.string(), 0};
  // Lines without comments, blanks skipped: the keyword (OFF, COFF, NOFF, ...,
  // possibly with the counts after it), then "vertices faces edges", then one
  // line per vertex and per face. A count larger than the lines that follow
  // had assimp reserve gigabytes for a file of a few bytes.
  std::istringstream text(bytes);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(text, line)) {
    line = line.substr(0, line.find('#'));
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
  }
  if (lines.empty()) return;  // assimp says what is wrong
  std::istringstream first(lines[0]);
  std::string keyword;
  first >> keyword;
  if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0) return;  // not an ASCII OFF file
  long vertices = -1, faces = -1;
  std::size_t next = 1;
  if (!(first >> vertices >> faces)) {
    if (lines.size() < 2) throw ConfigError(where, "the OFF file has no line of counts (is it cut short?)");
    std::istringstream counts(lines[1]);
    if (!(counts >> vertices >> faces)) throw ConfigError(where, "the OFF file's second line is not 'vertices faces edges'");
    next = 2;
  }
  if (vertices < 0 || faces < 0)
    throw ConfigError(where, "the OFF header declares " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                                 " faces: counts cannot be negative");
  const long follow = static_cast<long>(lines.size() - next);
  if (follow < vertices + faces)
    throw ConfigError(where, "the OFF header declares " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                                 " faces but only " + std::to_string(follow) + " lines follow (is the file cut short?)");
}

}  // namespace drape::mesh_io
