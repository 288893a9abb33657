#pragma once
// A garment posed with the body it is dressed on, and a posed drape brought
// back into the body's rest pose: TailorNet's unposing (Patel et al. 2020),
// which the seed names for poses. The garment follows the body's joints with
// the skinning weights of the body surface it lies on; a network predicts the
// drape in the rest pose (canonical space), where drapes of one shape in many
// poses look alike, and skinning poses it (the `skin` node, docs/poses.md).
#include <drape/bodies/skinning.hpp>
#include <drape/mesh.hpp>
#include <drape/tensor.hpp>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace drape {

// Skinning weights of a garment, [garment vertices, joints], rows summing to
// 1: each garment vertex takes the weights of its closest point on `body`
// (the weights of that face's corners blended by its barycentric
// coordinates), then `smoothing` passes over the garment's edges each replace
// a vertex's weights by the mean of its own and its neighbours'. Why smooth:
// the closest point jumps where the garment spans a crease of the body (under
// the sleeve at the armpit the trunk is nearer than the arm), and weights
// that jump there tear the sleeve from the shirt when the arm turns. Both
// meshes in one space: the garment dressed on the (unposed) body.
Eigen::MatrixXd garment_skinning_weights(const Mesh& body, const Eigen::MatrixXd& body_weights, const Mesh& garment,
                                         int smoothing = 10);

// The canonical garment posed: x' = sum_b w_b (R_b x + t_b) per vertex
// (skinning::blend, so a pose of rest transforms gives it back bit for bit).
Eigen::MatrixX3d pose_garment(const Eigen::MatrixX3d& canonical, const Eigen::MatrixXd& weights,
                              const std::vector<skinning::Rigid>& transforms);
// Its inverse: each vertex through the inverse of its blended transform
// (sum_b w_b R_b, sum_b w_b t_b). Error when that matrix is singular (weights
// splitting a vertex between joints turned half a turn apart).
Eigen::MatrixX3d unpose_garment(const Eigen::MatrixX3d& posed, const Eigen::MatrixXd& weights,
                                const std::vector<skinning::Rigid>& transforms);

// The transforms as a network input, [joints, 12] floats per row: R row by
// row, then t (the graph input `joint_transforms`, the skin node's data).
MatrixRM transforms_rows(const std::vector<skinning::Rigid>& transforms);
// Its inverse for sample `sample` of a [n, joints, 12] tensor of them.
std::vector<skinning::Rigid> transforms_of_rows(const Tensor& rows, int sample);

// The garment's skinning as the network nodes hold it (`skin`,
// `skin_rotation`), in float: bound at setup and checked there once for
// both. ConfigError naming `node` when the template has no weights (an empty
// matrix: its body model has no skeleton, or no assets are bound) or
// `transforms` is not [joints, 12].
struct NodeSkinning {
  Eigen::MatrixXf weights;               // [garment vertices, joints]
  std::vector<std::vector<int>> joints;  // per vertex, the joints with a weight (dense but mostly zero)

  NodeSkinning() = default;
  NodeSkinning(const Eigen::MatrixXf& garment_skinning, const Shape& transforms, const std::string& node);

  // Vertex i's blend sum_b w_ib [R_b | t_b] of sample s's transform rows.
  Eigen::Matrix<float, 3, 4> blended(const Tensor& rows, int s, int i) const {
    Eigen::Matrix<float, 3, 4> m = Eigen::Matrix<float, 3, 4>::Zero();
    for (int b : joints[static_cast<std::size_t>(i)]) {
      const float w = weights(i, b);
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) m(r, c) += w * rows(s, b, 3 * r + c);
        m(r, 3) += w * rows(s, b, 9 + r);
      }
    }
    return m;
  }
};

}  // namespace drape
