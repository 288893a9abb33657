#pragma once
// The MakeHuman body model read from a MakeHuman data folder (the CC0 assets in
// ../shared/assets/makehuman, or the user's own): base mesh hm08 + macro targets.
// Helper geometry (eyes, teeth, tights, joints, ...) is morphed along with the body
// (clothes bind to the tights helper) but only the `body` group is the body mesh.
#include "rig.hpp"
#include "targets.hpp"

#include <drape/mesh.hpp>

#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>

namespace drape::makehuman {

inline constexpr double kMetersPerUnit = 0.1;  // MakeHuman meshes are in decimetres

class Model {
 public:
  explicit Model(const std::filesystem::path& root);

  const std::filesystem::path& root() const { return root_; }
  // Every base vertex after the targets, in MakeHuman units (dm), helpers included.
  Eigen::MatrixX3d morph(const Sliders& sliders) const;
  // The body group as a triangle mesh in meters, Y up, feet at y = 0.
  Mesh body(const Sliders& sliders) const;
  // Same units and placement as body(): positions of a morphed base (raw dm) in meters.
  Eigen::MatrixX3d to_body_frame(const Eigen::MatrixX3d& raw_points, const Eigen::MatrixX3d& morphed_base) const;

  // MakeHuman's rig (rigs/default.mhskel and its weights, rig.hpp), read and
  // fitted on first use; ConfigError naming the missing files when the
  // folder has none (rig_missing() says so beforehand), or what is wrong
  // with them.
  const Rig& rig() const;
  const std::string& rig_missing() const { return rig_missing_; }

  int body_vertex_count() const { return body_vertices_; }
  const Eigen::MatrixX3i& body_faces() const { return body_faces_; }

 private:
  std::filesystem::path root_;
  Eigen::MatrixX3d base_;
  Eigen::MatrixX3i body_faces_;
  int body_vertices_ = 0;
  std::vector<Target> targets_;
  std::string rig_missing_;  // "" when the rig files are there
  mutable std::once_flag rig_once_;
  mutable std::optional<Rig> rig_;
};

}  // namespace drape::makehuman
