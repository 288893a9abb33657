// All eigenpairs of a dense symmetric matrix: LAPACK dsyevd (divide and
// conquer; about 12x faster than Eigen's SelfAdjointEigenSolver here), with
// Eigen as the fallback when the build found no LAPACK.
#include "eigensolvers.hpp"

#include <drape/errors.hpp>

#include <Eigen/Eigenvalues>

#include <string>
#include <vector>

#ifdef DRAPE_HAVE_LAPACK
extern "C" void dsyevd_(const char* jobz, const char* uplo, const int* n, double* a, const int* lda, double* w,
                        double* work, const int* lwork, int* iwork, const int* liwork, int* info);
#endif

namespace drape::spectral_detail {

bool lapack_available() {
#ifdef DRAPE_HAVE_LAPACK
  return true;
#else
  return false;
#endif
}

void dense_eigs(const Eigen::SparseMatrix<double>& a, int k, Eigen::VectorXd& values, Eigen::MatrixXd& vectors) {
  const int n = static_cast<int>(a.rows());
  Eigen::MatrixXd m = Eigen::MatrixXd(a);
#ifdef DRAPE_HAVE_LAPACK
  Eigen::VectorXd w(n);
  int info = 0, lwork = -1, liwork = -1, iwork_query = 0;
  double work_query = 0;
  dsyevd_("V", "L", &n, m.data(), &n, w.data(), &work_query, &lwork, &iwork_query, &liwork, &info);
  lwork = static_cast<int>(work_query);
  liwork = iwork_query;
  std::vector<double> work(static_cast<std::size_t>(lwork));
  std::vector<int> iwork(static_cast<std::size_t>(liwork));
  dsyevd_("V", "L", &n, m.data(), &n, w.data(), work.data(), &lwork, iwork.data(), &liwork, &info);
  if (info != 0) throw Error("compute_eigenbasis: LAPACK dsyevd failed with info = " + std::to_string(info));
  values = w.head(k);
  vectors = m.leftCols(k);
#else
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(m);
  if (solver.info() != Eigen::Success) throw Error("compute_eigenbasis: the dense eigensolver did not converge");
  values = solver.eigenvalues().head(k);
  vectors = solver.eigenvectors().leftCols(k);
#endif
}

}  // namespace drape::spectral_detail
