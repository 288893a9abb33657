#pragma once
// A mesh's left-right mirror map: where each vertex's reflection through the
// plane x = 0 lies on the mesh's own surface (a face and barycentric weights).
// A garment meshed panel by panel is symmetric in shape but not in its
// vertices, so a drape is mirrored vertex by vertex through its surface: the
// mirrored drape's vertex i is the reflection of the drape's point at the
// weights of row i (test-time mirror averaging, docs/poses.md; the same map
// scripts/mirror_dataset.py makes in numpy for the mirrored training drapes).
#include <Eigen/Core>

namespace drape::geometry {

struct MirrorMap {
  Eigen::MatrixX3i corners;  // [N, 3]: the face each reflected vertex lies on
  Eigen::MatrixX3d weights;  // [N, 3]: its barycentric weights there
  Eigen::VectorXd distance;  // [N]: how far the reflected vertex lies off the surface (the mesh's asymmetry)
};

// The map of a mesh as it stands (the garment's template dressed on the mean
// body, which is symmetric about x = 0). Error for a mesh without faces.
MirrorMap mirror_map(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);

// The reflection of `x` (a drape of the mesh's topology, [N, 3]) read
// through the map: row i is (-1, 1, 1) * sum_k weights(i, k) * x(corners(i, k)).
Eigen::MatrixX3d mirrored(const MirrorMap& map, const Eigen::MatrixX3d& x);

// The adjoint of mirrored(): for g, a gradient with respect to mirrored(map,
// x), the gradient with respect to x ([n, 3]): each row g_i, reflected,
// scattered to the corners of row i by its weights. sum(g .* mirrored(x))
// equals sum(mirrored_adjoint(g) .* x) for every x.
Eigen::MatrixX3d mirrored_adjoint(const MirrorMap& map, const Eigen::MatrixX3d& g, Eigen::Index n);

}  // namespace drape::geometry
