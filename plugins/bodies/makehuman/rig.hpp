#pragma once
// MakeHuman's rig as drape's skeleton (docs/poses.md, "MakeHuman's rig"):
// one drape joint per MakeHuman bone, turning about the bone's head, parents
// before children; skinning weights on the kept skin vertices; and the bone
// heads of any skin mesh of this topology (not only of a shape: also the
// morph between two shapes a drape's body takes), found as MakeHuman finds
// them on the mesh the macro targets would make of it.
#include "rig_files.hpp"
#include "targets.hpp"

#include <drape/bodies/body.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace drape::makehuman {

struct Rig {
  std::vector<BodyModel::Joint> joints;  // one per MakeHuman bone, named as MakeHuman names it
  // MakeHuman's own position of each bone head: the mean of these base-mesh
  // vertices (helper joint cubes, or skin vertices) of the morphed mesh.
  std::vector<std::vector<int>> head_vertices;
  // The skin in meters is 0.1 (base + offsets w) + translation for a body
  // the targets make (w: each target's weight): `skin_basis` holds 0.1
  // times each target's skin offsets and the three unit translations, one
  // column each, row 3 v + axis, factored for least squares; the bone heads
  // in the same columns are `head_basis` (rows 3 b + axis) over `head_base`.
  Eigen::MatrixXd skin_basis, head_basis;
  Eigen::VectorXd skin_base, head_base;
  Eigen::LDLT<Eigen::MatrixXd> skin_normal;
  Eigen::MatrixXd weights;  // skin vertices x bones, rows summing to 1
  int dropped_weights = 0;  // weight entries on helper vertices (not skin), left out
  int index(const std::string& bone) const;  // Error when the rig has no such bone
};

// `base`: the raw base mesh (every vertex, MakeHuman units); its first
// `skin_vertices` rows are the skin (the `body` group); `targets`: the macro
// targets that make every MakeHuman body. `angles_of` gives each
// bone's pose angles (empty for a bone no angle turns).
Rig build_rig(const RigFiles& files, const Eigen::MatrixX3d& base, int skin_vertices, const std::vector<Target>& targets,
              const std::function<std::vector<std::string>(const std::string& bone)>& angles_of);

// Bone heads of a skin mesh (skin_vertices x 3, meters, placed anywhere),
// one row per joint: the targets' weights and the translation that make the
// mesh nearest `skin` (least squares over every skin vertex), then the bone
// heads of the full mesh they make, helper joint cubes included. Exactly
// MakeHuman's joints (to rounding) for a body of the targets, and linear in
// `skin`, so a morph between two bodies moves the joints between theirs.
Eigen::MatrixX3d regress_joints(const Rig& rig, const Eigen::MatrixX3d& skin);
// MakeHuman's own bone heads: means of their vertex groups in a full morphed mesh (helpers included).
Eigen::MatrixX3d group_joints(const Rig& rig, const Eigen::MatrixX3d& all_vertices);

}  // namespace drape::makehuman
