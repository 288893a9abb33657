#include <drape/energy.hpp>
#include <drape/gradcheck.hpp>
#include <drape/errors.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>

namespace drape {

double GradCheckReport::worst() const {
  double w = 0.0;
  for (const auto& e : entries) w = std::max(w, e.max_error);
  return w;
}

std::string GradCheckReport::str() const {
  std::ostringstream o;
  for (const auto& e : entries) o << "  " << e.what << ": max relative error " << e.max_error << " over " << e.checked << " entries\n";
  return o.str();
}

namespace {

std::vector<std::size_t> sample_indices(std::size_t n, std::size_t max, std::mt19937_64& rng) {
  std::vector<std::size_t> idx(n);
  std::iota(idx.begin(), idx.end(), 0);
  if (n > max) {
    std::shuffle(idx.begin(), idx.end(), rng);
    idx.resize(max);
  }
  return idx;
}

}  // namespace

GradCheckReport check_node_gradients(Node& node, const std::map<std::string, Tensor>& inputs_given,
                                     const NodeContext& context, const GradCheckOptions& opt) {
  std::map<std::string, Tensor> inputs = inputs_given;
  ShapeMap shapes;
  int batch = 0;
  for (const auto& [k, t] : inputs) {
    shapes[k] = t.shape();
    batch = t.batch();
  }
  const ShapeMap out_shapes = node.setup(shapes, context);
  std::mt19937_64 rng(opt.seed);
  std::normal_distribution<float> normal(0.0f, 1.0f);

  std::map<std::string, Tensor> outputs, projection;
  for (const auto& [k, s] : out_shapes) {
    outputs[k] = Tensor(batch, s);
    projection[k] = Tensor(batch, s);
    for (std::size_t i = 0; i < projection[k].size(); ++i) projection[k].data()[i] = normal(rng);
  }
  auto objective = [&]() {
    TensorIn in;
    for (auto& [k, t] : inputs) in[k] = &t;
    TensorOut out;
    for (auto& [k, t] : outputs) out[k] = &t;
    node.forward(in, out);
    double sum = 0.0;
    for (const auto& [k, t] : outputs)
      for (std::size_t i = 0; i < t.size(); ++i) sum += double(t.data()[i]) * projection[k].data()[i];
    return sum;
  };

  objective();
  node.zero_grad();
  std::map<std::string, Tensor> grad_in;
  TensorIn in, out, gout;
  TensorOut gin;
  for (auto& [k, t] : inputs) {
    in[k] = &t;
    grad_in[k] = Tensor(t.batch(), t.rows(), t.cols());
    gin[k] = &grad_in[k];
  }
  for (auto& [k, t] : outputs) {
    out[k] = &t;
    gout[k] = &projection[k];
  }
  node.backward(in, out, gout, gin);

  GradCheckReport report;
  auto probe = [&](const std::string& what, Tensor& value, const Tensor& analytic) {
    GradCheckEntry e{what, 0.0, 0};
    double scale = 1e-12;
    for (std::size_t i = 0; i < analytic.size(); ++i) scale = std::max(scale, std::abs(double(analytic.data()[i])));
    for (std::size_t i : sample_indices(value.size(), opt.max_entries, rng)) {
      const float original = value.data()[i];
      const float h = static_cast<float>(opt.step * std::max(1.0, std::abs(double(original))));
      value.data()[i] = original + h;
      const double plus = objective();
      value.data()[i] = original - h;
      const double minus = objective();
      value.data()[i] = original;
      const double numeric = (plus - minus) / (2.0 * h);
      e.max_error = std::max(e.max_error, std::abs(numeric - analytic.data()[i]) / scale);
      ++e.checked;
    }
    report.entries.push_back(e);
  };
  for (auto& [k, t] : inputs) probe("input " + k, t, grad_in[k]);
  for (auto& [k, w] : node.weights()) {
    const Tensor analytic = w.grad;
    probe("weight " + k, w.value, analytic);
  }
  return report;
}

GradCheckReport check_energy_derivatives(const Energy& energy, const Eigen::MatrixX3d& x0, const GradCheckOptions& opt) {
  const Eigen::Index n = x0.rows();
  const Eigen::Index dofs = 3 * n;
  if (dofs > 3000) throw Error("check_energy_derivatives: keep the test mesh small (<= 1000 vertices)");
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(n, 3);
  energy.add_gradient(x0, g);
  auto dense_hessian = [&](bool project) {
    Triplets t;
    energy.add_hessian(x0, t, project);
    Eigen::SparseMatrix<double> h(dofs, dofs);
    h.setFromTriplets(t.begin(), t.end());
    return Eigen::MatrixXd(h);
  };
  const Eigen::MatrixXd h = dense_hessian(false);
  std::mt19937_64 rng(opt.seed);

  GradCheckReport report;
  GradCheckEntry eg{"gradient", 0.0, 0}, eh{"hessian", 0.0, 0};
  const double gscale = std::max(1e-300, g.cwiseAbs().maxCoeff());
  const double hscale = std::max(1e-300, h.cwiseAbs().maxCoeff());
  for (std::size_t i : sample_indices(static_cast<std::size_t>(dofs), opt.max_entries, rng)) {
    const Eigen::Index v = static_cast<Eigen::Index>(i) / 3, a = static_cast<Eigen::Index>(i) % 3;
    const double step = opt.step * std::max(1.0, std::abs(x0(v, a)));
    Eigen::MatrixX3d xp = x0, xm = x0;
    xp(v, a) += step;
    xm(v, a) -= step;
    const double numeric = (energy.value(xp) - energy.value(xm)) / (2 * step);
    eg.max_error = std::max(eg.max_error, std::abs(numeric - g(v, a)) / gscale);
    ++eg.checked;
    Eigen::MatrixX3d gp = Eigen::MatrixX3d::Zero(n, 3), gm = Eigen::MatrixX3d::Zero(n, 3);
    energy.add_gradient(xp, gp);
    energy.add_gradient(xm, gm);
    const Eigen::MatrixX3d column = (gp - gm) / (2 * step);
    for (Eigen::Index r = 0; r < dofs; ++r)
      eh.max_error = std::max(eh.max_error, std::abs(column(r / 3, r % 3) - h(r, static_cast<Eigen::Index>(i))) / hscale);
    ++eh.checked;
  }
  report.entries.push_back(eg);
  report.entries.push_back(eh);

  const Eigen::MatrixXd hp = dense_hessian(true);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(hp, Eigen::EigenvaluesOnly);
  const double min_eig = eig.eigenvalues().size() ? eig.eigenvalues().minCoeff() : 0.0;
  const double pscale = std::max(1e-300, hp.cwiseAbs().maxCoeff());
  report.entries.push_back({"psd", std::max(0.0, -min_eig) / pscale, static_cast<std::size_t>(dofs)});

  // add_hessian_lower against the lower triangle of add_hessian, both ways.
  GradCheckEntry lower{"lower", 0.0, 0};
  for (const bool project : {false, true}) {
    Triplets t;
    energy.add_hessian_lower(x0, t, project);
    for (const auto& entry : t)
      if (entry.row() < entry.col()) lower.max_error = std::numeric_limits<double>::infinity();
    Eigen::SparseMatrix<double> sparse(dofs, dofs);
    sparse.setFromTriplets(t.begin(), t.end());
    const Eigen::MatrixXd full = project ? hp : h;
    const Eigen::MatrixXd expected = full.triangularView<Eigen::Lower>();
    const double scale = std::max(1e-300, full.cwiseAbs().maxCoeff());
    lower.max_error = std::max(lower.max_error, (Eigen::MatrixXd(sparse) - expected).cwiseAbs().maxCoeff() / scale);
    lower.checked += t.size();
  }
  report.entries.push_back(lower);
  return report;
}

}  // namespace drape
