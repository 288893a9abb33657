// Body-to-garment correspondences and surface attachments on small examples.
#include "reference.hpp"

#include <drape/geometry/body_correspondence.hpp>
#include <drape/geometry/closed_shapes.hpp>

#include <catch2/catch.hpp>

#include <random>

using drape::Mesh;
using namespace drape::geometry;

namespace {

// A "garment" of points around the body at various offsets, some inside.
Mesh shell_around(const Mesh& body, int count, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  std::uniform_int_distribution<int> face(0, body.num_faces() - 1);
  Mesh g;
  g.vertices.resize(count, 3);
  for (int i = 0; i < count; ++i) {
    const int f = face(rng);
    double u = unit(rng), v = unit(rng);
    if (u + v > 1) u = 1 - u, v = 1 - v;
    const Eigen::Vector3d a = body.vertices.row(body.faces(f, 0)), b = body.vertices.row(body.faces(f, 1)),
                          c = body.vertices.row(body.faces(f, 2));
    const Eigen::Vector3d on = a + u * (b - a) + v * (c - a);
    g.vertices.row(i) = on * (1 + 0.1 * (unit(rng) - 0.3));
  }
  return g;
}

}  // namespace

TEST_CASE("correspondence: the body vertex nearest each garment vertex's closest body point") {
  std::mt19937 rng(29);
  Mesh body = torus(1.0, 0.3, 16, 8);
  // Stretch it so faces become obtuse: there the nearest vertex is not always a corner of the closest face.
  body.vertices.col(0) *= 2.5;
  const Mesh garment = shell_around(body, 400, rng);
  const std::vector<int> corr = body_to_garment_correspondence(body, garment);
  REQUIRE(corr.size() == 400u);
  const SurfaceAttachment attachment = attach_to_surface(body, garment.vertices);
  const Eigen::MatrixX3d c = attached_points(body.vertices, body.faces, attachment);
  int not_a_corner = 0;
  for (int i = 0; i < garment.num_vertices(); ++i) {
    // c is the closest surface point (checked against exhaustive search)...
    const Eigen::Vector3d p = garment.vertices.row(i);
    CHECK((p - c.row(i).transpose()).norm() == Approx(drape::test::mesh_distance(body, p)).margin(1e-12));
    // ...and the chosen vertex is at least as close to c as every body vertex.
    const double chosen = (body.vertices.row(corr[i]) - c.row(i)).norm();
    const double nearest = (body.vertices.rowwise() - c.row(i)).rowwise().norm().minCoeff();
    CHECK(chosen == nearest);
    const int f = attachment.face[i];
    not_a_corner += corr[i] != body.faces(f, 0) && corr[i] != body.faces(f, 1) && corr[i] != body.faces(f, 2);
  }
  CHECK(not_a_corner > 0);  // the example really exercises the non-corner case
}

TEST_CASE("correspondence on a hand-made example") {
  // Points straight above the face centroids of an icosahedron:
  // the closest point is the centroid, the nearest vertex one of its corners.
  const Mesh body = icosphere(0);
  Mesh garment;
  garment.vertices.resize(body.num_faces(), 3);
  for (int f = 0; f < body.num_faces(); ++f) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) centroid += body.vertices.row(body.faces(f, k)).transpose() / 3;
    garment.vertices.row(f) = 1.2 * centroid;
  }
  const std::vector<int> corr = body_to_garment_correspondence(body, garment);
  const SurfaceAttachment attachment = attach_to_surface(body, garment.vertices);
  for (int f = 0; f < body.num_faces(); ++f) {
    CHECK(attachment.face[f] == f);
    CHECK((attachment.barycentric.row(f) - Eigen::RowVector3d::Constant(1.0 / 3)).norm() < 1e-12);
    CHECK((corr[f] == body.faces(f, 0) || corr[f] == body.faces(f, 1) || corr[f] == body.faces(f, 2)));
  }
}

TEST_CASE("attachments follow a body of another shape") {
  std::mt19937 rng(31);
  const Mesh body = icosphere(2);
  const Mesh garment = shell_around(body, 200, rng);
  const SurfaceAttachment attachment = attach_to_surface(body, garment.vertices);
  // Barycentric weights are affine-invariant: on a scaled, shifted body the
  // attached points are the scaled, shifted closest points.
  Eigen::MatrixX3d other = body.vertices;
  other.col(1) *= 1.7;
  other.rowwise() += Eigen::RowVector3d(0.1, -0.2, 0.3);
  Eigen::MatrixX3d expected = attached_points(body.vertices, body.faces, attachment);
  expected.col(1) *= 1.7;
  expected.rowwise() += Eigen::RowVector3d(0.1, -0.2, 0.3);
  CHECK((attached_points(other, body.faces, attachment) - expected).cwiseAbs().maxCoeff() < 1e-12);
  SurfaceAttachment broken = attachment;
  broken.face[5] = body.num_faces();
  CHECK_THROWS_WITH(attached_points(body.vertices, body.faces, broken), Catch::Contains("point 5"));
  CHECK_THROWS_WITH(body_to_garment_correspondence(body, Mesh{}), Catch::Contains("no vertices"));
}
