// SMPL posed by θ: the plugin's posed bodies against SMPL's published
// equations (Loper et al. 2015, eqs. 1-4 and 9-10) written out here with 4x4
// matrices, on a small synthetic model file with SMPL's 24-joint tree and
// seeded random regressor, weights and pose blend shapes; the rest and the
// ends of the way into a pose; SMPL's θ from text and .npy files; bad files
// and bad θ refused in one line.
#include <drape/bodies/body.hpp>
#include <drape/bodies/posed_body.hpp>
#include <drape/bodies/smpl_theta.hpp>
#include <drape/io/h5.hpp>
#include <drape/warnings.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <random>

#include "test_support.hpp"

using namespace drape;

namespace {

// SMPL's kinematic tree (kintree_table's first row, the root's parent -1).
const std::vector<int> kSmplParents = {-1, 0, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 9, 9, 12, 13, 14, 16, 17, 18, 19, 20, 21};

struct SyntheticSmpl {
  Eigen::MatrixX3d v_template;
  Eigen::MatrixXd shapedirs;    // [3N, B]
  Eigen::MatrixXd j_regressor;  // [K, N]
  Eigen::MatrixXd weights;      // [N, K]
  Eigen::MatrixXd posedirs;     // [3N, 9(K-1)]
  Eigen::MatrixX3i faces;
  std::vector<int> parents;
};

// An upright ellipsoid (0.4 x 1.7 x 0.3 m) with two shape blend shapes, the
// given tree, each joint a random convex combination of six vertices,
// weights falling off smoothly with the distance to each joint (with seeded
// jitter) and posedirs of a few millimetres.
SyntheticSmpl make_synthetic(const std::vector<int>& parents, unsigned seed) {
  SyntheticSmpl m;
  const Mesh sphere = test::uv_sphere(1.0, 18, 16);
  const Eigen::Index n = sphere.vertices.rows();
  const auto k = static_cast<Eigen::Index>(parents.size());
  m.parents = parents;
  m.faces = sphere.faces;
  m.v_template = sphere.vertices;
  m.v_template.col(0) *= 0.2;
  m.v_template.col(1) = (0.85 + 0.85 * m.v_template.col(1).array()).matrix();
  m.v_template.col(2) *= 0.15;
  m.shapedirs = Eigen::MatrixXd::Zero(3 * n, 2);
  for (Eigen::Index v = 0; v < n; ++v) {
    m.shapedirs(3 * v, 0) = 0.1 * m.v_template(v, 0);
    m.shapedirs(3 * v + 2, 0) = 0.1 * m.v_template(v, 2);
    m.shapedirs(3 * v, 1) = 0.02 * m.v_template(v, 1);
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_int_distribution<Eigen::Index> vertex(0, n - 1);
  m.j_regressor = Eigen::MatrixXd::Zero(k, n);
  for (Eigen::Index j = 0; j < k; ++j) {
    double sum = 0;
    for (int i = 0; i < 6; ++i) {
      const double w = 0.2 + unit(rng);
      m.j_regressor(j, vertex(rng)) += w;
      sum += w;
    }
    m.j_regressor.row(j) /= sum;
  }
  const Eigen::MatrixX3d joints = m.j_regressor * m.v_template;
  m.weights.resize(n, k);
  for (Eigen::Index v = 0; v < n; ++v) {
    for (Eigen::Index j = 0; j < k; ++j) {
      const double d2 = (m.v_template.row(v) - joints.row(j)).squaredNorm();
      m.weights(v, j) = std::exp(-d2 / 0.05) * (0.5 + unit(rng)) + 1e-3 * unit(rng);
    }
    m.weights.row(v) /= m.weights.row(v).sum();
  }
  m.posedirs.resize(3 * n, 9 * (k - 1));
  for (Eigen::Index i = 0; i < m.posedirs.size(); ++i) m.posedirs.data()[i] = 0.003 * normal(rng);
  return m;
}

// The file as docs/smpl.md's converter writes it; `with_pose` false leaves
// out the four pose datasets.
// `indices_as_doubles`: /f and /kintree_table written as f64, as a
// converter that forgets their type does.
void write_synthetic(const SyntheticSmpl& m, const std::filesystem::path& file, bool with_pose = true,
                     bool indices_as_doubles = false) {
  const auto n = static_cast<std::size_t>(m.v_template.rows()), k = m.parents.size();
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  h5::File h = h5::File::create(file);
  const RowMajor vt = m.v_template, sd = m.shapedirs;
  h.write("/v_template", {n, 3}, vt.data());
  h.write("/shapedirs", {n, 3, 2}, sd.data());
  const Eigen::Matrix<std::int32_t, Eigen::Dynamic, 3, Eigen::RowMajor> f = m.faces;
  if (indices_as_doubles) {
    const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> fd = f.cast<double>();
    h.write("/f", {static_cast<std::size_t>(f.rows()), 3}, fd.data());
  } else {
    h.write("/f", {static_cast<std::size_t>(f.rows()), 3}, f.data());
  }
  if (with_pose) {
    const RowMajor jr = m.j_regressor, w = m.weights, pd = m.posedirs;
    h.write("/J_regressor", {k, n}, jr.data());
    h.write("/weights", {n, k}, w.data());
    std::vector<std::int64_t> tree(2 * k);
    for (std::size_t j = 0; j < k; ++j) {
      tree[j] = m.parents[j] < 0 ? 4294967295LL : m.parents[j];  // as SMPL's pickles hold it
      tree[k + j] = static_cast<std::int64_t>(j);
    }
    if (indices_as_doubles) {
      const std::vector<double> tree_d(tree.begin(), tree.end());
      h.write("/kintree_table", {2, k}, tree_d.data());
    } else {
      h.write("/kintree_table", {2, k}, tree.data());
    }
    h.write("/posedirs", {n, 3, 9 * (k - 1)}, pd.data());
  }
  h.close();
}

std::unique_ptr<BodyModel> load_smpl(const std::filesystem::path& file) {
  const auto& d = test::plugins().get("smpl");
  return test::plugins().create_body("smpl", Params(d.params, {{"file", {YAML::Node(file.string()), {}}}}, "smpl"));
}

// Rodrigues' formula as the SMPL paper writes it (eq. 1): R = I + sin|w| K + (1 - cos|w|) K^2,
// K the cross-product matrix of the unit axis w / |w|.
Eigen::Matrix3d paper_rodrigues(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle == 0) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d a = w / angle;
  Eigen::Matrix3d k;
  k << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return Eigen::Matrix3d::Identity() + std::sin(angle) * k + (1 - std::cos(angle)) * k * k;
}

// SMPL's M(beta, theta) with the root unturned (eqs. 2-4, 9-10), then scaled
// and put on y = 0 as drape places its unposed body.
Eigen::MatrixX3d paper_smpl(const SyntheticSmpl& m, const Eigen::Vector2d& betas, double scale,
                            const std::vector<Eigen::Vector3d>& theta) {
  const Eigen::Index n = m.v_template.rows(), k = static_cast<Eigen::Index>(m.parents.size());
  const Eigen::VectorXd offsets = m.shapedirs * betas;
  Eigen::MatrixX3d shaped = m.v_template;
  for (Eigen::Index v = 0; v < n; ++v) shaped.row(v) += offsets.segment<3>(3 * v).transpose();
  const Eigen::MatrixX3d joints = m.j_regressor * shaped;  // eq. 10
  std::vector<Eigen::Matrix3d> r(static_cast<std::size_t>(k));
  Eigen::VectorXd feature(9 * (k - 1));
  for (Eigen::Index j = 0; j < k; ++j) {
    r[static_cast<std::size_t>(j)] = paper_rodrigues(theta[static_cast<std::size_t>(j)]);
    if (j > 0)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          feature[9 * (j - 1) + 3 * a + b] = r[static_cast<std::size_t>(j)](a, b) - (a == b ? 1.0 : 0.0);  // eq. 9
  }
  const Eigen::VectorXd pose_offsets = m.posedirs * feature;
  // G_k = prod over the chain of [R_j | J_j - J_parent(j)] (eq. 4), then G'_k = G_k [I | -J_k].
  std::vector<Eigen::Matrix4d> g(static_cast<std::size_t>(k));
  for (Eigen::Index j = 0; j < k; ++j) {
    Eigen::Matrix4d local = Eigen::Matrix4d::Identity();
    local.topLeftCorner<3, 3>() = r[static_cast<std::size_t>(j)];
    const int p = m.parents[static_cast<std::size_t>(j)];
    const Eigen::RowVector3d parent_at = p < 0 ? Eigen::RowVector3d::Zero() : Eigen::RowVector3d(joints.row(p));
    local.topRightCorner<3, 1>() = (joints.row(j) - parent_at).transpose();
    g[static_cast<std::size_t>(j)] = p < 0 ? local : Eigen::Matrix4d(g[static_cast<std::size_t>(p)] * local);
  }
  for (Eigen::Index j = 0; j < k; ++j) {
    Eigen::Matrix4d& gj = g[static_cast<std::size_t>(j)];
    gj.topRightCorner<3, 1>() -= gj.topLeftCorner<3, 3>() * joints.row(j).transpose();
  }
  Eigen::MatrixX3d out(n, 3);
  for (Eigen::Index v = 0; v < n; ++v) {
    Eigen::Vector4d p;
    p << shaped.row(v).transpose() + pose_offsets.segment<3>(3 * v), 1.0;
    Eigen::Vector4d sum = Eigen::Vector4d::Zero();
    for (Eigen::Index j = 0; j < k; ++j) sum += m.weights(v, j) * (g[static_cast<std::size_t>(j)] * p);
    out.row(v) = sum.head<3>().transpose();
  }
  out *= scale;
  out.col(1).array() -= scale * shaped.col(1).minCoeff();
  return out;
}

// θ drawn per non-root joint, each component normal with `spread` radians.
std::vector<Eigen::Vector3d> random_theta(std::size_t joints, double spread, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, spread);
  std::vector<Eigen::Vector3d> theta(joints, Eigen::Vector3d::Zero());
  for (std::size_t j = 1; j < joints; ++j) theta[j] = {normal(rng), normal(rng), normal(rng)};
  return theta;
}

std::vector<double> flat_theta(const std::vector<Eigen::Vector3d>& theta) {
  std::vector<double> out;
  for (const auto& v : theta) out.insert(out.end(), {v.x(), v.y(), v.z()});
  return out;
}

Eigen::VectorXd shape_of(double beta0, double beta1, double scale) { return Eigen::Vector3d(beta0, beta1, scale); }

double max_apart(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) { return (a - b).cwiseAbs().maxCoeff(); }

}  // namespace

TEST_CASE("SMPL posed by theta follows the paper's equations", "[smpl][pose]") {
  test::TempDir dir;
  const SyntheticSmpl m = make_synthetic(kSmplParents, 7);
  write_synthetic(m, dir / "model.h5");
  const auto body = load_smpl(dir / "model.h5");
  REQUIRE(body->poseable());
  for (unsigned seed : {1u, 2u, 3u}) {
    const Eigen::Vector2d betas(0.8 * seed - 1.5, 0.5 - 0.3 * seed);
    const double scale = 0.9 + 0.1 * seed;
    const auto theta = random_theta(kSmplParents.size(), 0.4, seed);
    const Pose pose = pose_from_theta(flat_theta(theta), *body, "test");
    const Eigen::VectorXd shape = shape_of(betas[0], betas[1], scale);
    const Eigen::MatrixX3d expected = paper_smpl(m, betas, scale, theta);
    INFO("seed " << seed);
    CHECK(max_apart(expected, body->vertices(shape)) > 0.05);  // the pose moves the body
    CHECK(max_apart(body->posed(shape, pose), expected) < 1e-12);
    // The same from the unposed mesh alone (its scale recovered from it).
    CHECK(max_apart(body->posed_vertices(body->vertices(shape), pose, 1.0), expected) < 1e-12);
  }
}

TEST_CASE("SMPL joints angles and rest follow the file", "[smpl][pose]") {
  test::TempDir dir;
  const SyntheticSmpl m = make_synthetic(kSmplParents, 8);
  write_synthetic(m, dir / "model.h5");
  const auto body = load_smpl(dir / "model.h5");
  const auto joints = body->joints();
  REQUIRE(joints.size() == 24);
  CHECK(joints[0].name == "pelvis");
  CHECK(joints[0].angles.empty());  // the global orientation is not a pose angle
  CHECK(joints[18].name == "left_elbow");
  CHECK(joints[18].parent == 16);
  CHECK(joints[18].angles == std::vector<std::string>{"left_elbow_x", "left_elbow_y", "left_elbow_z"});
  for (std::size_t j = 0; j < joints.size(); ++j) CHECK(joints[j].parent == kSmplParents[j]);
  const auto angles = body->pose_angles();
  REQUIRE(angles.size() == 69);
  for (const PoseAngle& a : angles) {
    CHECK(a.min == -180);
    CHECK(a.max == 180);
    CHECK(a.sample_lo == 0);
    CHECK(a.sample_hi == 0);
  }
  const Eigen::VectorXd shape = shape_of(0.5, -0.3, 1.1);
  const Pose rest = body->rest_pose(shape);
  CHECK(rest.angles.size() == 69);
  for (const auto& [name, degrees] : rest.angles) CHECK(degrees == 0);
  CHECK(max_apart(body->joint_positions(shape), m.j_regressor * body->vertices(shape)) == 0);
  CHECK(body->skinning_weights() == m.weights);
}

TEST_CASE("SMPL at zero theta is the unposed body bit for bit", "[smpl][pose]") {
  test::TempDir dir;
  const SyntheticSmpl m = make_synthetic(kSmplParents, 9);
  write_synthetic(m, dir / "model.h5");
  const auto body = load_smpl(dir / "model.h5");
  const Eigen::VectorXd shape = shape_of(-0.7, 0.4, 0.95);
  const Eigen::MatrixX3d unposed = body->vertices(shape);
  const Pose zero = pose_from_theta(std::vector<double>(72, 0.0), *body, "test");
  REQUIRE(zero.angles.size() == 69);
  CHECK(body->posed(shape, zero) == unposed);
  CHECK(body->posed(shape, Pose{}) == unposed);
  CHECK(body->posed_vertices(unposed, zero, 1.0) == unposed);
  CHECK(pose_body(*body, "smpl", shape, zero) == unposed);
}

TEST_CASE("SMPL part of the way into a pose scales theta", "[smpl][pose]") {
  test::TempDir dir;
  const SyntheticSmpl m = make_synthetic(kSmplParents, 10);
  write_synthetic(m, dir / "model.h5");
  const auto body = load_smpl(dir / "model.h5");
  const Eigen::Vector2d betas(1.0, 0.2);
  const Eigen::VectorXd shape = shape_of(betas[0], betas[1], 1.05);
  const auto theta = random_theta(24, 0.5, 11);
  const Pose pose = pose_from_theta(flat_theta(theta), *body, "test");
  const Eigen::MatrixX3d unposed = body->vertices(shape);
  CHECK(body->posed_vertices(unposed, pose, 0.0) == unposed);
  CHECK(max_apart(body->posed_vertices(unposed, pose, 1.0), body->posed(shape, pose)) < 1e-12);
  for (double fraction : {0.25, 0.5}) {
    std::vector<Eigen::Vector3d> part = theta;
    for (auto& v : part) v *= fraction;
    INFO("fraction " << fraction);
    CHECK(max_apart(body->posed_vertices(unposed, pose, fraction), paper_smpl(m, betas, 1.05, part)) < 1e-12);
  }
  // Half way between two shapes (a scene's body morphing while it turns):
  // the blend is a body of the model, its scale the mean of the two.
  const Eigen::VectorXd other = shape_of(-1.0, 0.6, 0.9);
  const Eigen::MatrixX3d between = 0.5 * (unposed + body->vertices(other));
  // Its s * betas and s are the means of the two's.
  const double s = 0.5 * (shape[2] + other[2]);
  const Eigen::Vector2d mixed = 0.5 * (shape[2] * shape.head<2>() + other[2] * other.head<2>()) / s;
  const Eigen::MatrixX3d blended = paper_smpl(m, mixed, s, theta);
  const double lift = between.col(1).minCoeff();  // the blend of two feet-on-floor bodies stands on the floor
  CHECK(std::abs(lift) < 1e-12);
  CHECK(max_apart(body->posed_vertices(between, pose, 1.0), blended) < 1e-12);
}

TEST_CASE("SMPL theta from text and npy files", "[smpl][pose]") {
  test::TempDir dir;
  const SyntheticSmpl m = make_synthetic(kSmplParents, 12);
  write_synthetic(m, dir / "model.h5");
  const auto body = load_smpl(dir / "model.h5");
  const auto theta = random_theta(24, 0.3, 13);
  const std::vector<double> flat = flat_theta(theta);
  {
    std::ofstream text(dir / "theta.txt");
    text.precision(17);
    text << "# SMPL pose\n";
    for (std::size_t i = 0; i < flat.size(); ++i) text << flat[i] << (i % 3 == 2 ? "\n" : ", ");
  }
  CHECK(read_theta_file(dir / "theta.txt") == flat);
  {
    // NumPy's format 1.0: a float64 array of shape (24, 3).
    std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (24, 3), }";
    header.append(64 - (10 + header.size() + 1) % 64, ' ');
    header += '\n';
    std::ofstream npy(dir / "theta.npy", std::ios::binary);
    npy.write("\x93NUMPY\x01\x00", 8);
    const char len[2] = {static_cast<char>(header.size() & 0xff), static_cast<char>(header.size() >> 8)};
    npy.write(len, 2);
    npy << header;
    npy.write(reinterpret_cast<const char*>(flat.data()), static_cast<std::streamsize>(flat.size() * sizeof(double)));
  }
  CHECK(read_theta_file(dir / "theta.npy") == flat);
  // 69 numbers (no root) are the same pose as 72 with a zero root.
  const std::vector<double> no_root(flat.begin() + 3, flat.end());
  CHECK(pose_from_theta(no_root, *body, "t").angles == pose_from_theta(flat, *body, "t").angles);
  // An axis-angle vector longer than pi is the same rotation the other way round.
  std::vector<Eigen::Vector3d> long_way = theta;
  long_way[18] = Eigen::Vector3d(0.6, -0.8, 0.0) * (2 * M_PI - 1.0);  // = 1 radian about the opposite axis
  std::vector<Eigen::Vector3d> short_way = theta;
  short_way[18] = Eigen::Vector3d(-0.6, 0.8, 0.0);
  const Pose wrapped = pose_from_theta(flat_theta(long_way), *body, "t");
  CHECK(wrapped.angles.at("left_elbow_y") == Approx(0.8 * 180 / M_PI));
  CHECK(max_apart(body->posed(shape_of(0, 0, 1), wrapped), paper_smpl(m, {0, 0}, 1.0, short_way)) < 1e-12);
}

TEST_CASE("bad SMPL theta is refused in one line", "[smpl][pose]") {
  test::TempDir dir;
  const SyntheticSmpl m = make_synthetic(kSmplParents, 14);
  write_synthetic(m, dir / "model.h5");
  const auto body = load_smpl(dir / "model.h5");
  CHECK(test::message_of([&] { pose_from_theta(std::vector<double>(70, 0.0), *body, "--smpl-theta t.txt"); }) ==
        "--smpl-theta t.txt: 70 numbers; SMPL's theta for this model's 24 joints is 72 (one axis-angle vector per joint "
        "in radians, the root first) or 69 (without the root)");
  std::vector<double> turned(72, 0.0);
  turned[1] = 0.5;
  CHECK(test::message_of([&] { pose_from_theta(turned, *body, "--smpl-theta t.txt"); })
            .find("the root (pelvis) turns by (0, 0.5, 0) radians; drape's bodies stand upright") != std::string::npos);
  std::ofstream(dir / "nan.txt") << "0 0 0\n0.1 nan 0.2\n";
  CHECK(test::message_of([&] { read_theta_file(dir / "nan.txt"); }) ==
        "theta file " + (dir / "nan.txt").string() + ": number 5 of 6 is NaN");
  std::ofstream(dir / "inf.txt") << "0 inf 0";
  CHECK(test::message_of([&] { read_theta_file(dir / "inf.txt"); }).find("number 2 of 3 is infinite") != std::string::npos);
  std::ofstream(dir / "word.txt") << "0 0\n0 x 0";
  CHECK(test::message_of([&] { read_theta_file(dir / "word.txt"); }) ==
        "theta file " + (dir / "word.txt").string() + ":2: 'x' is not a number");
  // The parametric body's joints are not SMPL's.
  const auto parametric = test::parametric_body();
  CHECK(test::message_of([&] { pose_from_theta(std::vector<double>(72, 0.0), *parametric, "--smpl-theta t.txt"); })
            .find("do not take SMPL's axis-angle theta") != std::string::npos);
}

TEST_CASE("an SMPL file without pose datasets refuses a pose", "[smpl][pose]") {
  test::TempDir dir;
  const SyntheticSmpl m = make_synthetic(kSmplParents, 15);
  write_synthetic(m, dir / "shape_only.h5", false);
  const auto body = load_smpl(dir / "shape_only.h5");
  CHECK_FALSE(body->poseable());
  Pose p;
  p.angles["left_elbow_x"] = 10;
  const std::string why = "the SMPL file " + (dir / "shape_only.h5").string() +
                          " has no /J_regressor, /weights, /kintree_table or /posedirs: it makes unposed bodies only; "
                          "docs/smpl.md shows how to convert them";
  CHECK(test::message_of([&] { body->posed(body->mean_shape(), p); }) == why);
  CHECK(unposeable_reason(*body) == why);
  CHECK(test::message_of([&] { pose_body(*body, "smpl", body->mean_shape(), p); }) == "body smpl: " + why);
  CHECK(body->posed(body->mean_shape(), Pose{}) == body->vertices(body->mean_shape()));
}

TEST_CASE("SMPL pose datasets of inconsistent sizes are named", "[smpl][pose]") {
  test::TempDir dir;
  const SyntheticSmpl m = make_synthetic(kSmplParents, 16);
  const auto n = static_cast<std::size_t>(m.v_template.rows());
  const std::vector<double> zeros(n * 3 * 9 * 24, 0.0);
  {
    write_synthetic(m, dir / "partial.h5", false);
    h5::File h = h5::File::open(dir / "partial.h5", h5::Access::ReadWrite);
    h.write("/J_regressor", {24, n}, zeros.data());
    h.close();
    CHECK(test::message_of([&] { load_smpl(dir / "partial.h5"); })
              .find("has /J_regressor but not /weights, /kintree_table and /posedirs: SMPL's pose needs all four") !=
          std::string::npos);
  }
  const std::string jr = "/J_regressor is [24, " + std::to_string(n) + "]";
  // Each file with one dataset of the wrong size.
  auto with_bad = [&](const std::string& bad, const h5::Dims& dims) {
    const auto file = dir / ("bad_" + bad.substr(1) + ".h5");
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    h5::File h = h5::File::create(file);
    const RowMajor vt = m.v_template, sd = m.shapedirs, jreg = m.j_regressor, w = m.weights, pd = m.posedirs;
    h.write("/v_template", {n, 3}, vt.data());
    h.write("/shapedirs", {n, 3, 2}, sd.data());
    const Eigen::Matrix<std::int32_t, Eigen::Dynamic, 3, Eigen::RowMajor> f = m.faces;
    h.write("/f", {static_cast<std::size_t>(f.rows()), 3}, f.data());
    std::vector<std::int64_t> tree(48);
    for (std::size_t j = 0; j < 24; ++j) tree[j] = kSmplParents[j] < 0 ? -1 : kSmplParents[j], tree[24 + j] = static_cast<std::int64_t>(j);
    const auto put = [&](const std::string& name, const h5::Dims& right, const double* data) {
      h.write(name, name == bad ? dims : right, name == bad ? zeros.data() : data);
    };
    put("/J_regressor", {24, n}, jreg.data());
    put("/weights", {n, 24}, w.data());
    put("/posedirs", {n, 3, 207}, pd.data());
    if (bad == "/kintree_table") {
      std::vector<std::int64_t> wrong(dims[0] * dims[1], 0);
      h.write("/kintree_table", dims, wrong.data());
    } else {
      h.write("/kintree_table", {2, 24}, tree.data());
    }
    h.close();
    return test::message_of([&] { load_smpl(file); });
  };
  CHECK(with_bad("/weights", {n, 23}).find("/weights is [" + std::to_string(n) + ", 23] but " + jr) != std::string::npos);
  CHECK(with_bad("/posedirs", {n, 3, 198}).find("/posedirs is [" + std::to_string(n) + ", 3, 198] but " + jr + ": expected [" +
                                                std::to_string(n) + ", 3, 207]") != std::string::npos);
  CHECK(with_bad("/kintree_table", {2, 23}).find("/kintree_table is [2, 23] but " + jr) != std::string::npos);
  CHECK(with_bad("/J_regressor", {24, n - 1}).find("/J_regressor is [24, " + std::to_string(n - 1) + "], expected [K, " +
                                                    std::to_string(n) + "]") != std::string::npos);
}

// Values a file's shapes cannot catch, refused at load naming the file and
// the dataset: skinning weights that do not sum to 1 (doubled, they posed an
// outside check's arm 9.8 cm too far, said nowhere), NaN in the shape
// datasets (drape body printed "beta0 = nan" and exit 1 at the write), and a
// face list with no triangles (refused as "the shape blend shapes do not
// change the volume").
TEST_CASE("SMPL weights that do not sum to 1 and NaN shapes are refused at load", "[smpl][pose]") {
  test::TempDir dir;
  SyntheticSmpl m = make_synthetic(kSmplParents, 17);
  write_synthetic(m, dir / "good.h5");
  CHECK_NOTHROW(load_smpl(dir / "good.h5"));
  SyntheticSmpl doubled = m;
  doubled.weights.row(5) *= 2.0;
  write_synthetic(doubled, dir / "doubled.h5");
  CHECK_THAT(test::message_of([&] { load_smpl(dir / "doubled.h5"); }),
             Catch::Contains("doubled.h5: /weights row 5 sums to 2;") && Catch::Contains("must sum to 1"));
  // A joint regressor row that is no average places its joint off the body;
  // a weight of 1e300 is printed as such, not as a 300-digit sum.
  SyntheticSmpl scaled_joint = m;
  scaled_joint.j_regressor.row(3) *= 1.5;
  write_synthetic(scaled_joint, dir / "jr_scaled.h5");
  CHECK_THAT(test::message_of([&] { load_smpl(dir / "jr_scaled.h5"); }),
             Catch::Contains("jr_scaled.h5: /J_regressor row 3 (joint spine1) sums to 1.5;") &&
                 Catch::Contains("its row summing to 1"));
  SyntheticSmpl huge = m;
  huge.weights(6, 0) = 1e300;
  write_synthetic(huge, dir / "huge.h5");
  CHECK_THAT(test::message_of([&] { load_smpl(dir / "huge.h5"); }), Catch::Contains("/weights row 6 sums to 1e+300;"));
  SyntheticSmpl nan_template = m;
  nan_template.v_template(3, 1) = std::nan("");
  write_synthetic(nan_template, dir / "vt.h5");
  CHECK_THAT(test::message_of([&] { load_smpl(dir / "vt.h5"); }), Catch::Contains("vt.h5: /v_template holds NaN"));
  SyntheticSmpl nan_shapes = m;
  nan_shapes.shapedirs(7, 1) = std::numeric_limits<double>::infinity();
  write_synthetic(nan_shapes, dir / "sd.h5");
  CHECK_THAT(test::message_of([&] { load_smpl(dir / "sd.h5"); }), Catch::Contains("sd.h5: /shapedirs holds NaN or infinite"));
  SyntheticSmpl no_faces = m;
  no_faces.faces.resize(0, 3);
  write_synthetic(no_faces, dir / "f.h5");
  CHECK_THAT(test::message_of([&] { load_smpl(dir / "f.h5"); }), Catch::Contains("f.h5: /f holds no triangles"));
  SyntheticSmpl negative = m;
  negative.weights.row(4).setZero();
  negative.weights(4, 0) = -0.2, negative.weights(4, 1) = 1.2;  // a row summing to 1 with a weight below 0
  write_synthetic(negative, dir / "negative.h5");
  CHECK_THAT(test::message_of([&] { load_smpl(dir / "negative.h5"); }),
             Catch::Contains("negative.h5: /weights row 4 holds a negative weight"));
  // An HDF5 file named .pkl is read by its contents.
  std::filesystem::copy_file(dir / "good.h5", dir / "really_hdf5.pkl");
  CHECK_NOTHROW(load_smpl(dir / "really_hdf5.pkl"));
  // SMPL's own files are pointed to the conversion (they were "not an HDF5 file").
  std::ofstream(dir / "smpl.pkl") << "not hdf5";
  CHECK_THAT(test::message_of([&] { load_smpl(dir / "smpl.pkl"); }),
             Catch::Contains("smpl.pkl: SMPL's own .pkl files are read after converting them to HDF5"));
  SyntheticSmpl flat = m;
  flat.shapedirs.setZero();
  write_synthetic(flat, dir / "flat.h5");
  CHECK_THAT(test::message_of([&] { load_smpl(dir / "flat.h5"); }),
             Catch::Contains("flat.h5: the shape blend shapes (/shapedirs) do not change the body's volume"));
}

// What an outside check's own SMPL files met (2026-12-07): a parent index
// 15.9 stored as a float was read as 15 (the elbow hung from the head, the
// posed body 0.33 m off SMPL's, without a word); NaN in a pose dataset was
// "the pose datasets hold NaN" without naming which; a mesh wound inward
// reached "BMI -26.8 to -20.9"; 3 betas of a file's 2 were cut to 2.
TEST_CASE("SMPL datasets of the wrong kind are refused naming the dataset", "[smpl][pose]") {
  test::TempDir dir;
  const SyntheticSmpl m = make_synthetic(kSmplParents, 19);
  write_synthetic(m, dir / "whole.h5", true, true);  // integral values in a float dataset: still refused
  CHECK_THAT(test::message_of([&] { load_smpl(dir / "whole.h5"); }),
             Catch::Contains("whole.h5: dataset /f holds floating-point numbers; it must hold integers"));
  SyntheticSmpl posedirs_nan = m;
  posedirs_nan.posedirs(2, 5) = std::nan("");
  write_synthetic(posedirs_nan, dir / "pd.h5");
  CHECK_THAT(test::message_of([&] { load_smpl(dir / "pd.h5"); }), Catch::Contains("pd.h5: /posedirs holds NaN or infinite"));
  SyntheticSmpl jr_inf = m;
  jr_inf.j_regressor(1, 0) = std::numeric_limits<double>::infinity();
  write_synthetic(jr_inf, dir / "jr.h5");
  CHECK_THAT(test::message_of([&] { load_smpl(dir / "jr.h5"); }), Catch::Contains("jr.h5: /J_regressor holds NaN or infinite"));
  SyntheticSmpl inward = m;
  inward.faces.col(1).swap(inward.faces.col(2));
  write_synthetic(inward, dir / "inward.h5");
  CHECK_THAT(test::message_of([&] { load_smpl(dir / "inward.h5"); }),
             Catch::Contains("inward.h5: the mean body") && Catch::Contains("its triangles (/f) face inward"));
  // The file's 2 shape directions: 2 and the default are taken, 3 is refused with both counts.
  write_synthetic(m, dir / "good.h5");
  const auto& d = test::plugins().get("smpl");
  const auto with_betas = [&](int betas) {
    return test::plugins().create_body("smpl", Params(d.params, {{"file", {YAML::Node((dir / "good.h5").string()), {}}},
                                                                 {"betas", {YAML::Node(betas), {}}}},
                                                      "smpl"));
  };
  CHECK(with_betas(2)->shape_names().size() == 3);
  CHECK(load_smpl(dir / "good.h5")->shape_names().size() == 3);  // beta0, beta1, scale
  CHECK_THAT(test::message_of([&] { with_betas(3); }),
             Catch::Contains("betas 3 asked for, but /shapedirs holds 2 shape directions"));
}

// An SMPL file is one sex: a sex asked for is said not to be used, once
// (it made the same body without a word).
TEST_CASE("SMPL says once that a requested sex is not used", "[smpl]") {
  test::TempDir dir;
  write_synthetic(make_synthetic(kSmplParents, 18), dir / "m.h5");
  const auto body = load_smpl(dir / "m.h5");
  std::vector<std::string> said;
  const WarningHandler before = set_warning_handler([&](const std::string& text) { said.push_back(text); });
  const auto [lo, hi] = body->bmi_range();
  BodyRequest request;
  request.bmi = 0.5 * (lo + hi);
  request.height = 1.7;
  const Eigen::VectorXd as_default = body->solve(request);
  CHECK(said.empty());
  request.sex = 0.0;
  const Eigen::VectorXd female = body->solve(request);
  body->solve(request);
  set_warning_handler(before);
  REQUIRE(said.size() == 1);
  CHECK_THAT(said[0], Catch::Contains("an SMPL file is one sex, so the sex asked for or drawn (0.0") && Catch::Contains("m.h5"));
  CHECK((female - as_default).cwiseAbs().maxCoeff() == 0.0);  // the same body: the warning is the truth
}

TEST_CASE("drape body poses an SMPL body by a theta file", "[smpl][pose][cli]") {
  test::TempDir dir;
  const SyntheticSmpl m = make_synthetic(kSmplParents, 17);
  write_synthetic(m, dir / "model.h5");
  write_synthetic(m, dir / "shape_only.h5", false);
  // The synthetic body's joints lie anywhere in it: small turns keep it
  // clear of itself, large ones fold it (refused below).
  for (const auto& [name, spread] : {std::pair{"theta.txt", 0.04}, std::pair{"wild.txt", 0.6}}) {
    std::ofstream text(dir / name);
    text.precision(17);
    for (double x : flat_theta(random_theta(24, spread, 18))) text << x << " ";
  }
  const std::string smpl = "body --model smpl --param file=" + (dir / "model.h5").string() + " --bmi ";
  const auto body = load_smpl(dir / "model.h5");
  const double bmi = 0.5 * (body->bmi_range().first + body->bmi_range().second);
  std::string out;
  const auto posed = dir / "posed.obj";
  const int code = test::run_drape(smpl + std::to_string(bmi) + " --height 1.6 --smpl-theta " + (dir / "theta.txt").string() +
                                       " --out " + posed.string(), out);
  INFO(out);
  REQUIRE(code == 0);
  CHECK(std::filesystem::exists(posed));
  CHECK(out.find("posed: ") != std::string::npos);
  // Bad input: one line, exit 2, nothing written.
  auto refused = [&](const std::string& args, const std::string& says, bool before_solving = true) {
    const auto target = dir / "refused.obj";
    const int code = test::run_drape(args + " --out " + target.string(), out);
    INFO(out);
    CHECK(code == 2);
    CHECK(out.find(says) != std::string::npos);
    if (before_solving) CHECK(std::count(out.begin(), out.end(), '\n') == 1);
    CHECK_FALSE(std::filesystem::exists(target));
  };
  std::ofstream(dir / "short.txt") << "0.1 0.2 0.3";
  refused(smpl + std::to_string(bmi) + " --smpl-theta " + (dir / "short.txt").string(), "3 numbers; SMPL's theta");
  std::ofstream(dir / "nan.txt") << "nan";
  refused(smpl + std::to_string(bmi) + " --smpl-theta " + (dir / "nan.txt").string(), "is NaN");
  refused(smpl + std::to_string(bmi) + " --smpl-theta " + (dir / "wild.txt").string(),
          "this pose makes the body pass through itself", false);  // after the body's measurements
  refused("body --model smpl --param file=" + (dir / "shape_only.h5").string() + " --bmi " + std::to_string(bmi) +
              " --smpl-theta " + (dir / "theta.txt").string(),
          "has no /J_regressor, /weights, /kintree_table or /posedirs: it makes unposed bodies only");
  // SMPL ships no pose distribution: drawing poses is refused, not a θ = 0 for every body.
  const auto drawn_dir = dir / "drawn";
  CHECK(test::run_drape(smpl + std::to_string(bmi) + ":" + std::to_string(bmi + 1) + " --sample 2 --poses --out-dir " +
                            drawn_dir.string(),
                        out) == 2);
  CHECK(out.find("body model 'smpl' has no pose distribution to draw from") != std::string::npos);
  // (It named --pose-range, which only drape generate has.)
  CHECK(out.find("drape generate takes one as --pose-range") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(drawn_dir));
  // No SMPL file: where it looked, and how to bring one (it said only "no such file").
  CHECK(test::run_drape("body --model smpl --param file=" + (dir / "none.h5").string() + " --bmi 25 --out " +
                            (dir / "b.obj").string(), out) == 2);
  CHECK(out.find("none.h5: no such file (looked for it from ") != std::string::npos);
  CHECK(out.find("--param file=smpl.h5") != std::string::npos);
  CHECK(out.find("docs/smpl.md converts it") != std::string::npos);
  refused("body --model smpl --param file=" + (dir / "shape_only.h5").string() + " --bmi " + std::to_string(bmi) +
              " --pose left_elbow_x=10",
          "docs/smpl.md shows how to convert them");
}
