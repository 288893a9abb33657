// A binary glTF's own lengths checked against the file before assimp reads it:
// a 249 KB .glb whose first chunk claimed 2 GiB had assimp allocate and read
// for a minute at 2.1 GB before it failed (an outside check). The container
// (glTF 2.0, "GLB"): a 12-byte header (magic "glTF", version, total length),
// then chunks of an 8-byte header (length, type) and `length` bytes.
#include <drape/errors.hpp>

#include "mesh_io_internal.hpp"

#include <cstdint>
#include <cstring>
#include <string>

namespace drape::mesh_io {

namespace {

std::uint32_t little_endian_u32(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (int k = 3; k >= 0; --k) value = (value << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(k)]);
  return value;
}

}  // namespace

void require_complete_glb(const std::filesystem::path& file) {
  const std::string bytes = read_file_bytes(file);
  const SourceLocation where{file.string(), 0};
  if (bytes.size() < 12 || bytes.compare(0, 4, "glTF") != 0) return;  // no GLB container: assimp says what it is
  const std::uint32_t total = little_endian_u32(bytes, 8);
  if (total != bytes.size())
    throw ConfigError(where, "the GLB header gives the file " + std::to_string(total) + " bytes, but it has " +
                                 std::to_string(bytes.size()) + " (cut short, or damaged)");
  std::size_t at = 12;
  for (int chunk = 0; at < bytes.size(); ++chunk) {
    if (bytes.size() - at < 8)
      throw ConfigError(where, "GLB chunk " + std::to_string(chunk) + " at byte " + std::to_string(at) +
                                   " has no room for its 8-byte header (damaged)");
    const std::uint64_t length = little_endian_u32(bytes, at);
    if (length > bytes.size() - at - 8)
      throw ConfigError(where, "GLB chunk " + std::to_string(chunk) + " at byte " + std::to_string(at) + " says " +
                                   std::to_string(length) + " bytes, but " + std::to_string(bytes.size() - at - 8) +
                                   " follow it (damaged)");
    at += 8 + static_cast<std::size_t>(length);
  }
}

}  // namespace drape::mesh_io
