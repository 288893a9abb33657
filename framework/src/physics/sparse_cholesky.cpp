#include "sparse_cholesky.hpp"

#include "supernodal_solve.hpp"

#include <drape/errors.hpp>
#include <drape/nn/blas_threads.hpp>
#include <drape/physics/solver.hpp>

#include <Eigen/SparseCholesky>
#ifdef DRAPE_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <mutex>
#ifdef _OPENMP
#include <omp.h>
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

#ifdef DRAPE_HAVE_CHOLMOD
// Debian's CHOLMOD (SuiteSparse 5) opens OpenMP teams of a fixed size,
// num_threads(CHOLMOD_OMP_NUM_THREADS) = 4 at its build, around loops that
// only clear or zero a few hundred entries, once per supernode. That clause
// overrides OMP_NUM_THREADS, so a one-thread drape woke three helper threads
// thousands of times per factorisation: on 2 cores, 38 % of a drape's time was
// spent in the kernel's futex calls and libgomp's spinning (perf, default
// shirt). The guard makes every parallel region opened inside it (on this
// thread: the ICV is per thread) run on one thread. The loops only write
// zeros and markers, so the factor is the same bits.
class SerialOpenMP {
 public:
#ifdef _OPENMP
  SerialOpenMP() : previous_(omp_get_max_active_levels()) { omp_set_max_active_levels(0); }
  ~SerialOpenMP() { omp_set_max_active_levels(previous_); }

 private:
  int previous_;
#endif
};

// Eigen keeps CHOLMOD's factor protected; this exposes it read-only.
class SupernodalLLT final : public Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> {
 public:
  const cholmod_factor* factor() const { return m_cholmodFactor; }
};

// CHOLMOD's supernodal LL' (nested dissection) for the factorisation and the
// exact solve; preconditioning solves run on a float copy of its factor
// (supernodal_solve.hpp).
class CholmodCholesky final : public SparseCholesky {
 public:
  explicit CholmodCholesky(bool float_preconditioner) : float_preconditioner_(float_preconditioner) {
    // Nested dissection only: on the default T-shirt (10.5k dofs) it needs
    // 5.0e8 flops per factorisation against 7.1e8 for AMD, which CHOLMOD's
    // default (try AMD, then METIS) ends up close to; measured 67 vs 81 ms.
    cholmod_common& common = llt_.cholmod();
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_NESDIS;
    // A matrix that is not positive definite is an answer (factorize returns
    // false and the solver shifts the diagonal), not an error for the user's
    // terminal: CHOLMOD printed "warning: matrix not positive definite" there.
    common.print = 0;
    // One BLAS thread inside CHOLMOD, for every solver: these factorisations
    // are too small to gain from more (measured the same time), OpenBLAS's idle
    // threads spin against one-solver-per-core jobs (drape generate: 13.6 s
    // instead of 4.4 s per coarse drape), and a multi-threaded BLAS rounds
    // differently, which would make a drape depend on the thread count.
    set_blas_threads(1);
  }
  bool factorize(const SparseMatrix& a) override {
    const SerialOpenMP serial;
    if (!key_.same(a)) {
      // METIS (CHOLMOD's nested dissection) draws from one process-wide random
      // generator: two solvers ordering at the same moment (drape generate's
      // workers, most often the samples a resumed job starts together)
      // interleave its draws and get orderings that depend on the timing, so
      // drapes that round differently. One ordering at a time, each from
      // METIS's fixed seed, gives the same ordering whatever runs beside it.
      static std::mutex metis;
      const std::lock_guard<std::mutex> lock(metis);
      llt_.analyzePattern(a);
      key_.set(a);
      single_pattern_stale_ = true;
    }
    llt_.factorize(a);
    if (llt_.info() != Eigen::Success) return false;
    if (float_preconditioner_) {
      const cholmod_factor* l = llt_.factor();
      if (!l || !l->is_super || !l->is_ll || l->xtype != CHOLMOD_REAL || l->itype != CHOLMOD_INT)
        throw Error("cholmod: expected a real supernodal LL' factor with int indices");
      if (single_pattern_stale_)
        single_.set_pattern(static_cast<int>(l->n), static_cast<int>(l->nsuper), static_cast<const int*>(l->Perm),
                            static_cast<const int*>(l->super), static_cast<const int*>(l->pi),
                            static_cast<const int*>(l->px), static_cast<const int*>(l->s));
      single_pattern_stale_ = false;
      single_.set_values(static_cast<const double*>(l->x), l->xsize);
    }
    return true;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const override {
    const SerialOpenMP serial;
    return llt_.solve(b);
  }
  Eigen::VectorXd precondition(const Eigen::VectorXd& r) const override {
    if (!float_preconditioner_) return solve(r);
    Eigen::VectorXd z;
    single_.solve(r, z);
    return z;
  }
  std::string name() const override { return float_preconditioner_ ? "cholmod" : "cholmod (double preconditioner)"; }

 private:
  bool float_preconditioner_;
  SupernodalLLT llt_;
  PatternKey key_;
  FloatSupernodalFactor single_;
  bool single_pattern_stale_ = true;  // the float copy's pattern predates the last analysis
};
#endif

}  // namespace

bool cholmod_available() {
#ifdef DRAPE_HAVE_CHOLMOD
  return true;
#else
  return false;
#endif
}

std::unique_ptr<SparseCholesky> make_sparse_cholesky(const std::string& name, bool float_preconditioner) {
  if (name == "eigen" || (name == "auto" && !cholmod_available()))
    return std::make_unique<EigenBackedCholesky<Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>>>(
        "eigen");
  if (name == "cholmod" || name == "auto") {
#ifdef DRAPE_HAVE_CHOLMOD
    return std::make_unique<CholmodCholesky>(float_preconditioner);
#else
    throw ConfigError("linear_solver: cholmod was not found when drape was built (install libsuitesparse-dev); use eigen");
#endif
  }
  throw ConfigError("linear_solver: unknown '" + name + "'; known: auto, eigen, cholmod");
}

}  // namespace drape::physics
