// Our own OBJ writer: v and vt in table order, then f v/vt (1-based), so that
// read_mesh gives back exactly the same vertices, UVs and faces.
#include "mesh_io_internal.hpp"

#include <charconv>
#include <string>

namespace drape::mesh_io {
namespace {

// Shortest text that reads back to the same double.
void append(std::string& out, double x) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, result.ptr);
}
void append(std::string& out, int x) {
  char buffer[16];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, result.ptr);
}

}  // namespace

void write_obj(const std::filesystem::path& file, const Mesh& mesh) {
  std::string text = "# written by drape\n";
  text.reserve(static_cast<std::size_t>(mesh.num_vertices()) * 40 + static_cast<std::size_t>(mesh.uv.rows()) * 30 +
               static_cast<std::size_t>(mesh.num_faces()) * 40);
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    text += "v";
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      append(text, mesh.vertices(v, k));
    }
    text += '\n';
  }
  const bool with_uv = mesh.has_uv();
  if (with_uv) {
    for (Eigen::Index t = 0; t < mesh.uv.rows(); ++t) {
      text += "vt ";
      append(text, mesh.uv(t, 0));
      text += ' ';
      append(text, mesh.uv(t, 1));
      text += '\n';
    }
  }
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    text += 'f';
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      append(text, mesh.faces(f, k) + 1);
      if (with_uv) {
        text += '/';
        append(text, mesh.uv_faces(f, k) + 1);
      }
    }
    text += '\n';
  }
  write_file_bytes(file, text);
}

}  // namespace drape::mesh_io
