#pragma once
// A PLY file's header as it declares its elements (internal to the mesh
// readers: the completeness check and the exact positions read it).
#include <string>
#include <vector>

namespace drape::mesh_io {

struct PlyProperty {
  std::string name;
  std::string type;        // a scalar's type, or a list's item type
  std::string count_type;  // a list's count type ("" for a scalar)
  bool is_list() const { return !count_type.empty(); }
};

struct PlyElement {
  std::string name;
  long count = 0;  // (a negative count in the file reads as 0)
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  std::string format;             // ascii, binary_little_endian, binary_big_endian
  std::vector<PlyElement> elements;
  std::size_t body_offset = 0;    // where the data after end_header's line starts
};

// The bytes of one value of a PLY type (char ... double, int8 ... float64); 0 for an unknown type.
long ply_type_size(const std::string& type);

// An unsigned value of `size` bytes at `at` of a binary body, in its byte order
// (a list's count; a double's raw bits).
unsigned long long ply_unsigned(const std::string& body, std::size_t at, long size, bool big_endian);

// The bytes a binary body's elements take from its start, walked list by
// list (-1 when the body ends first, or a type is unknown).
long ply_binary_extent(const std::string& body, const std::vector<PlyElement>& elements, bool big_endian);

// The header of `bytes`, when they hold one up to its end_header line;
// false (and `header` untouched) when there is no end_header.
bool parse_ply_header(const std::string& bytes, PlyHeader& header);

}  // namespace drape::mesh_io
