// A garment's skinning from the body it is dressed on: weights that are a
// partition of unity, posing that is linear blend skinning of the body's own
// joints (a "garment" that is the body itself, unsmoothed, poses exactly as
// the body model poses the body), and unposing that undoes posing.
#include <drape/bodies/body.hpp>
#include <drape/bodies/garment_skinning.hpp>

#include <catch2/catch.hpp>

#include "test_support.hpp"

using namespace drape;

namespace {

Pose test_pose() {
  Pose p;
  p.angles = {{"left_shoulder_abduction", 80}, {"right_elbow_flexion", 60}, {"spine_twist", 20}, {"left_knee_flexion", 30}};
  return p;
}

}  // namespace

TEST_CASE("a body's own surface as a garment poses exactly as the body does", "[pose][skinning]") {
  const auto model = test::parametric_body();
  const Eigen::VectorXd shape = model->solve({32, 1.68, 0.0, {}});
  Mesh body;
  body.vertices = model->vertices(shape);
  body.faces = model->faces();
  const Eigen::MatrixXd w = garment_skinning_weights(body, model->skinning_weights(), body, 0);
  // Each vertex's closest surface point is itself: its own weights, whichever face it is found on.
  CHECK((w - model->skinning_weights()).cwiseAbs().maxCoeff() < 1e-9);
  const auto transforms = model->joint_transforms(body.vertices, test_pose());
  REQUIRE(transforms.size() == model->joints().size());
  const Eigen::MatrixX3d posed = pose_garment(body.vertices, w, transforms);
  CHECK((posed - model->posed_vertices(body.vertices, test_pose(), 1.0)).cwiseAbs().maxCoeff() < 1e-9);
  // The left arm moved and the right foot did not.
  CHECK((posed - body.vertices).rowwise().norm().maxCoeff() > 0.2);
}

TEST_CASE("garment skinning weights are smooth partitions of unity and unposing undoes posing", "[pose][skinning]") {
  const auto model = test::parametric_body();
  const Eigen::VectorXd shape = model->mean_shape();
  Mesh body;
  body.vertices = model->vertices(shape);
  body.faces = model->faces();
  // A sleeve-like band of points around the left upper arm, 2 cm off its
  // surface: a garment made of a tube of the body's own faces pushed out.
  Mesh garment = body;
  Eigen::MatrixX3d normals = Eigen::MatrixX3d::Zero(body.vertices.rows(), 3);
  for (Eigen::Index f = 0; f < body.faces.rows(); ++f) {
    const Eigen::Vector3d a = body.vertices.row(body.faces(f, 0)), b = body.vertices.row(body.faces(f, 1)),
                          c = body.vertices.row(body.faces(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) normals.row(body.faces(f, k)) += n.transpose();
  }
  garment.vertices = body.vertices + 0.02 * normals.rowwise().normalized();
  const Eigen::MatrixXd w = garment_skinning_weights(body, model->skinning_weights(), garment, 10);
  CHECK((w.rowwise().sum().array() - 1.0).abs().maxCoeff() < 1e-12);
  CHECK(w.minCoeff() >= 0.0);
  const auto transforms = model->joint_transforms(body.vertices, test_pose());
  const Eigen::MatrixX3d posed = pose_garment(garment.vertices, w, transforms);
  CHECK((unpose_garment(posed, w, transforms) - garment.vertices).cwiseAbs().maxCoeff() < 1e-9);
  // The rest pose's transforms are the identity: posing changes nothing.
  const auto rest = model->joint_transforms(body.vertices, model->rest_pose(shape));
  CHECK((pose_garment(garment.vertices, w, rest) - garment.vertices).cwiseAbs().maxCoeff() < 1e-9);
  // The skinned garment follows the body: each vertex stays within a few
  // centimetres of where the posed body surface carries its closest point.
  const Eigen::MatrixX3d body_posed = model->posed_vertices(body.vertices, test_pose(), 1.0);
  const Eigen::VectorXd moved = (posed - body_posed).rowwise().norm();
  CHECK(moved.mean() < 0.03);
}

TEST_CASE("a body model without a skeleton gives no joint transforms", "[pose][skinning]") {
  const auto model = test::skeletonless_body();
  CHECK_THROWS_AS(model->joint_transforms(model->vertices(model->mean_shape()), test_pose()), ConfigError);
}
