// Assets with an encoder body (AssetsSpec::encoder_body; docs/bodies.md, "One
// encoder for both rigs"): the human rig's template with the mannequin's
// vertices for the encoder.
#include <drape/assets/assets.hpp>
#include <drape/assets/weight_ties.hpp>
#include <drape/training/model.hpp>

#include <catch2/catch.hpp>

#include "test_support.hpp"

#include <algorithm>
#include <vector>

using namespace drape;

namespace {

AssetsSpec human_spec(const std::string& encoder_body) {
  AssetsSpec s;
  s.body_params["rig"] = "human";
  s.garment_params["resolution"] = "coarse";
  s.eigen_k = 8;
  s.levels = 2;
  s.encoder_body = encoder_body;
  return s;
}

}  // namespace

TEST_CASE("an assets spec without an encoder body keeps its text, one with it reads back", "[assets]") {
  AssetsSpec plain = human_spec("");
  // The text every cache key and model file before the encoder body was made from, unchanged.
  CHECK(plain.yaml() ==
        "body: { model: parametric, params: { rig: human, } }\ngarment: { template: tshirt, params: { resolution: coarse, "
        "} }\nlevels: 2\neigen_k: 8\n");
  const AssetsSpec with = human_spec("parametric");
  CHECK(with.yaml() == plain.yaml() + "encoder_body: { model: parametric, params: { } }\n");
  const AssetsSpec back = parse_assets_spec(with.yaml(), "test");
  CHECK(back.encoder_body == "parametric");
  CHECK(back.yaml() == with.yaml());
  CHECK(parse_assets_spec(plain.yaml(), "test").encoder_body.empty());
}

TEST_CASE("the human rig's assets read at the mannequin's vertices for the encoder", "[assets]") {
  test::TempDir dir;
  const auto human = build_assets(test::plugins(), human_spec("parametric"), dir.path());
  AssetsSpec mannequin_spec = human_spec("");
  mannequin_spec.body_params.clear();
  const auto mannequin = build_assets(test::plugins(), mannequin_spec, dir.path());
  const int ne = mannequin->body.num_vertices(), nb = human->body.num_vertices();
  REQUIRE(ne != nb);  // two topologies: 6,490 and 6,904 vertices
  REQUIRE(human->encoder_resampling.size() == ne);
  REQUIRE(human->encoder_resampling.resampled_template.rows() == ne);
  // Each encoder point is the human template at a face's barycentric point ...
  for (int i = 0; i < ne; i += 97) {
    const int f = human->encoder_resampling.attachment.face[i];
    REQUIRE(f >= 0);
    REQUIRE(f < human->body.faces.rows());
    const Eigen::Vector3d w = human->encoder_resampling.attachment.barycentric.row(i).transpose();
    CHECK(w.minCoeff() >= -1e-12);
    CHECK(w.sum() == Approx(1.0));
    Eigen::RowVector3d p = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 3; ++k) p += w[k] * human->body.vertices.row(human->body.faces(f, k));
    CHECK((p - human->encoder_resampling.resampled_template.row(i)).norm() < 1e-12);
  }
  // ... near the mannequin's template vertex of the same index (the two mean bodies differ by millimetres on the
  // torso, up to centimetres at the head, hands and feet).
  std::vector<double> gap(static_cast<std::size_t>(ne));
  for (int i = 0; i < ne; ++i) gap[static_cast<std::size_t>(i)] = (human->encoder_resampling.resampled_template.row(i) - mannequin->body.vertices.row(i)).norm();
  std::nth_element(gap.begin(), gap.begin() + ne / 2, gap.end());
  CHECK(gap[static_cast<std::size_t>(ne / 2)] < 0.003);
  CHECK(*std::max_element(gap.begin(), gap.end()) < 0.05);
  // The correspondences index the encoder's points: each garment vertex reads one within a few centimetres.
  REQUIRE(human->correspondence.size() == static_cast<std::size_t>(human->garment->mesh.num_vertices()));
  for (std::size_t g = 0; g < human->correspondence.size(); ++g) {
    const int c = human->correspondence[g];
    REQUIRE(c >= 0);
    REQUIRE(c < ne);
    CHECK((human->encoder_resampling.resampled_template.row(c) - human->garment->mesh.vertices.row(static_cast<Eigen::Index>(g))).norm() < 0.12);
  }
  // Everything a network's weights are tied to is the encoder body's own assets', bit for bit: the
  // correspondences (into its vertices, which the encoder's points resample), the hierarchy and the
  // eigenbasis (on the garment dressed on the human rig the eigenvectors differ past the first few).
  CHECK(human->correspondence == mannequin->correspondence);
  REQUIRE(human->hierarchy.levels.size() == mannequin->hierarchy.levels.size());
  for (std::size_t l = 0; l < human->hierarchy.levels.size(); ++l) {
    CHECK(human->hierarchy.levels[l].mesh.faces == mannequin->hierarchy.levels[l].mesh.faces);
    CHECK(human->hierarchy.levels[l].mesh.vertices == mannequin->hierarchy.levels[l].mesh.vertices);
  }
  CHECK(human->eigenvalues == mannequin->eigenvalues);
  CHECK(human->eigenvectors == mannequin->eigenvectors);
  // The garment itself (its template, the losses' rest shape) is the one dressed on the human rig.
  CHECK((human->garment->mesh.vertices - mannequin->garment->mesh.vertices).norm() > 1e-3);
  // Without the encoder body the same template has no resampling and its own vertices' correspondences.
  AssetsSpec own = human_spec("");
  const auto plain = build_assets(test::plugins(), own, dir.path());
  CHECK(plain->encoder_resampling.size() == 0);
  CHECK(plain->hash != human->hash);

  // What drape train --init compares (weight_ties.hpp): nothing differs between the mannequin's assets
  // and the human rig's with the mannequin as encoder body; the human rig's own assets differ first in
  // what the correspondences index. (These 8 eigenvectors, the lowest modes, are alike on both
  // garments; the shipped graph's 1000 are not: tests/python/test_encoder_body.py.)
  CHECK(weight_ties_differ(*mannequin, *human).empty());
  const std::vector<std::string> differ = weight_ties_differ(*mannequin, *plain);
  REQUIRE_FALSE(differ.empty());
  CHECK(differ[0] == "the correspondences index " + std::to_string(ne) + " body points there and " +
                         std::to_string(nb) + " here");
}

// weight_ties_differ on assets changed by hand: one correspondence, one eigenvector flipped (the same
// vector: not counted) and one turned into another, a hierarchy level's faces.
TEST_CASE("weight ties: each difference named and counted", "[assets]") {
  test::TempDir dir;
  AssetsSpec spec = human_spec("");
  spec.body_params.clear();
  const auto a = build_assets(test::plugins(), spec, dir.path());
  Assets b = *a;
  CHECK(weight_ties_differ(*a, b).empty());
  b.eigenvectors.col(3) *= -1.0f;  // a flipped sign is the same eigenvector
  CHECK(weight_ties_differ(*a, b).empty());
  b.correspondence[17] = b.correspondence[17] + 1;
  b.eigenvectors.col(5).swap(b.eigenvectors.col(6));  // two others (orthogonal to what they replace)
  std::swap(b.hierarchy.levels[1].mesh.faces(0, 0), b.hierarchy.levels[1].mesh.faces(0, 1));
  const std::vector<std::string> differ = weight_ties_differ(*a, b);
  REQUIRE(differ.size() == 3);
  CHECK(differ[0] == "1 of " + std::to_string(a->correspondence.size()) + " garment vertices read another body point");
  CHECK(differ[1] == "the hierarchy's level 1 clusters the garment otherwise");
  CHECK(differ[2].rfind("2 of 8 eigenvectors are others (|cos| below 0.9, the first at 5)", 0) == 0);
}
