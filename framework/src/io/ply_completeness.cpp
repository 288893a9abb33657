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
#include "ply_header.hpp"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

namespace drape::mesh_io {

std::string require_complete_ply(const std::filesystem::path& file) {
  const std::string bytes = read_file_bytes(file);
  const SourceLocation where{file.string(), 0};
  PlyHeader header;
  if (!parse_ply_header(bytes, header)) {
    // A header cut before its end sends assimp's PLY reader into an endless
    // loop (libassimp 5.2); refused before assimp sees it.
    if (bytes.rfind("ply", 0) == 0)
      throw ConfigError(where, "the PLY header has no end_header line (is the file cut short?)");
    return bytes;  // not a PLY file: assimp says what it is
  }
  long elements = 0, min_bytes = 0;
  for (const PlyElement& e : header.elements) {
    elements += e.count;
    for (const PlyProperty& p : e.properties) {
      // A face has at least three corners; other lists may be empty.
      const long items = (e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index")) ? 3 : 0;
      min_bytes += p.is_list() ? e.count * (ply_type_size(p.count_type) + items * ply_type_size(p.type))
                               : e.count * ply_type_size(p.type);
    }
  }
  const std::string body = bytes.substr(std::min(header.body_offset, bytes.size()));
  const std::string& format = header.format;
  // assimp's reader takes the first data for the vertices whatever the
  // header says comes first: a file with a camera element before them was
  // read with the camera as a vertex and no faces, without a word (ASCII and
  // binary alike).
  for (const PlyElement& e : header.elements) {
    if (e.name == "vertex") break;
    if (e.count > 0)
      throw ConfigError(where, "the element '" + e.name + "' comes before the vertices, which the PLY reader drape "
                               "uses (assimp) misreads: write the vertices first");
  }
  if (format == "ascii") {
    long lines = 0;
    std::istringstream text(body);
    std::string line;
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
  } else if (const long used = ply_binary_extent(body, header.elements, format == "binary_big_endian");
             used >= 0 && static_cast<long>(body.size()) > used) {
    throw ConfigError(where, "the header's elements take " + std::to_string(used) + " bytes but " +
                                 std::to_string(body.size()) + " follow: a count in the header is short, and what "
                                 "follows it would be left out");
  }
  return bytes;
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
