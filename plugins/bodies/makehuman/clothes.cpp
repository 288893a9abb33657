#include "clothes.hpp"

#include <drape/errors.hpp>
#include <drape/io/mesh_io.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <numeric>
#include <system_error>
#include <sstream>
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

namespace {

// The names in "0,1" or "shirt, trousers" (one piece: "0").
std::vector<std::string> piece_names(const std::string& text, const fs::path& obj) {
  std::vector<std::string> names;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) {
    const auto a = part.find_first_not_of(" \t"), b = part.find_last_not_of(" \t");
    if (a == std::string::npos) throw ConfigError(obj.string() + ": piece '" + text + "' names an empty piece");
    names.push_back(part.substr(a, b - a + 1));
  }
  if (names.empty()) throw ConfigError(obj.string() + ": no piece named");
  return names;
}

// Per outfit vertex: which of the named pieces it belongs to (-1: none). A
// piece is an index among the connected pieces (numbered by their first
// vertex) or an OBJ group; a vertex named twice is refused.
std::vector<int> part_of_vertex(const PolygonMesh& outfit, const std::vector<std::string>& names, const fs::path& obj) {
  const std::vector<int> piece = piece_of_vertex(outfit);
  std::vector<int> roots;  // connected pieces numbered by their first vertex
  for (int v = 0; v < outfit.num_vertices(); ++v)
    if (piece[static_cast<std::size_t>(v)] == v) roots.push_back(v);
  std::vector<int> part(static_cast<std::size_t>(outfit.num_vertices()), -1);
  const auto take = [&](int v, int k) {
    int& p = part[static_cast<std::size_t>(v)];
    if (p >= 0 && p != k)
      throw ConfigError(obj.string() + ": pieces " + names[static_cast<std::size_t>(p)] + " and " +
                        names[static_cast<std::size_t>(k)] + " share vertex " + std::to_string(v));
    p = k;
  };
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string& name = names[k];
    if (name.find_first_not_of("0123456789") == std::string::npos) {
      const std::size_t index = std::stoul(name);
      if (index >= roots.size())
        throw ConfigError(obj.string() + ": has " + std::to_string(roots.size()) + " connected pieces (0-" +
                          std::to_string(roots.size() - 1) + "), no piece " + name);
      for (int v = 0; v < outfit.num_vertices(); ++v)
        if (piece[static_cast<std::size_t>(v)] == roots[index]) take(v, static_cast<int>(k));
    } else {
      for (int v : group_vertices(outfit, name, obj.string())) take(v, static_cast<int>(k));
    }
  }
  return part;
}

// An outfit folder that is not there: the outfits that are, and the close
// ones first (a misspelled name otherwise reads as a missing .obj).
void require_outfit(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_directory(dir, ec)) return;
  const fs::path clothes = dir.parent_path();
  std::vector<std::string> outfits;
  for (const fs::directory_entry& e : fs::directory_iterator(clothes, ec))
    if (e.is_directory(ec)) outfits.push_back(e.path().filename().string());
  std::sort(outfits.begin(), outfits.end());
  std::string text = "no MakeHuman outfit '" + dir.filename().string() + "' in " + clothes.string();
  if (outfits.empty()) throw ConfigError(text + " (the folder has no outfits" + (ec ? ": " + ec.message() : std::string()) + ")");
  text += " (its outfits:";
  for (const std::string& o : outfits) text += " " + o;
  throw ConfigError(text + ")" + did_you_mean(dir.filename().string(), outfits));
}

}  // namespace

Garment load_clothes(const Model& model, const fs::path& dir, const Sliders& body, const std::string& piece_text) {
  require_outfit(dir);
  const std::string name = dir.filename().string();
  const fs::path obj = dir / (name + ".obj"), clo = dir / (name + ".mhclo");
  const PolygonMesh outfit = read_obj_polygons(obj);
  const ClothesBinding binding = read_mhclo(clo);
  if (static_cast<int>(binding.refs.size()) != outfit.num_vertices())
    throw ConfigError(clo.string() + " binds " + std::to_string(binding.refs.size()) + " vertices but " + obj.string() +
                      " has " + std::to_string(outfit.num_vertices()));
  if (outfit.corner_uv.empty()) throw ConfigError(obj.string() + ": the garment needs UVs (its material space)");
  const Eigen::MatrixX3d morphed = model.morph(body);

  // The pieces' vertices, in the outfit's order.
  const std::vector<std::string> names = piece_names(piece_text, obj);
  const std::vector<int> part = part_of_vertex(outfit, names, obj);
  std::vector<int> new_index(static_cast<std::size_t>(outfit.num_vertices()), -1);
  std::vector<int> kept;
  for (int v = 0; v < outfit.num_vertices(); ++v)
    if (part[static_cast<std::size_t>(v)] >= 0) new_index[static_cast<std::size_t>(v)] = static_cast<int>(kept.size()), kept.push_back(v);

  const Eigen::MatrixX3d fitted = model.to_body_frame(fit_clothes(binding, morphed), morphed);
  Garment g;
  g.body_model = "makehuman";  // the .mhclo binds it to MakeHuman's body (the plugin's body name)
  g.mesh.vertices.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i) g.mesh.vertices.row(static_cast<Eigen::Index>(i)) = fitted.row(kept[i]);
  std::vector<Eigen::Vector3i> faces, uv_faces;
  std::vector<Eigen::Vector3i> outfit_faces;  // the same faces in the outfit's numbering, for the rest shape
  std::vector<int> face_part;
  for (int f = 0; f < outfit.num_faces(); ++f) {
    const int s = outfit.face_start[static_cast<std::size_t>(f)];
    const int k_part = part[static_cast<std::size_t>(outfit.corner_vertex[static_cast<std::size_t>(s)])];
    if (k_part < 0) continue;
    for (int k = 1; k + 1 < outfit.face_size(f); ++k) {
      const std::size_t c[3] = {static_cast<std::size_t>(s), static_cast<std::size_t>(s + k), static_cast<std::size_t>(s + k + 1)};
      const Eigen::Vector3i of(outfit.corner_vertex[c[0]], outfit.corner_vertex[c[1]], outfit.corner_vertex[c[2]]);
      outfit_faces.push_back(of);
      faces.emplace_back(new_index[static_cast<std::size_t>(of[0])], new_index[static_cast<std::size_t>(of[1])],
                         new_index[static_cast<std::size_t>(of[2])]);
      uv_faces.emplace_back(outfit.corner_uv[c[0]], outfit.corner_uv[c[1]], outfit.corner_uv[c[2]]);
      face_part.push_back(k_part);
    }
  }
  if (faces.empty()) throw ConfigError(obj.string() + ": piece " + piece_text + " has no faces");
  g.mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  g.mesh.uv_faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    g.mesh.faces.row(static_cast<Eigen::Index>(i)) = faces[i].transpose();
    g.mesh.uv_faces.row(static_cast<Eigen::Index>(i)) = uv_faces[i].transpose();
  }
  // Texture UVs are in [0,1]; material space must be in meters. One uniform
  // scale per piece makes its UV area equal the 3D area of the piece as
  // fitted to the default body, so the garment starts near its rest size.
  // Each piece gets UV rows of its own: pieces of an outfit share one texture
  // atlas, but not one scale.
  const Eigen::MatrixX3d default_body = model.morph(Sliders{});
  const Eigen::MatrixX3d rest = model.to_body_frame(fit_clothes(binding, default_body), default_body);
  const std::size_t parts = names.size();
  std::vector<double> area3(parts, 0.0), area_uv(parts, 0.0);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const auto& f = outfit_faces[i];
    const std::size_t k = static_cast<std::size_t>(face_part[i]);
    area3[k] += 0.5 * (rest.row(f[1]) - rest.row(f[0])).cross(rest.row(f[2]) - rest.row(f[0])).norm();
    const auto& t = uv_faces[i];
    area_uv[k] += area2d(outfit.uv.row(t[0]), outfit.uv.row(t[1]), outfit.uv.row(t[2]));
  }
  const Eigen::Index n_uv = outfit.uv.rows();
  g.mesh.uv.resize(n_uv * static_cast<Eigen::Index>(parts), 2);
  for (std::size_t k = 0; k < parts; ++k) {
    if (area_uv[k] <= 0) throw ConfigError(obj.string() + ": piece " + names[k] + "'s UV layout has zero area");
    g.mesh.uv.middleRows(static_cast<Eigen::Index>(k) * n_uv, n_uv) = outfit.uv * std::sqrt(area3[k] / area_uv[k]);
  }
  for (std::size_t i = 0; i < faces.size(); ++i)
    g.mesh.uv_faces.row(static_cast<Eigen::Index>(i)).array() += face_part[i] * static_cast<int>(n_uv);
  // One piece: one material, "knit". Several: a region per piece, named
  // "piece<index>" or by its group, each given a fabric in the scene's materials.
  if (parts == 1) {
    Material knit;
    knit.name = "knit";
    g.materials = {knit};
    return g;
  }
  for (const std::string& n : names) {
    Material m;
    m.name = n.find_first_not_of("0123456789") == std::string::npos ? "piece" + n : n;
    g.materials.push_back(m);
  }
  g.face_material.resize(static_cast<Eigen::Index>(faces.size()));
  for (std::size_t i = 0; i < faces.size(); ++i) g.face_material[static_cast<Eigen::Index>(i)] = face_part[i];
  // Where MakeHuman fits pieces through each other (a shirt's hem through the
  // jeans' waistband), dressing lays them in layers (garment_layers.hpp).
  return g;
}

}  // namespace drape::makehuman
