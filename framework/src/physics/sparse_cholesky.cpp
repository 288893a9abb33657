#include "sparse_cholesky.hpp"

#include <drape/errors.hpp>
#include <drape/solver.hpp>

#include <Eigen/SparseCholesky>
#ifdef DRAPE_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

namespace drape::physics {

namespace {

// Remembers the analysed pattern by its size and non-zero count; the Newton
// matrices always carry the full topological pattern (explicit zeros
// included), so a change in either means a different pattern.
struct PatternKey {
  Eigen::Index rows = -1, nonzeros = -1;
  bool same(const SparseMatrix& a) const { return rows == a.rows() && nonzeros == a.nonZeros(); }
  void set(const SparseMatrix& a) {
    rows = a.rows();
    nonzeros = a.nonZeros();
  }
};

template <class Solver>
class EigenBackedCholesky final : public SparseCholesky {
 public:
  explicit EigenBackedCholesky(std::string name) : name_(std::move(name)) {}
  Solver& solver() { return solver_; }
  bool factorize(const SparseMatrix& a) override {
    if (!key_.same(a)) {
      solver_.analyzePattern(a);
      key_.set(a);
    }
    solver_.factorize(a);
    return solver_.info() == Eigen::Success;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const override { return solver_.solve(b); }
  std::string name() const override { return name_; }

 private:
  std::string name_;
  Solver solver_;
  PatternKey key_;
};

}  // namespace

bool cholmod_available() {
#ifdef DRAPE_HAVE_CHOLMOD
  return true;
#else
  return false;
#endif
}

std::unique_ptr<SparseCholesky> make_sparse_cholesky(const std::string& name) {
  if (name == "eigen" || (name == "auto" && !cholmod_available()))
    return std::make_unique<EigenBackedCholesky<Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>>>(
        "eigen");
  if (name == "cholmod" || name == "auto") {
#ifdef DRAPE_HAVE_CHOLMOD
    auto c = std::make_unique<EigenBackedCholesky<Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>>>("cholmod");
    // Nested dissection only: on the default T-shirt (10.5k dofs) it needs
    // 5.0e8 flops per factorisation against 7.1e8 for AMD, which CHOLMOD's
    // default (try AMD, then METIS) ends up close to; measured 67 vs 81 ms.
    cholmod_common& common = c->solver().cholmod();
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_NESDIS;
    // One BLAS thread inside CHOLMOD, for every solver: these factorisations
    // are too small to gain from more (measured the same time), OpenBLAS's idle
    // threads spin against one-solver-per-core jobs (drape generate: 13.6 s
    // instead of 4.4 s per coarse drape), and a multi-threaded BLAS rounds
    // differently, which would make a drape depend on the thread count.
    set_blas_threads(1);
    return c;
#else
    throw ConfigError("linear_solver: cholmod was not found when drape was built (install libsuitesparse-dev); use eigen");
#endif
  }
  throw ConfigError("linear_solver: unknown '" + name + "'; known: auto, eigen, cholmod");
}

}  // namespace drape::physics
