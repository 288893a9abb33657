#include "smpl_model.hpp"

#include <drape/bodies/body_space.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/volume.hpp>
#include <drape/io/h5.hpp>

#include <sstream>

namespace drape::smpl {

SmplData read_smpl_h5(const std::filesystem::path& file) {
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
  d.v_template = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(vt.data(), n, 3);
  const auto b = static_cast<Eigen::Index>(sd_shape[2]);
  d.shapedirs = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(sd.data(), 3 * n, b);
  d.faces.resize(static_cast<Eigen::Index>(f_shape[0]), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (faces[i] < 0 || faces[i] >= n)
      throw ConfigError(file.string() + ": /f refers to vertex " + std::to_string(faces[i]) + " of " + std::to_string(n));
    d.faces(static_cast<Eigen::Index>(i / 3), static_cast<Eigen::Index>(i % 3)) = static_cast<int>(faces[i]);
  }
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
  betas_ = std::min<int>(num_betas, static_cast<int>(data_.shapedirs.cols()));
  if (betas_ < 1) throw ConfigError("an SMPL model needs at least one shape blend shape");
  // d volume / d beta_i by central differences at the mean: the "weight" direction.
  direction_ = Eigen::VectorXd::Zero(betas_);
  for (int i = 0; i < betas_; ++i) {
    Eigen::VectorXd s = mean_shape();
    s[i] = 0.5;
    const double plus = geometry::mesh_volume(vertices(s), data_.faces);
    s[i] = -0.5;
    direction_[i] = plus - geometry::mesh_volume(vertices(s), data_.faces);
  }
  if (direction_.norm() == 0.0) throw ConfigError("the SMPL shape blend shapes do not change the volume");
  direction_.normalize();
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
