#include "model.hpp"
#include "rig_pose.hpp"

#include <drape/errors.hpp>
#include <drape/io/mesh_io.hpp>

namespace fs = std::filesystem;

namespace drape::makehuman {

Model::Model(const fs::path& root) : root_(root) {
  const fs::path obj = root / "base" / "base.obj";
  if (!fs::exists(obj))
    throw ConfigError("MakeHuman data not found: '" + obj.string() + "' is missing (point `path` at a MakeHuman folder "
                      "with base/base.obj and targets/macrodetails/)");
  const PolygonMesh poly = read_obj_polygons(obj);
  base_ = poly.vertices;
  // The skin surface is the `body` group; every helper (eyes, teeth, tights,
  // joint cubes) is dropped from the body mesh but still morphed for clothes.
  const std::vector<int> body = group_vertices(poly, "body", obj.string());
  body_vertices_ = static_cast<int>(body.size());
  if (body.empty() || body.back() != body_vertices_ - 1)
    throw ConfigError(obj.string() + ": the `body` group must use vertices 0.." + std::to_string(body_vertices_ - 1) +
                      " (hm08 layout)");
  int body_group = -1;
  for (std::size_t g = 0; g < poly.group_names.size(); ++g)
    if (poly.group_names[g] == "body") body_group = static_cast<int>(g);
  std::vector<Eigen::Vector3i> tris;
  for (int f = 0; f < poly.num_faces(); ++f) {
    if (poly.face_group[static_cast<std::size_t>(f)] != body_group) continue;
    const int s = poly.face_start[static_cast<std::size_t>(f)];
    for (int k = 1; k + 1 < poly.face_size(f); ++k)
      tris.emplace_back(poly.corner_vertex[static_cast<std::size_t>(s)], poly.corner_vertex[static_cast<std::size_t>(s + k)],
                        poly.corner_vertex[static_cast<std::size_t>(s + k + 1)]);
  }
  body_faces_.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (std::size_t i = 0; i < tris.size(); ++i) body_faces_.row(static_cast<Eigen::Index>(i)) = tris[i].transpose();
  targets_ = load_macro_targets(root);
  rig_missing_ = missing_rig_files(root);
}

const Rig& Model::rig() const {
  if (!rig_missing_.empty()) throw ConfigError(rig_missing_);
  // Reading the weights and fitting the joints costs about a second: only a
  // posed body pays it, once per folder.
  std::call_once(rig_once_, [&] {
    rig_ = build_rig(read_rig_files(root_, static_cast<int>(base_.rows())), base_, body_vertices_, targets_, angles_of_bone);
  });
  return *rig_;
}

Eigen::MatrixX3d Model::morph(const Sliders& sliders) const { return apply_targets(base_, targets_, sliders); }

Eigen::MatrixX3d Model::to_body_frame(const Eigen::MatrixX3d& raw, const Eigen::MatrixX3d& morphed) const {
  // Meters, and feet on the ground: the lowest body vertex of this body at y = 0.
  const double ground = morphed.topRows(body_vertices_).col(1).minCoeff();
  Eigen::MatrixX3d out = raw * kMetersPerUnit;
  out.col(1).array() -= ground * kMetersPerUnit;
  return out;
}

Mesh Model::body(const Sliders& sliders) const {
  const Eigen::MatrixX3d all = morph(sliders);
  Mesh m;
  m.vertices = to_body_frame(all.topRows(body_vertices_), all);
  m.faces = body_faces_;
  return m;
}

}  // namespace drape::makehuman
