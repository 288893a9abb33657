// PLY and glTF are written through assimp's exporter. Both store one UV per
// vertex, so a vertex whose corners have different UVs (a UV seam) is written
// once with the UV of its first corner, at its own index, and once more per
// other UV, appended after all original vertices. read_mesh merges those
// copies back (identical position), so vertex order and count survive.
//
// Measured limits of assimp 5.2.5's glTF exporter (it always runs
// JoinIdenticalVertices): vertices used by no face are dropped, and distinct
// vertices with the same UV that lie within ~1e-5 of the mesh size of each
// other are joined (measured on a box of diagonal 1.4: 1e-6 apart joined,
// 1e-5 apart kept). The first is refused with a clear error here; the second
// does not happen on real garments and bodies. PLY keeps everything.
#include <drape/errors.hpp>

#include "mesh_io_internal.hpp"

#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include <map>
#include <memory>
#include <utility>
#include <vector>

namespace drape::mesh_io {
namespace {

// Output vertex k is original vertex source[k] with uv row uv_row[k] (-1: none).
struct SeamSplit {
  std::vector<int> source, uv_row;
  std::vector<unsigned> corners;  // [F*3] output vertex per face corner
};

SeamSplit split_uv_seams(const Mesh& mesh) {
  const int V = mesh.num_vertices();
  SeamSplit s;
  s.source.resize(static_cast<std::size_t>(V));
  for (int v = 0; v < V; ++v) s.source[v] = v;
  s.uv_row.assign(static_cast<std::size_t>(V), -1);
  s.corners.reserve(static_cast<std::size_t>(mesh.num_faces()) * 3);
  const bool with_uv = mesh.has_uv();
  std::map<std::pair<int, std::pair<double, double>>, int> copies;  // (vertex, uv) -> appended vertex
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces(f, k);
      int out = v;
      if (with_uv) {
        const int t = mesh.uv_faces(f, k);
        if (s.uv_row[v] < 0) {
          s.uv_row[v] = t;
        } else if (mesh.uv.row(t) != mesh.uv.row(s.uv_row[v])) {
          const auto [it, added] =
              copies.try_emplace({v, {mesh.uv(t, 0), mesh.uv(t, 1)}}, static_cast<int>(s.source.size()));
          if (added) {
            s.source.push_back(v);
            s.uv_row.push_back(t);
          }
          out = it->second;
        }
      }
      s.corners.push_back(static_cast<unsigned>(out));
    }
  }
  return s;
}

std::unique_ptr<aiScene> make_scene(const Mesh& mesh, const SeamSplit& split) {
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode;
  scene->mRootNode->mNumMeshes = 1;
  scene->mRootNode->mMeshes = new unsigned[1]{0};
  scene->mNumMaterials = 1;  // exporters expect at least one material
  scene->mMaterials = new aiMaterial*[1]{new aiMaterial};
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh*[1]{new aiMesh};

  aiMesh& out = *scene->mMeshes[0];
  out.mMaterialIndex = 0;
  out.mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  const auto n = static_cast<unsigned>(split.source.size());
  out.mNumVertices = n;
  out.mVertices = new aiVector3D[n];
  for (unsigned i = 0; i < n; ++i) {
    const auto row = mesh.vertices.row(split.source[i]);
    out.mVertices[i] = aiVector3D(static_cast<ai_real>(row(0)), static_cast<ai_real>(row(1)), static_cast<ai_real>(row(2)));
  }
  if (mesh.has_uv()) {
    out.mNumUVComponents[0] = 2;
    out.mTextureCoords[0] = new aiVector3D[n];
    for (unsigned i = 0; i < n; ++i) {
      const int t = split.uv_row[i];
      out.mTextureCoords[0][i] = t < 0 ? aiVector3D(0, 0, 0)
                                       : aiVector3D(static_cast<ai_real>(mesh.uv(t, 0)),
                                                    static_cast<ai_real>(mesh.uv(t, 1)), 0);
    }
  }
  out.mNumFaces = static_cast<unsigned>(mesh.num_faces());
  out.mFaces = new aiFace[out.mNumFaces];
  for (unsigned f = 0; f < out.mNumFaces; ++f) {
    out.mFaces[f].mNumIndices = 3;
    out.mFaces[f].mIndices = new unsigned[3]{split.corners[3 * f], split.corners[3 * f + 1], split.corners[3 * f + 2]};
  }
  return scene;
}

std::string base64(const unsigned char* data, std::size_t size) {
  static const char* const alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (std::size_t i = 0; i < size; i += 3) {
    const std::size_t left = size - i;
    const unsigned b = (unsigned{data[i]} << 16) | (left > 1 ? unsigned{data[i + 1]} << 8 : 0u) |
                       (left > 2 ? unsigned{data[i + 2]} : 0u);
    out += alphabet[(b >> 18) & 63];
    out += alphabet[(b >> 12) & 63];
    out += left > 1 ? alphabet[(b >> 6) & 63] : '=';
    out += left > 2 ? alphabet[b & 63] : '=';
  }
  return out;
}

// assimp's .gltf comes as JSON plus a separate .bin named after the temporary
// file; embedding the buffer as a data URI gives one self-contained file that
// can be renamed atomically.
std::string embed_gltf_buffer(const aiExportDataBlob& blob, const std::string& what) {
  std::string json(static_cast<const char*>(blob.data), blob.size);
  const std::string uri = "\"$blobfile.bin\"";  // the name ExportToBlob gives the buffer
  const std::size_t at = json.find(uri);
  if (!blob.next || at == std::string::npos || json.find(uri, at + 1) != std::string::npos)
    throw Error("cannot write " + what + ": assimp's glTF output does not have the expected single buffer");
  const aiExportDataBlob& bin = *blob.next;
  json.replace(at, uri.size(),
               "\"data:application/octet-stream;base64," +
                   base64(static_cast<const unsigned char*>(bin.data), bin.size) + "\"");
  return json;
}

}  // namespace

void write_with_assimp(const std::filesystem::path& file, const Mesh& mesh, const std::string& format_id,
                       const std::string& what) {
  const SeamSplit split = split_uv_seams(mesh);
  if (format_id != "plyb") {
    std::vector<char> used(static_cast<std::size_t>(mesh.num_vertices()), 0);
    for (unsigned c : split.corners) used[split.source[c]] = 1;
    for (int v = 0; v < mesh.num_vertices(); ++v)
      if (!used[v])
        throw ConfigError(what + ": cannot write as glTF: vertex " + std::to_string(v) +
                          " belongs to no face and assimp's glTF exporter drops such vertices; write .obj or .ply");
  }
  const std::unique_ptr<aiScene> scene = make_scene(mesh, split);
  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(scene.get(), format_id);
  if (!blob) throw Error("cannot write " + what + ": assimp: " + exporter.GetErrorString());
  if (format_id == "gltf2") {
    write_file_bytes(file, embed_gltf_buffer(*blob, what));
  } else {
    write_file_bytes(file, std::string(static_cast<const char*>(blob->data), blob->size));
  }
}

}  // namespace drape::mesh_io
