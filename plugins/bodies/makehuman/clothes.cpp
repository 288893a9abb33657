#include "clothes.hpp"

#include <drape/errors.hpp>
#include <drape/mesh_io.hpp>

#include <Eigen/Geometry>

#include <numeric>

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

Garment load_tshirt(const Model& model, const fs::path& dir, const Sliders& body) {
  const std::string name = dir.filename().string();
  const fs::path obj = dir / (name + ".obj"), clo = dir / (name + ".mhclo");
  const PolygonMesh outfit = read_obj_polygons(obj);
  const ClothesBinding binding = read_mhclo(clo);
  if (static_cast<int>(binding.refs.size()) != outfit.num_vertices())
    throw ConfigError(clo.string() + " binds " + std::to_string(binding.refs.size()) + " vertices but " + obj.string() +
                      " has " + std::to_string(outfit.num_vertices()));
  if (outfit.corner_uv.empty()) throw ConfigError(obj.string() + ": the garment needs UVs (its material space)");

  // The shirt is the piece of vertex 0; MakeHuman outfits list it first, so its
  // vertices are a prefix 0..n-1 and the garment keeps the outfit's vertex order.
  const std::vector<int> piece = piece_of_vertex(outfit);
  int n = 0;
  while (n < outfit.num_vertices() && piece[static_cast<std::size_t>(n)] == piece[0]) ++n;
  for (int v = n; v < outfit.num_vertices(); ++v)
    if (piece[static_cast<std::size_t>(v)] == piece[0])
      throw ConfigError(obj.string() + ": the first piece (the T-shirt) does not occupy a prefix of the vertices");

  const Eigen::MatrixX3d morphed = model.morph(body);
  const Eigen::MatrixX3d fitted = model.to_body_frame(fit_clothes(binding, morphed), morphed);

  Garment g;
  g.mesh.vertices = fitted.topRows(n);
  std::vector<Eigen::Vector3i> faces, uv_faces;
  for (int f = 0; f < outfit.num_faces(); ++f) {
    const int s = outfit.face_start[static_cast<std::size_t>(f)];
    if (outfit.corner_vertex[static_cast<std::size_t>(s)] >= n) continue;
    for (int k = 1; k + 1 < outfit.face_size(f); ++k) {
      const std::size_t c[3] = {static_cast<std::size_t>(s), static_cast<std::size_t>(s + k), static_cast<std::size_t>(s + k + 1)};
      faces.emplace_back(outfit.corner_vertex[c[0]], outfit.corner_vertex[c[1]], outfit.corner_vertex[c[2]]);
      uv_faces.emplace_back(outfit.corner_uv[c[0]], outfit.corner_uv[c[1]], outfit.corner_uv[c[2]]);
    }
  }
  g.mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  g.mesh.uv_faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    g.mesh.faces.row(static_cast<Eigen::Index>(i)) = faces[i].transpose();
    g.mesh.uv_faces.row(static_cast<Eigen::Index>(i)) = uv_faces[i].transpose();
  }
  // Texture UVs are in [0,1]; material space must be in meters. One uniform
  // scale makes the total UV area equal the 3D area of the garment as fitted to
  // the default body, so the shirt starts near its rest size.
  const Eigen::MatrixX3d rest = model.to_body_frame(fit_clothes(binding, model.morph(Sliders{})), model.morph(Sliders{}));
  double area3 = 0, area_uv = 0;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const auto& f = faces[i];
    area3 += 0.5 * (rest.row(f[1]) - rest.row(f[0])).cross(rest.row(f[2]) - rest.row(f[0])).norm();
    const auto& t = uv_faces[i];
    area_uv += area2d(outfit.uv.row(t[0]), outfit.uv.row(t[1]), outfit.uv.row(t[2]));
  }
  if (area_uv <= 0) throw ConfigError(obj.string() + ": the T-shirt's UV layout has zero area");
  g.mesh.uv = outfit.uv * std::sqrt(area3 / area_uv);
  Material knit;
  knit.name = "knit";
  g.materials = {knit};
  return g;
}

}  // namespace drape::makehuman
