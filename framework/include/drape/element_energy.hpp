#pragma once
// An energy that is a sum over elements of N vertices each (faces, hinges):
// the subclass writes one element's value, gradient and Hessian on its own
// stencil; this base does the rest once for every such energy (the size
// check, the gather of positions, the deterministic parallel sum, the
// per-vertex gradient gather and the triplet bookkeeping of both Hessian
// forms), as IPC Toolkit's Potential does for its collision stencils.
//
//   class Spring final : public ElementEnergy<2> {
//     void bind(const EnergyContext& c) override { ...; set_elements(num_vertices, edges); }
//     double element_value(int e, const Stencil& x) const override;
//     double element_gradient(int e, const Stencil& x, StencilGradient& g) const override;
//     void element_hessian(int e, const Stencil& x, bool project_psd, StencilHessian& h) const override;
//   };
//
// Results do not depend on the number of threads (element_assembly.hpp).
#include <drape/element_assembly.hpp>
#include <drape/energy_input.hpp>
#include <drape/errors.hpp>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace drape {

template <int N>
class ElementEnergy : public Energy {
 public:
  using Stencil = Eigen::Matrix<double, 3, N>;  // the element's vertex positions, one per column
  using StencilGradient = Eigen::Matrix<double, 3 * N, 1>;
  using StencilHessian = Eigen::Matrix<double, 3 * N, 3 * N>;
  using Element = std::array<int, N>;

  double value(const Eigen::MatrixX3d& x) const final {
    check(x);
    return deterministic_sum(num_elements(), [&](int e) { return element_value(e, stencil(x, e)); });
  }

  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const final {
    check(x);
    std::vector<Eigen::Vector3d> corner(gather_.num_slots());
    const double total = deterministic_sum(num_elements(), [&](int e) {
      StencilGradient ge;
      const double v = element_gradient(e, stencil(x, e), ge);
      for (int k = 0; k < N; ++k) corner[static_cast<std::size_t>(N * e + k)] = ge.template segment<3>(3 * k);
      return v;
    });
    gather_.add_to(corner, g);
    return total;
  }

  void add_hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd) const final {
    hessian(x, h, project_psd, false);
  }
  void add_hessian_lower(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd) const final {
    hessian(x, h, project_psd, true);
  }

  int num_elements() const { return static_cast<int>(elements_.size()); }
  const Element& element(int e) const { return elements_[static_cast<std::size_t>(e)]; }

 protected:
  ElementEnergy() = default;

  // Called by bind() once the elements are known: their vertices and the
  // number of vertices of the positions every call will be given.
  void set_elements(int num_vertices, std::vector<Element> elements) {
    vertices_ = num_vertices;
    elements_ = std::move(elements);
    gather_.build(vertices_, num_elements(), N, [&](int e, int k) { return elements_[static_cast<std::size_t>(e)][static_cast<std::size_t>(k)]; });
  }

  virtual double element_value(int e, const Stencil& x) const = 0;
  // Sets g = dE_e/dx over the stencil (3 N, vertex by vertex) and returns E_e.
  virtual double element_gradient(int e, const Stencil& x, StencilGradient& g) const = 0;
  // The exact Hessian, or with project_psd the PSD one Newton needs.
  virtual void element_hessian(int e, const Stencil& x, bool project_psd, StencilHessian& h) const = 0;

 private:
  Stencil stencil(const Eigen::MatrixX3d& x, int e) const {
    Stencil s;
    const Element& v = elements_[static_cast<std::size_t>(e)];
    for (int k = 0; k < N; ++k) s.col(k) = x.row(v[static_cast<std::size_t>(k)]).transpose();
    return s;
  }

  void hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd, bool lower) const {
    check(x);
    const std::size_t offset = h.size();
    const int n = num_elements();
    const std::size_t per_element = hessian_entries<N>(lower);
    h.resize(offset + per_element * static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static) if (n >= kParallelHessianMinimum)
    for (int e = 0; e < n; ++e) {
      StencilHessian block;
      element_hessian(e, stencil(x, e), project_psd, block);
      write_element_hessian<N>(block, elements_[static_cast<std::size_t>(e)].data(), lower,
                               h.data() + offset + per_element * static_cast<std::size_t>(e));
    }
  }

  void check(const Eigen::MatrixX3d& x) const { check_energy_input(x, vertices_); }

  int vertices_ = 0;
  std::vector<Element> elements_;
  CornerGather gather_;
};

// The checks every energy over a garment's faces makes in bind() (as
// ConfigErrors; the framework names the energy, error_context.hpp): a garment is bound, it has finite
// material-space UVs (uv, uv_faces) with indices in range, at least one
// material, a face-material map of the right size naming existing materials,
// and face vertex indices in range.
const Garment& checked_garment(const EnergyContext& context);
// The same checks with the messages prefixed by `energy` (for code called
// outside the registry's plugin calls).
const Garment& checked_garment(const EnergyContext& context, const std::string& energy);

}  // namespace drape
