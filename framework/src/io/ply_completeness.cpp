// A PLY file copied only in part still has its whole header, and assimp then
// fills the missing vertices and faces with garbage instead of failing. The
// header says how many elements follow, which gives a lower bound on the size
// of the body (binary) or on its number of lines (ASCII, one element a line).
// The other way, a count short of what follows (a face count of 1,900 over
// 1,906 faces) had assimp read the first 1,900 and leave a hole without a
// word: data after the last element the header declares is refused too
// (binary: the elements walked list by list; ASCII: one line an element).
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

// One element's property as the header declares it.
struct Property {
  long size = 0;                  // a scalar's bytes, or a list's item bytes
  long count_size = 0;            // a list's count bytes (0: a scalar)
};
struct Element {
  long count = 0;
  std::vector<Property> properties;
};

// The bytes the binary body's elements take, walked list by list (-1 when
// the body ends first, or a type is unknown).
long binary_extent(const std::string& body, const std::vector<Element>& elements, bool big_endian) {
  std::size_t at = 0;
  for (const Element& e : elements)
    for (long i = 0; i < e.count; ++i)
      for (const Property& p : e.properties) {
        if (p.size == 0) return -1;
        if (p.count_size == 0) {
          at += static_cast<std::size_t>(p.size);
          continue;
        }
        if (at + static_cast<std::size_t>(p.count_size) > body.size()) return -1;
        unsigned long long n = 0;
        for (long b = 0; b < p.count_size; ++b) {
          const auto byte = static_cast<unsigned char>(body[at + static_cast<std::size_t>(big_endian ? b : p.count_size - 1 - b)]);
          n = (n << 8) | byte;
        }
        at += static_cast<std::size_t>(p.count_size) + n * static_cast<std::size_t>(p.size);
        if (at > body.size()) return -1;
      }
  return at > body.size() ? -1 : static_cast<long>(at);
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
  std::vector<Element> declared;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format") {
      words >> format;
    } else if (keyword == "element") {
      words >> element >> element_count;
      elements += std::max(element_count, 0L);
      declared.push_back({std::max(element_count, 0L), {}});
    } else if (keyword == "property") {
      std::string type, count_type, item_type, name;
      words >> type;
      if (type == "list") {
        words >> count_type >> item_type >> name;
        // A face has at least three corners; other lists may be empty.
        const long items = (element == "face" && (name == "vertex_indices" || name == "vertex_index")) ? 3 : 0;
        min_bytes += element_count * (type_size(count_type) + items * type_size(item_type));
        if (!declared.empty()) declared.back().properties.push_back({type_size(item_type), type_size(count_type)});
      } else {
        min_bytes += element_count * type_size(type);
        if (!declared.empty()) declared.back().properties.push_back({type_size(type), 0});
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
    if (lines > elements)
      throw ConfigError(where, "the header declares " + std::to_string(elements) + " elements but " +
                                   std::to_string(lines) + " lines follow: a count in the header is short, and "
                                   "what follows it would be left out");
  } else if (static_cast<long>(body.size()) < min_bytes) {
    throw ConfigError(where, "the header declares at least " + std::to_string(min_bytes) + " bytes of data but only " +
                                 std::to_string(body.size()) + " follow (is the file cut short?)");
  } else if (const long used = binary_extent(body, declared, format == "binary_big_endian");
             used >= 0 && static_cast<long>(body.size()) > used) {
    throw ConfigError(where, "the header's elements take " + std::to_string(used) + " bytes but " +
                                 std::to_string(body.size()) + " follow: a count in the header is short, and what "
                                 "follows it would be left out");
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
