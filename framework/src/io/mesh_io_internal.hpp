#pragma once
// Shared between the mesh readers and writers; not part of the public API.
#include <drape/mesh.hpp>
#include <drape/io/mesh_io.hpp>

#include <Eigen/Core>

#include <filesystem>
#include <optional>
#include <string>

namespace drape::mesh_io {

// Through assimp: any format it reads; vertex order restored (see the .cpp).
// With `materials`, also each triangle's material (MaterialMesh).
Mesh read_with_assimp(const std::filesystem::path& file, MaterialMesh* materials = nullptr);

// assimp reads a PLY that is cut short without complaint (it fills in what is
// missing), so the body's size is checked against the header: ConfigError if short.
// Returns the file's bytes (read once: read_ply_double_positions takes them).
std::string require_complete_ply(const std::filesystem::path& file);
// The same for an ASCII OFF file: its counts against the lines that follow.
void require_complete_off(const std::filesystem::path& file);

// A .glb whose header or chunk lengths disagree with the file: refused
// before assimp reads it (glb_completeness.cpp).
void require_complete_glb(const std::filesystem::path& file);
// A PLY's vertex positions in double when its header declares x, y and z
// double (assimp reads them into floats); nullopt for float positions or a
// file it cannot walk (assimp's reading stands then). `bytes`: the file's, as
// require_complete_ply checked them (its vertices the first element).
std::optional<Eigen::MatrixX3d> read_ply_double_positions(const std::string& bytes);

// These write straight to `file` (the temporary of write_atomically).
// `format_id` is assimp's exporter id: "plyb", "gltf2" or "glb2".
void write_with_assimp(const std::filesystem::path& file, const Mesh& mesh, const std::string& format_id,
                       const std::string& what);
void write_obj(const std::filesystem::path& file, const Mesh& mesh);
void write_file_bytes(const std::filesystem::path& file, const std::string& bytes);

// The whole file as bytes; ConfigError naming the file if it cannot be read.
std::string read_file_bytes(const std::filesystem::path& file);

// Lower-case extension with the dot (".obj").
std::string lower_extension(const std::filesystem::path& file);

}  // namespace drape::mesh_io
