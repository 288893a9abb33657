#include "clothes.hpp"

#include <drape/errors.hpp>
#include <drape/io/mesh_io.hpp>

#include <Eigen/Geometry>

#include <numeric>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace drape::makehuman {
namespace {

// Connected pieces by shared vertices (union-find over polygon corners).
std::vector<int> piece_of_vertex(const PolygonMesh& p) {
  std::vector<int> parent(static_cast<std::size_t>(p.num_vertices()));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) v = parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
    return v;
  };
  for (int f = 0; f < p.num_faces(); ++f)
    for (int k = 1; k < p.face_size(f); ++k) {
      const int a = find(p.corner_vertex[static_cast<std::size_t>(p.face_start[static_cast<std::size_t>(f)])]);
      const int b = find(p.corner_vertex[static_cast<std::size_t>(p.face_start[static_cast<std::size_t>(f)] + k)]);
      parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  std::vector<int> piece(parent.size());
  for (std::size_t v = 0; v < parent.size(); ++v) piece[v] = find(static_cast<int>(v));
  return piece;
}

double area2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

}  // namespace

Garment load_clothes(const Model& model, const fs::path& dir, const Sliders& body, const std::string& piece_name) {
  const std::string name = dir.filename().string();
  const fs::path obj = dir / (name + ".obj"), clo = dir / (name + ".mhclo");
  const PolygonMesh outfit = read_obj_polygons(obj);
  const ClothesBinding binding = read_mhclo(clo);
  if (static_cast<int>(binding.refs.size()) != outfit.num_vertices())
    throw ConfigError(clo.string() + " binds " + std::to_string(binding.refs.size()) + " vertices but " + obj.string() +
                      " has " + std::to_string(outfit.num_vertices()));
  if (outfit.corner_uv.empty()) throw ConfigError(obj.string() + ": the garment needs UVs (its material space)");
  const Eigen::MatrixX3d morphed = model.morph(body);

  // The piece's vertices, in the outfit's order.
  const std::vector<int> piece = piece_of_vertex(outfit);
  std::vector<char> chosen(static_cast<std::size_t>(outfit.num_vertices()), 0);
  const bool by_index = !piece_name.empty() && piece_name.find_first_not_of("0123456789") == std::string::npos;
  if (by_index) {
    std::vector<int> roots;  // pieces numbered by their first vertex
    for (int v = 0; v < outfit.num_vertices(); ++v)
      if (piece[static_cast<std::size_t>(v)] == v) roots.push_back(v);
    const std::size_t index = std::stoul(piece_name);
    if (index >= roots.size())
      throw ConfigError(obj.string() + ": has " + std::to_string(roots.size()) + " connected pieces (0-" +
                        std::to_string(roots.size() - 1) + "), no piece " + piece_name);
    for (int v = 0; v < outfit.num_vertices(); ++v) chosen[static_cast<std::size_t>(v)] = piece[static_cast<std::size_t>(v)] == roots[index];
  } else {
    for (int v : group_vertices(outfit, piece_name, obj.string())) chosen[static_cast<std::size_t>(v)] = 1;
  }
  std::vector<int> new_index(static_cast<std::size_t>(outfit.num_vertices()), -1);
  std::vector<int> kept;
  for (int v = 0; v < outfit.num_vertices(); ++v)
    if (chosen[static_cast<std::size_t>(v)]) new_index[static_cast<std::size_t>(v)] = static_cast<int>(kept.size()), kept.push_back(v);

  const Eigen::MatrixX3d fitted = model.to_body_frame(fit_clothes(binding, morphed), morphed);
  Garment g;
  g.mesh.vertices.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i) g.mesh.vertices.row(static_cast<Eigen::Index>(i)) = fitted.row(kept[i]);
  std::vector<Eigen::Vector3i> faces, uv_faces;
  std::vector<Eigen::Vector3i> outfit_faces;  // the same faces in the outfit's numbering, for the rest shape
  for (int f = 0; f < outfit.num_faces(); ++f) {
    const int s = outfit.face_start[static_cast<std::size_t>(f)];
    if (!chosen[static_cast<std::size_t>(outfit.corner_vertex[static_cast<std::size_t>(s)])]) continue;
    for (int k = 1; k + 1 < outfit.face_size(f); ++k) {
      const std::size_t c[3] = {static_cast<std::size_t>(s), static_cast<std::size_t>(s + k), static_cast<std::size_t>(s + k + 1)};
      const Eigen::Vector3i of(outfit.corner_vertex[c[0]], outfit.corner_vertex[c[1]], outfit.corner_vertex[c[2]]);
      outfit_faces.push_back(of);
      faces.emplace_back(new_index[static_cast<std::size_t>(of[0])], new_index[static_cast<std::size_t>(of[1])],
                         new_index[static_cast<std::size_t>(of[2])]);
      uv_faces.emplace_back(outfit.corner_uv[c[0]], outfit.corner_uv[c[1]], outfit.corner_uv[c[2]]);
    }
  }
  if (faces.empty()) throw ConfigError(obj.string() + ": piece " + piece_name + " has no faces");
  g.mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  g.mesh.uv_faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    g.mesh.faces.row(static_cast<Eigen::Index>(i)) = faces[i].transpose();
    g.mesh.uv_faces.row(static_cast<Eigen::Index>(i)) = uv_faces[i].transpose();
  }
  // Texture UVs are in [0,1]; material space must be in meters. One uniform
  // scale makes the total UV area equal the 3D area of the piece as fitted to
  // the default body, so the garment starts near its rest size.
  const Eigen::MatrixX3d default_body = model.morph(Sliders{});
  const Eigen::MatrixX3d rest = model.to_body_frame(fit_clothes(binding, default_body), default_body);
  double area3 = 0, area_uv = 0;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const auto& f = outfit_faces[i];
    area3 += 0.5 * (rest.row(f[1]) - rest.row(f[0])).cross(rest.row(f[2]) - rest.row(f[0])).norm();
    const auto& t = uv_faces[i];
    area_uv += area2d(outfit.uv.row(t[0]), outfit.uv.row(t[1]), outfit.uv.row(t[2]));
  }
  if (area_uv <= 0) throw ConfigError(obj.string() + ": piece " + piece_name + "'s UV layout has zero area");
  g.mesh.uv = outfit.uv * std::sqrt(area3 / area_uv);
  Material knit;
  knit.name = "knit";
  g.materials = {knit};
  return g;
}

}  // namespace drape::makehuman
