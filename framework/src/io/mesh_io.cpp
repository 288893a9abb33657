// read_mesh / write_mesh: pick the reader or writer by extension, check the
// mesh, write atomically.
#include <drape/vertex_count.hpp>
#include <drape/io/atomic_file.hpp>
#include <drape/errors.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/io/write_failure.hpp>

#include "mesh_io_internal.hpp"

#include <assimp/Importer.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>

namespace fs = std::filesystem;

namespace drape {
namespace mesh_io {

std::string lower_extension(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string read_file_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ConfigError(SourceLocation{file.string(), 0}, std::string("cannot open: ") + std::strerror(errno));
  std::string bytes;
  in.seekg(0, std::ios::end);
  bytes.resize(static_cast<std::size_t>(in.tellg()));
  in.seekg(0, std::ios::beg);
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!in) throw ConfigError(SourceLocation{file.string(), 0}, "cannot read the whole file");
  return bytes;
}

void write_file_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw Error("cannot write '" + file.string() + "': " + std::strerror(errno));
}

}  // namespace mesh_io

namespace {

// An invalid mesh handed to write_mesh is a program error, not the user's.
void check_mesh(const Mesh& mesh, const std::string& what) {
  const auto fail = [&](const std::string& why) { throw Error("cannot write " + what + ": " + why); };
  if (!mesh.vertices.allFinite()) fail("a vertex coordinate is not a finite number");
  if (mesh.num_faces() > 0 && (mesh.faces.minCoeff() < 0 || mesh.faces.maxCoeff() >= mesh.num_vertices()))
    fail("a face index is outside 0.." + std::to_string(mesh.num_vertices() - 1));
  if (mesh.uv.rows() == 0) return;
  if (mesh.uv_faces.rows() != mesh.faces.rows())
    fail("uv_faces has " + std::to_string(mesh.uv_faces.rows()) + " rows but there are " +
         std::to_string(mesh.faces.rows()) + " faces");
  if (!mesh.uv.allFinite()) fail("a texture coordinate is not a finite number");
  if (mesh.num_faces() > 0 && (mesh.uv_faces.minCoeff() < 0 || mesh.uv_faces.maxCoeff() >= mesh.uv.rows()))
    fail("a uv_faces index is outside 0.." + std::to_string(mesh.uv.rows() - 1));
}

const char* const kWritable = ".obj, .ply, .gltf or .glb";

}  // namespace

namespace {

// The file's extension when it is a mesh drape reads; ConfigError otherwise.
std::string readable_extension(const fs::path& file) {
  const SourceLocation where{file.string(), 0};
  std::error_code ec;
  if (!fs::exists(file, ec)) throw ConfigError(where, "no such file");
  if (fs::is_directory(file, ec)) throw ConfigError(where, "is a folder, not a mesh file");
  const std::string ext = mesh_io::lower_extension(file);
  if (ext != ".obj" && (ext.empty() || !Assimp::Importer().IsExtensionSupported(ext)))
    throw ConfigError(where, "unknown mesh format '" + ext + "'; use " + kWritable + " (or another format assimp reads)");
  return ext;
}

}  // namespace

Mesh read_mesh(const fs::path& file) {
  if (readable_extension(file) == ".obj") return triangulate(read_obj_polygons(file));
  return mesh_io::read_with_assimp(file);
}

MaterialMesh read_mesh_with_materials(const fs::path& file) {
  MaterialMesh out;
  if (readable_extension(file) != ".obj") {
    out.mesh = mesh_io::read_with_assimp(file, &out);
    return out;
  }
  const PolygonMesh polygons = read_obj_polygons(file);
  out.mesh = triangulate(polygons);
  out.material_names = polygons.material_names;
  out.face_material.reserve(static_cast<std::size_t>(out.mesh.num_faces()));
  // triangulate splits polygon f into face_size(f) - 2 consecutive triangles
  for (int f = 0; f < polygons.num_faces(); ++f)
    out.face_material.insert(out.face_material.end(), static_cast<std::size_t>(polygons.face_size(f) - 2),
                             polygons.face_material[static_cast<std::size_t>(f)]);
  return out;
}

namespace {

// assimp's exporter for a writable extension ("" for OBJ, drape's own writer);
// ConfigError for any other.
std::string writer_format(const fs::path& file) {
  const std::string ext = mesh_io::lower_extension(file);
  if (ext == ".ply") return "plyb";  // binary: compact, and exact floats
  if (ext == ".gltf") return "gltf2";
  if (ext == ".glb") return "glb2";
  if (ext != ".obj")
    throw ConfigError("cannot write '" + file.string() + "': unknown mesh format '" + ext + "'; use " + kWritable +
                      did_you_mean(ext, {".obj", ".ply", ".gltf", ".glb"}));
  return {};
}

}  // namespace

void check_mesh_output(const fs::path& file) {
  writer_format(file);
  if (const std::string cause = write_failure_cause(file, false); !cause.empty())
    throw ConfigError("cannot write '" + file.string() + "': " + cause);
}

void write_mesh(const fs::path& file, const Mesh& mesh) {
  const std::string what = "'" + file.string() + "'";
  const std::string assimp_format = writer_format(file);
  check_mesh(mesh, what);  // the folder is write_atomically's to check (write_failure_cause)
  write_atomically(file, [&](const fs::path& tmp) {
    if (assimp_format.empty()) {
      mesh_io::write_obj(tmp, mesh);
    } else {
      mesh_io::write_with_assimp(tmp, mesh, assimp_format, what);
    }
  });
}

void require_vertex_count(const Mesh& mesh, int expected, const std::string& what_file, const std::string& why) {
  require_vertex_count(mesh.num_vertices(), expected, what_file, why);
}

void require_vertex_count(const Mesh& mesh, int expected, const std::string& what) {
  require_vertex_count(mesh, expected, what, "");
}

}  // namespace drape
