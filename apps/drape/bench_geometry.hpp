#pragma once
// Shared pieces of `drape bench geometry`: the closest-point methods it compares
// each report one row of timings on the same body and queries.
#include <Eigen/Core>

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace drape::cli::bench {

struct Row {
  std::string method;
  double build_ms = 0;
  double update_ms = 0;        // new vertex positions, same faces (refit or rebuild)
  std::string update_kind;     // "refit" or "rebuild"
  double query_us = 0;         // per point, one thread, closest point only (no sign)
  double max_error = 0;        // largest |distance - exhaustive distance| on the checked points
};

struct Problem {
  Eigen::MatrixX3d vertices, moved;  // the body and the same body morphed
  Eigen::MatrixX3i faces;
  Eigen::MatrixX3d queries;          // near the morphed body
  Eigen::VectorXd reference;         // exhaustive distances of the first `checked` queries to `moved`
  int checked = 0;
  int repeats = 3;
};

// Best of `repeats` runs of f, in milliseconds.
inline double best_ms(int repeats, const std::function<void()>& f) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

// CGAL's AABB tree, when CGAL's headers were found at build time.
std::optional<Row> bench_cgal(const Problem& problem);

}  // namespace drape::cli::bench
