#pragma once
// Finite-difference checks that every plugin's test runs: a node's gradients for
// its inputs and weights (float, central differences on a random projection of
// the outputs), and an energy's gradient and Hessian (double).
#include <drape/energy.hpp>
#include <drape/node.hpp>

#include <string>
#include <vector>

namespace drape {

struct GradCheckEntry {
  std::string what;        // "input x", "weight w1", "gradient", "hessian", "psd", "lower"
  double max_error = 0.0;  // max |analytic - numeric| / max |analytic| over the tensor
  std::size_t checked = 0;
};

struct GradCheckReport {
  std::vector<GradCheckEntry> entries;
  double worst() const;
  bool ok(double tolerance) const { return worst() <= tolerance; }
  std::string str() const;
};

struct GradCheckOptions {
  double step = 1e-3;          // central difference step (scaled by max(1, |value|) for energies)
  std::size_t max_entries = 64;  // entries per tensor probed (randomly chosen)
  std::uint64_t seed = 7;
};

// Sets the node up with the inputs' shapes (inputs are used as given), then
// compares backward() against central differences of sum(R * outputs).
GradCheckReport check_node_gradients(Node& node, const std::map<std::string, Tensor>& inputs,
                                     const NodeContext& context = {}, const GradCheckOptions& options = {});

// Gradient vs differences of value(); exact Hessian vs differences of the
// gradient; and the projected Hessian's smallest eigenvalue >= -1e-9 * scale
// (entry "psd", error = max(0, -min eigenvalue) / max |H|); add_hessian_lower
// equals the lower triangle of add_hessian, exact and projected (entry
// "lower"; an entry above the diagonal is an infinite error). Keep x small (dense).
GradCheckReport check_energy_derivatives(const Energy& energy, const Eigen::MatrixX3d& x,
                                         const GradCheckOptions& options = {1e-6, 64, 7});

}  // namespace drape
