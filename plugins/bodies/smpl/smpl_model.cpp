#include "smpl_model.hpp"

#include <drape/bodies/body_space.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/volume.hpp>
#include <drape/io/h5.hpp>
#include <drape/warnings.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

namespace drape::smpl {

SmplData read_smpl_h5(const std::filesystem::path& file) {
  // SMPL's licence keeps it out of drape: a user converts their own copy.
  // Without one, say so, not only "no such file" (an outside check).
  std::error_code ec;
  if (!std::filesystem::exists(file, ec))
    throw ConfigError(file.string() + ": no such file (looked for it from " + std::filesystem::current_path(ec).string() +
                      "): the SMPL body needs a model file converted from SMPL's own, which its licence keeps out of "
                      "drape: --param file=smpl.h5 (in Python, params={'file': ...}) names yours, and docs/smpl.md "
                      "converts it");
  // SMPL's own files (.pkl, .npz) are not HDF5: said with the way there
  // (it was "not an HDF5 file" alone, an outside check).
  // (By the contents: an HDF5 file named .pkl is read; HDF5's signature
  // starts the file, or a user block of 512 bytes.)
  const auto is_hdf5 = [&] {
    std::ifstream in(file, std::ios::binary);
    const std::string signature = "\x89HDF\r\n\x1a\n";
    for (const std::streamoff at : {0, 512}) {
      std::string head(signature.size(), '\0');
      in.clear();
      in.seekg(at);
      if (in.read(head.data(), static_cast<std::streamsize>(head.size())) && head == signature) return true;
    }
    return false;
  };
  if (const std::string ext = file.extension().string(); (ext == ".pkl" || ext == ".npz" || ext == ".npy") && !is_hdf5())
    throw ConfigError(file.string() + ": SMPL's own " + ext + " files are read after converting them to HDF5 with the "
                      "script in docs/smpl.md (\"Converting the official file\"); --param file= names the .h5 it writes");
  const h5::File f = h5::File::open(file);
  SmplData d;
  h5::Dims vt_shape, sd_shape, f_shape;
  const std::vector<double> vt = f.read<double>("/v_template", &vt_shape);
  if (vt_shape.size() != 2 || vt_shape[1] != 3) throw ConfigError(file.string() + ": /v_template must be [N, 3]");
  const auto n = static_cast<Eigen::Index>(vt_shape[0]);
  const std::vector<double> sd = f.read<double>("/shapedirs", &sd_shape);
  if (sd_shape.size() != 3 || static_cast<Eigen::Index>(sd_shape[0]) != n || sd_shape[1] != 3)
    throw ConfigError(file.string() + ": /shapedirs must be [N, 3, B] with N = " + std::to_string(n));
  const std::vector<std::int64_t> faces = f.read<std::int64_t>("/f", &f_shape);
  if (f_shape.size() != 2 || f_shape[1] != 3) throw ConfigError(file.string() + ": /f must be [F, 3]");
  // (An empty /f was refused later as "the shape blend shapes do not change
  // the volume", and a NaN in the shape datasets as a non-finite body when
  // written, naming neither the file nor the dataset: outside checks.)
  if (f_shape[0] == 0) throw ConfigError(file.string() + ": /f holds no triangles (expected [F, 3], F > 0)");
  for (const auto& [name, values] : {std::pair{"/v_template", &vt}, std::pair{"/shapedirs", &sd}})
    for (const double x : *values)
      if (!std::isfinite(x)) throw ConfigError(file.string() + ": " + name + " holds NaN or infinite values");
  d.v_template = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(vt.data(), n, 3);
  const auto b = static_cast<Eigen::Index>(sd_shape[2]);
  d.shapedirs = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(sd.data(), 3 * n, b);
  d.faces.resize(static_cast<Eigen::Index>(f_shape[0]), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (faces[i] < 0 || faces[i] >= n)
      throw ConfigError(file.string() + ": /f refers to vertex " + std::to_string(faces[i]) + " of " + std::to_string(n));
    d.faces(static_cast<Eigen::Index>(i / 3), static_cast<Eigen::Index>(i % 3)) = static_cast<int>(faces[i]);
  }
  d.rig = read_smpl_rig(f, n);
  d.file = file;
  return d;
}

namespace {
double height_of(const Eigen::MatrixX3d& v) { return v.col(1).maxCoeff() - v.col(1).minCoeff(); }
double bmi_of(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f) {
  const double h = height_of(v);
  return geometry::mesh_volume(v, f) * 985.0 / (h * h);
}
}  // namespace

SmplBody::SmplBody(SmplData data, int num_betas) : data_(std::move(data)) {
  // More betas than the file has shape directions were cut to its count
  // without a word (an outside check asked for 20 of a file's 10).
  if (num_betas > data_.shapedirs.cols())
    throw ConfigError(data_.file.string() + ": betas " + std::to_string(num_betas) + " asked for, but /shapedirs holds " +
                      std::to_string(data_.shapedirs.cols()) + " shape directions; give betas <= " +
                      std::to_string(data_.shapedirs.cols()));
  betas_ = num_betas;
  if (betas_ < 1)
    throw ConfigError(data_.file.string() + ": an SMPL model needs at least one shape blend shape (/shapedirs is [N, 3, " +
                      std::to_string(data_.shapedirs.cols()) + "], betas " + std::to_string(num_betas) + ")");
  // The body's triangles face outward, as SMPL's do: a mesh wound inward has
  // a negative volume, and BMIs from it were negative ("reaches BMI -26.8 to
  // -20.9"), which no request can meet and nothing explained.
  if (const double volume = geometry::mesh_volume(vertices(mean_shape()), data_.faces); !(volume > 0))
    throw ConfigError(data_.file.string() + ": the mean body (/v_template with /f) encloses a volume of " +
                      std::to_string(volume) + " m^3; " +
                      (volume < 0 ? "its triangles (/f) face inward: give each triangle's corners in the other order"
                                  : "it encloses nothing (in meters, /f a closed surface)"));
  // d volume / d beta_i by central differences at the mean: the "weight" direction.
  direction_ = Eigen::VectorXd::Zero(betas_);
  for (int i = 0; i < betas_; ++i) {
    Eigen::VectorXd s = mean_shape();
    s[i] = 0.5;
    const double plus = geometry::mesh_volume(vertices(s), data_.faces);
    s[i] = -0.5;
    direction_[i] = plus - geometry::mesh_volume(vertices(s), data_.faces);
  }
  if (direction_.norm() == 0.0)
    throw ConfigError(data_.file.string() + ": the shape blend shapes (/shapedirs) do not change the body's volume, so no "
                      "BMI can be reached");
  direction_.normalize();
  if (data_.rig) {
    const Eigen::Index n = num_vertices();
    Eigen::MatrixXd basis = Eigen::MatrixXd::Zero(3 * n, betas_ + 4);
    for (Eigen::Index v = 0; v < n; ++v)
      for (int axis = 0; axis < 3; ++axis) {
        basis(3 * v + axis, 0) = data_.v_template(v, axis);
        basis(3 * v + axis, betas_ + 1 + axis) = 1.0;
      }
    basis.middleCols(1, betas_) = data_.shapedirs.leftCols(betas_);
    scale_fit_.emplace(basis);
  }
}

const SmplRig& SmplBody::rig() const {
  if (!data_.rig)
    throw ConfigError("the SMPL file " + data_.file.string() +
                      " has no /J_regressor, /weights, /kintree_table or /posedirs: it makes unposed bodies only; "
                      "docs/smpl.md shows how to convert them");
  return *data_.rig;
}

std::vector<PoseAngle> SmplBody::pose_angles() const { return data_.rig ? smpl_pose_angles(*data_.rig) : std::vector<PoseAngle>{}; }
std::vector<BodyModel::Joint> SmplBody::joints() const { return data_.rig ? smpl_joints(*data_.rig) : std::vector<Joint>{}; }
Eigen::MatrixX3d SmplBody::joint_positions(const Eigen::VectorXd& shape) const { return rig().j_regressor * vertices(shape); }
Eigen::MatrixXd SmplBody::skinning_weights() const { return rig().weights; }

Pose SmplBody::rest_pose(const Eigen::VectorXd&) const {
  Pose rest;
  for (const PoseAngle& a : pose_angles()) rest.angles[a.name] = 0;
  return rest;
}

Eigen::MatrixX3d SmplBody::posed(const Eigen::VectorXd& shape, const Pose& pose) const {
  if (pose.empty()) return vertices(shape);
  rig();  // the file's reason first, before the pose's names are checked against no angles
  check_pose(pose, pose_angles(), "body smpl pose");
  const Eigen::MatrixX3d unposed = vertices(shape);  // checks the shape's size before its scale is read
  return pose_shaped(rig(), unposed, shape[betas_], axis_angles(rig(), pose, 1.0));
}

Eigen::MatrixX3d SmplBody::posed_vertices(const Eigen::MatrixX3d& unposed, const Pose& pose, double fraction) const {
  if (pose.empty()) return unposed;
  rig();
  check_pose(pose, pose_angles(), "body smpl pose");
  if (unposed.rows() != num_vertices())
    throw ConfigError("body smpl: a body to pose has " + std::to_string(unposed.rows()) + " vertices, the model " +
                      std::to_string(num_vertices()));
  if (!(fraction >= 0 && fraction <= 1)) throw ConfigError("body smpl: a pose fraction must lie in [0, 1]");
  if (fraction == 0) return unposed;
  return pose_shaped(rig(), unposed, scale_of(unposed), axis_angles(rig(), pose, fraction));
}

std::vector<skinning::Rigid> SmplBody::joint_transforms(const Eigen::MatrixX3d& unposed, const Pose& pose) const {
  rig();
  check_pose(pose, pose_angles(), "body smpl pose");
  if (unposed.rows() != num_vertices())
    throw ConfigError("body smpl: a body to pose has " + std::to_string(unposed.rows()) + " vertices, the model " +
                      std::to_string(num_vertices()));
  return pose_transforms(rig(), unposed, axis_angles(rig(), pose, 1.0));
}

double SmplBody::scale_of(const Eigen::MatrixX3d& unposed) const {
  Eigen::VectorXd flat(3 * unposed.rows());
  for (Eigen::Index v = 0; v < unposed.rows(); ++v) flat.segment<3>(3 * v) = unposed.row(v).transpose();
  const double s = scale_fit_->solve(flat)[0];
  if (!(s > 0 && std::isfinite(s))) throw ConfigError("body smpl: the body to pose is no scaled SMPL body (scale " + std::to_string(s) + ")");
  return s;
}

std::vector<std::string> SmplBody::shape_names() const {
  std::vector<std::string> names;
  for (int i = 0; i < betas_; ++i) names.push_back("beta" + std::to_string(i));
  names.push_back("scale");
  return names;
}

Eigen::VectorXd SmplBody::mean_shape() const {
  Eigen::VectorXd s = Eigen::VectorXd::Zero(betas_ + 1);
  s[betas_] = 1.0;
  return s;
}

Eigen::MatrixX3d SmplBody::vertices(const Eigen::VectorXd& shape) const {
  if (shape.size() != betas_ + 1)
    throw ConfigError("an SMPL shape here has " + std::to_string(betas_) + " betas and a scale (" +
                      std::to_string(shape.size()) + " values given)");
  const Eigen::VectorXd offsets = data_.shapedirs.leftCols(betas_) * shape.head(betas_);
  Eigen::MatrixX3d v = data_.v_template;
  for (Eigen::Index i = 0; i < v.rows(); ++i) v.row(i) += offsets.segment<3>(3 * i).transpose();
  v *= shape[betas_];
  v.col(1).array() -= v.col(1).minCoeff();  // feet on the ground, as every drape body
  return v;
}

Eigen::VectorXd SmplBody::shape_at(double t, double height) const {
  Eigen::VectorXd s = mean_shape();
  s.head(betas_) = t * direction_;
  s[betas_] = height / height_of(vertices(s));
  return s;
}

double SmplBody::bmi_at(double t, double height) const { return bmi_of(vertices(shape_at(t, height)), data_.faces); }

std::pair<double, double> SmplBody::bmi_range() const { return {bmi_at(-t_max_, 1.75), bmi_at(t_max_, 1.75)}; }

Eigen::VectorXd SmplBody::solve(const BodyRequest& r) const {
  check_proportions(*this, "smpl", r);  // it offers none: a request with girths is refused
  // An SMPL file is one sex (SMPL ships female, male and neutral files): a
  // sex asked for made the same body without a word, and a generated
  // dataset recorded sexes its bodies did not have (an outside check). The
  // request's default (1) is no request.
  if (r.sex != BodyRequest{}.sex)
    std::call_once(sex_warned_, [&] {
      warn("smpl: an SMPL file is one sex, so the sex asked for or drawn (" + std::to_string(r.sex) + ") is not used: " +
           data_.file.filename().string() + " makes its own; give SMPL's female or male file for another (docs/smpl.md)");
    });
  if (!(r.height > 0.5 && r.height < 3.0)) throw ConfigError("height must be in meters (0.5 - 3.0)");
  double lo = -t_max_, hi = t_max_;
  const double bmi_lo = bmi_at(lo, r.height), bmi_hi = bmi_at(hi, r.height);
  if (r.bmi < bmi_lo || r.bmi > bmi_hi) {
    std::ostringstream o;
    o.precision(3);
    o << "this SMPL model reaches BMI " << bmi_lo << " to " << bmi_hi << " within 3 standard deviations; BMI " << r.bmi
      << " is outside";
    throw ConfigError(o.str());
  }
  for (int i = 0; i < 50 && hi - lo > 1e-7; ++i) {
    const double t = 0.5 * (lo + hi);
    (bmi_at(t, r.height) < r.bmi ? lo : hi) = t;
  }
  return shape_at(0.5 * (lo + hi), r.height);
}

}  // namespace drape::smpl
