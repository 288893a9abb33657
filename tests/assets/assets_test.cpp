// The assets cache: everything precomputed for a template, built once, cached
// in HDF5 by a hash of the template and settings, identical when reloaded.
#include <drape/assets/assets.hpp>

#include <catch2/catch.hpp>

#include <fstream>

#include "test_support.hpp"

using namespace drape;

namespace {
AssetsSpec coarse_spec() {
  AssetsSpec s;
  s.garment_params["resolution"] = "coarse";
  s.eigen_k = 64;
  return s;
}
}  // namespace

TEST_CASE("assets hold the garment, body, correspondences, hierarchy, Laplacians and eigenbasis", "[assets]") {
  test::TempDir dir;
  AssetsTimings t;
  const auto a = build_assets(test::plugins(), coarse_spec(), dir.path(), &t);
  CHECK_FALSE(t.from_cache);
  const int ng = a->garment->mesh.num_vertices();
  const auto dims = a->dims();
  CHECK(dims.at("garment_vertices") == ng);
  CHECK(dims.at("body_vertices") == a->body.num_vertices());
  CHECK(dims.at("eigen_k") == 64);
  REQUIRE(a->hierarchy.num_levels() == 4);
  for (int l = 1; l < 4; ++l) {
    const double ratio = double(a->hierarchy.levels[l - 1].mesh.num_vertices()) / a->hierarchy.levels[l].mesh.num_vertices();
    INFO("level " << l << " ratio " << ratio);
    CHECK(ratio > 3.0);
    CHECK(ratio < 5.0);
    CHECK(dims.at("level" + std::to_string(l) + "_vertices") == a->hierarchy.levels[l].mesh.num_vertices());
  }
  REQUIRE(a->laplacians.size() == 4);
  for (const auto& L : a->laplacians) {
    const Eigen::VectorXf rows = L * Eigen::VectorXf::Ones(L.cols());
    CHECK(rows.cwiseAbs().maxCoeff() < 1e-5f);
  }
  REQUIRE(static_cast<int>(a->correspondence.size()) == ng);
  for (int c : a->correspondence) {
    CHECK(c >= 0);
    CHECK(c < a->body.num_vertices());
  }
  // Corresponding body vertices are near their garment vertices (the shirt sits on the torso).
  double worst = 0;
  for (int v = 0; v < ng; ++v)
    worst = std::max(worst, (a->garment->mesh.vertices.row(v) - a->body.vertices.row(a->correspondence[v])).norm());
  CHECK(worst < 0.2);
  CHECK(a->eigenvectors.rows() == ng);
  const Eigen::MatrixXd gram = a->eigenvectors.cast<double>().transpose() * a->eigenvectors.cast<double>();
  CHECK((gram - Eigen::MatrixXd::Identity(64, 64)).cwiseAbs().maxCoeff() < 1e-5);  // float storage
  for (Eigen::Index i = 1; i < a->eigenvalues.size(); ++i) CHECK(a->eigenvalues[i] >= a->eigenvalues[i - 1]);
}

TEST_CASE("the assets cache reloads identical data and is keyed by the settings", "[assets]") {
  test::TempDir dir;
  const auto built = build_assets(test::plugins(), coarse_spec(), dir.path());
  AssetsTimings t;
  const auto cached = build_assets(test::plugins(), coarse_spec(), dir.path(), &t);
  CHECK(t.from_cache);
  CHECK(cached->hash == built->hash);
  CHECK(cached->correspondence == built->correspondence);
  CHECK(cached->eigenvectors == built->eigenvectors);
  CHECK(cached->eigenvalues == built->eigenvalues);
  REQUIRE(cached->hierarchy.num_levels() == built->hierarchy.num_levels());
  for (int l = 0; l < 4; ++l) {
    const auto &x = cached->hierarchy.levels[l], &y = built->hierarchy.levels[l];
    CHECK(x.mesh.faces == y.mesh.faces);
    CHECK(x.fine_index == y.fine_index);
    CHECK(x.upsample.nonZeros() == y.upsample.nonZeros());
    if (y.upsample.nonZeros()) CHECK((Eigen::MatrixXf(x.upsample) - Eigen::MatrixXf(y.upsample)).cwiseAbs().maxCoeff() == 0.0f);
  }
  // Other settings, another key; a corrupt cache file is rebuilt, not trusted.
  AssetsSpec other = coarse_spec();
  other.eigen_k = 32;
  const auto rebuilt = build_assets(test::plugins(), other, dir.path(), &t);
  CHECK_FALSE(t.from_cache);
  CHECK(rebuilt->hash != built->hash);
  std::ofstream(dir / ("assets-" + built->hash + ".h5"), std::ios::trunc) << "garbage";
  const auto again = build_assets(test::plugins(), coarse_spec(), dir.path(), &t);
  CHECK_FALSE(t.from_cache);
  CHECK(again->eigenvectors == built->eigenvectors);
  CHECK(build_assets(test::plugins(), coarse_spec(), dir.path(), &t)->hash == built->hash);
  CHECK(t.from_cache);
}
