// Every format other than OBJ is read through assimp, and assimp's vertex order
// is mapped back to the file's.
//
// What assimp 5.2.5 does, measured by writing shuffled meshes and reading them
// back with no post-processing (tests/io/mesh_round_trip_test.cpp keeps checking it):
// - PLY: mVertices in the order of the file's vertex element, unused vertices
//   kept, polygons kept as written (a quad stays one 4-index face).
// - glTF/GLB: mVertices in accessor order, one aiMesh per primitive.
// - OBJ (not used, we parse it ourselves): one vertex per face corner, in face
//   order; JoinIdenticalVertices then splits at UV seams, so the `v` order is lost.
// - STL and similar "triangle soup" formats: one vertex per corner.
// So the rule is: vertices in assimp's order, and a vertex whose position is
// bit-identical to an earlier one is merged into that first occurrence when
// it is a copy the format makes: a corner of a triangle soup (STL, or any
// mesh whose every vertex is one face's corner), a UV-seam copy (its texture coordinate differs; write_mesh appends
// them after the original vertices, see assimp_mesh_writer.cpp), or the same
// vertex in another of the file's meshes (a glTF primitive per material).
// Any other vertex at the same position is a vertex of its own, as an OBJ's
// `v` line is: a body of 6,904 vertices two of which coincide keeps 6,904,
// and a garment's is refused by the mesh garment as its OBJ is (its `weld`
// merges them). An outside check found a PLY garment with one such vertex
// read renumbered from it on, without a word, where the OBJ was refused.
// Node transforms are applied (in double): a glTF in centimetres scaled by
// its node to metres, or moved aside by it, is read where every viewer
// shows it (an outside check: it was refused as 82 m across, or draped on
// the body as if not moved). A mesh placed by two nodes (an instance) is
// refused: its vertices would be two meshes. Each aiMesh has one
// material: with MaterialMesh, its name labels the mesh's triangles.
#include <drape/errors.hpp>

#include "mesh_io_internal.hpp"

#include <assimp/DefaultLogger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>
#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <mutex>
#include <new>
#include <string>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <vector>

namespace drape::mesh_io {
namespace {

struct PositionKey {
  std::uint32_t bits[3];
  bool operator==(const PositionKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};
struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint32_t b : k.bits) h = (h ^ b) * 1099511628211ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};
PositionKey key_of(const aiVector3D& p) {
  PositionKey key{};
  const float xyz[3] = {p.x + 0.0f, p.y + 0.0f, p.z + 0.0f};  // + 0 turns -0 into +0
  std::memcpy(key.bits, xyz, sizeof xyz);
  return key;
}

// assimp reports some damage only as a warning and reads on without what it
// could not use: a glTF face with an index past its vertices is dropped
// ("Some faces had out-of-range indices. Those faces were dropped."), and
// other readers skip faces with invalid indices the same way. A garment read
// so has a hole and a body lost a face, and nothing would say so: the
// warnings are collected here (per thread: readers may run in parallel) and
// those of lost data refused.
thread_local std::vector<std::string> assimp_warnings;

class WarningCollector : public Assimp::LogStream {
 public:
  void write(const char* message) override {
    std::string m = message;  // "Warn,  T0: what", the severity and thread first
    if (const std::size_t colon = m.find(": "); colon != std::string::npos && colon < 16) m.erase(0, colon + 2);
    assimp_warnings.push_back(std::move(m));
  }
};

// assimp's logger is one per process: created once, with this stream for
// warnings and errors only (no default stream: assimp prints nothing itself).
void collect_assimp_warnings() {
  static std::once_flag once;
  std::call_once(once, [] {
    Assimp::DefaultLogger::create("", Assimp::Logger::NORMAL, 0);
    Assimp::DefaultLogger::get()->attachStream(new WarningCollector, Assimp::Logger::Warn | Assimp::Logger::Err);
  });
  assimp_warnings.clear();
}

// The first warning of data assimp left out, or "".
std::string warning_of_lost_data() {
  for (const std::string& w : assimp_warnings) {
    std::string lower = w;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    for (const char* sign : {"out-of-range", "out of range", "invalid index", "dropped"})
      if (lower.find(sign) != std::string::npos) return w;
  }
  return "";
}

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && (s.back() == ' ' || s.back() == '\r')) s.pop_back();
  return s;
}

}  // namespace

Mesh read_with_assimp(const std::filesystem::path& file, MaterialMesh* materials) {
  const SourceLocation where{file.string(), 0};
  Assimp::Importer importer;
  // No post-processing at all: Triangulate may pick the other diagonal of a quad,
  // JoinIdenticalVertices and ImproveCacheLocality reorder vertices.
  // Checked before assimp reads: a PLY header cut short loops its reader
  // forever, and counts far beyond the file make it reserve gigabytes.
  const std::string extension = lower_extension(file);
  std::string ply_bytes;  // (read once: checked here, its double positions read at the end)
  if (extension == ".ply") ply_bytes = require_complete_ply(file);
  if (extension == ".off") require_complete_off(file);
  if (extension == ".glb") require_complete_glb(file);
  const aiScene* scene = nullptr;
  collect_assimp_warnings();
  try {
    scene = importer.ReadFile(file.string(), 0);
  } catch (const std::bad_alloc&) {
    throw ConfigError(where, "cannot read this mesh: it asks for more memory than there is (a vertex or face count in "
                             "it far larger than the file?)");
  }
  if (!scene) {
    const std::string error = one_line(importer.GetErrorString());
    // assimp picks a reader by the contents as well as the name: a glTF cut
    // short or with a flipped bit in its JSON is "no suitable reader found",
    // which reads as a format drape does not take (an outside check).
    if (error.find("No suitable reader found") != std::string::npos && importer.IsExtensionSupported(extension))
      throw ConfigError(where, "cannot read this mesh: no " + extension.substr(1) + " reader accepts its contents, though " +
                                   extension + " is a format drape reads: the file is damaged or truncated, or is not " +
                                   "the format its name says (" + error + ")");
    throw ConfigError(where, "cannot read this mesh: " + error);
  }
  if (const std::string lost = warning_of_lost_data(); !lost.empty())
    throw ConfigError(where, "the file is damaged: " + one_line(lost) + " (assimp would read on without them)");
  if (scene->mNumMeshes == 0) throw ConfigError(where, "the file holds no mesh");

  // Each mesh's placement: the product of the transforms of the nodes above it.
  std::vector<aiMatrix4x4> placement(scene->mNumMeshes);
  std::vector<int> placed_by(scene->mNumMeshes, 0);
  const auto place = [&](const auto& self, const aiNode* node, const aiMatrix4x4& above) -> void {
    const aiMatrix4x4 here = above * node->mTransformation;
    for (unsigned k = 0; k < node->mNumMeshes; ++k)
      if (const unsigned m = node->mMeshes[k]; m < scene->mNumMeshes) placement[m] = here, ++placed_by[m];
    for (unsigned c = 0; c < node->mNumChildren; ++c) self(self, node->mChildren[c], here);
  };
  if (scene->mRootNode) place(place, scene->mRootNode, aiMatrix4x4());
  for (unsigned m = 0; m < scene->mNumMeshes; ++m)
    if (placed_by[m] > 1)
      throw ConfigError(where, "mesh " + std::to_string(m) + " is placed by " + std::to_string(placed_by[m]) +
                                   " nodes (instances): drape reads one surface a mesh; give each copy its own mesh");

  bool with_uv = true;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) with_uv = with_uv && scene->mMeshes[m]->HasTextureCoords(0);

  struct First {
    int vertex;        // ours
    unsigned mesh;     // the aiMesh it came from
    aiVector3D uv;     // its texture coordinate (with UVs)
  };
  std::unordered_map<PositionKey, First, PositionHash> first_at;
  std::vector<double> positions, uvs;
  std::vector<int> faces, uv_faces;
  std::vector<int> merged;  // aiMesh vertex -> our vertex, for the current aiMesh
  int uv_offset = 0;
  std::unordered_map<unsigned, int> region_of_material;  // assimp material -> index into materials->material_names
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    int region = 0;
    if (materials) {
      // Each aiMesh has one material; its name is the region (glTF: the
      // material's "name"; assimp names one it made up "DefaultMaterial").
      const auto [it, added] = region_of_material.try_emplace(mesh->mMaterialIndex, static_cast<int>(materials->material_names.size()));
      if (added) {
        aiString name;
        const bool named = mesh->mMaterialIndex < scene->mNumMaterials &&
                           scene->mMaterials[mesh->mMaterialIndex]->Get(AI_MATKEY_NAME, name) == aiReturn_SUCCESS &&
                           name.length > 0;
        materials->material_names.push_back(named ? name.C_Str() : "default");
      }
      region = it->second;
    }
    // A triangle soup (STL, or a PLY written so): every corner its own
    // vertex, nothing but its position to join it by.
    std::vector<unsigned> corners(mesh->mNumVertices, 0);
    for (unsigned f = 0; f < mesh->mNumFaces; ++f)
      for (unsigned k = 0; k < mesh->mFaces[f].mNumIndices; ++k)
        if (mesh->mFaces[f].mIndices[k] < mesh->mNumVertices) ++corners[mesh->mFaces[f].mIndices[k]];
    const bool soup = extension == ".stl" || std::all_of(corners.begin(), corners.end(), [](unsigned c) { return c == 1; });
    merged.assign(mesh->mNumVertices, 0);
    const aiMatrix4x4& t = placement[m];  // (identity for a mesh no node moves)
    const bool moved = !t.IsIdentity();
    for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
      const aiVector3D& p = mesh->mVertices[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw ConfigError(where, "vertex " + std::to_string(i) + " of mesh " + std::to_string(m) +
                                     " has a coordinate that is not a finite number");
      const aiVector3D uv = with_uv ? mesh->mTextureCoords[0][i] : aiVector3D();
      const auto next = static_cast<int>(positions.size() / 3);
      // Where the vertex is placed (in double: a float's rounding would move an unplaced mesh's vertices too).
      double xyz[3] = {p.x, p.y, p.z};
      if (moved) {
        xyz[0] = t.a1 * p.x + t.a2 * p.y + t.a3 * p.z + t.a4;
        xyz[1] = t.b1 * p.x + t.b2 * p.y + t.b3 * p.z + t.b4;
        xyz[2] = t.c1 * p.x + t.c2 * p.y + t.c3 * p.z + t.c4;
      }
      // Keyed where it is placed (unmoved: its own float bits).
      const aiVector3D placed(static_cast<float>(xyz[0]), static_cast<float>(xyz[1]), static_cast<float>(xyz[2]));
      const auto [it, added] = first_at.try_emplace(key_of(placed), First{next, m, uv});
      const First& first = it->second;
      const bool copy = soup || first.mesh != m || (with_uv && (first.uv.x != uv.x || first.uv.y != uv.y));
      if (added || !copy) positions.insert(positions.end(), {xyz[0], xyz[1], xyz[2]});
      merged[i] = added || !copy ? next : first.vertex;
      if (with_uv) {
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
          throw ConfigError(where, "texture coordinate of vertex " + std::to_string(i) + " of mesh " +
                                       std::to_string(m) + " is not a finite number");
        uvs.insert(uvs.end(), {uv.x, uv.y});
      }
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        if (face.mIndices[k] >= mesh->mNumVertices)
          throw ConfigError(where, "face " + std::to_string(f) + " of mesh " + std::to_string(m) +
                                       " refers to vertex " + std::to_string(face.mIndices[k]) + " but there are " +
                                       std::to_string(mesh->mNumVertices) +
                                       // A binary PLY whose vertex count is short of its vertices reads the rest as
                                       // faces: an index in the hundreds of millions (an outside check).
                                       (extension == ".ply" ? " (check the header's element counts against the data: "
                                                              "a vertex count short of the vertices that follow reads "
                                                              "the rest as faces)"
                                                            : ""));
      // Points and lines carry no surface; polygons become a fan like in OBJ.
      for (unsigned k = 1; k + 1 < face.mNumIndices; ++k) {
        for (unsigned c : {0u, k, k + 1}) {
          faces.push_back(merged[face.mIndices[c]]);
          if (with_uv) uv_faces.push_back(uv_offset + static_cast<int>(face.mIndices[c]));
        }
        if (materials) materials->face_material.push_back(region);
      }
    }
    uv_offset += static_cast<int>(mesh->mNumVertices);
  }

  using RowMajor3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  using RowMajor2d = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;
  using RowMajor3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
  Mesh out;
  out.vertices = Eigen::Map<const RowMajor3d>(positions.data(), static_cast<Eigen::Index>(positions.size() / 3), 3);
  out.faces = Eigen::Map<const RowMajor3i>(faces.data(), static_cast<Eigen::Index>(faces.size() / 3), 3);
  if (with_uv) {
    out.uv = Eigen::Map<const RowMajor2d>(uvs.data(), static_cast<Eigen::Index>(uvs.size() / 2), 2);
    out.uv_faces = Eigen::Map<const RowMajor3i>(uv_faces.data(), static_cast<Eigen::Index>(uv_faces.size() / 3), 3);
  }
  if (out.num_vertices() == 0) throw ConfigError(where, "the file holds no vertices");
  // A PLY written in double: its positions as written, where assimp kept each
  // vertex (one mesh, no vertex merged: the counts agree) and the float it
  // read is the double rounded.
  if (extension == ".ply" && scene->mNumMeshes == 1)
    if (const std::optional<Eigen::MatrixX3d> exact = read_ply_double_positions(ply_bytes);
        exact && exact->rows() == out.num_vertices() &&
        ((exact->cast<float>().cast<double>() - out.vertices).cwiseAbs().array() <=
         1e-6 * out.vertices.cwiseAbs().array().max(1.0)).all())
      out.vertices = *exact;
  return out;
}

}  // namespace drape::mesh_io
