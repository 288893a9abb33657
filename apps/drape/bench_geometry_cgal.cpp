// The CGAL AABB-tree row of `drape bench geometry`. CGAL is optional (not in
// scripts/setup.sh): without its headers this row is simply absent.
#include "bench_geometry.hpp"

#if __has_include(<CGAL/AABB_tree.h>)
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>

namespace drape::cli::bench {

std::optional<Row> bench_cgal(const Problem& problem) {
  using Kernel = CGAL::Simple_cartesian<double>;
  using Triangle = Kernel::Triangle_3;
  using Iterator = std::vector<Triangle>::const_iterator;
  using Primitive = CGAL::AABB_triangle_primitive<Kernel, Iterator>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
  auto triangles = [&](const Eigen::MatrixX3d& v) {
    std::vector<Triangle> t;
    t.reserve(problem.faces.rows());
    for (Eigen::Index f = 0; f < problem.faces.rows(); ++f) {
      auto corner = [&](int k) {
        const auto r = v.row(problem.faces(f, k));
        return Kernel::Point_3(r[0], r[1], r[2]);
      };
      t.emplace_back(corner(0), corner(1), corner(2));
    }
    return t;
  };
  Row row;
  row.method = "CGAL AABB_tree (+ accelerate_distance_queries)";
  row.update_kind = "rebuild";
  std::vector<Triangle> body = triangles(problem.vertices), moved = triangles(problem.moved);
  row.build_ms = best_ms(problem.repeats, [&] {
    Tree tree(body.cbegin(), body.cend());
    tree.accelerate_distance_queries();
  });
  // CGAL trees cannot refit: a moving body means a new tree (triangles copied in too).
  Tree tree;
  row.update_ms = best_ms(problem.repeats, [&] {
    moved = triangles(problem.moved);
    tree.rebuild(moved.cbegin(), moved.cend());
    tree.accelerate_distance_queries();
  });
  std::vector<Kernel::Point_3> closest(problem.queries.rows());
  const double ms = best_ms(problem.repeats, [&] {
    for (Eigen::Index i = 0; i < problem.queries.rows(); ++i)
      closest[i] = tree.closest_point(Kernel::Point_3(problem.queries(i, 0), problem.queries(i, 1), problem.queries(i, 2)));
  });
  row.query_us = 1e3 * ms / static_cast<double>(problem.queries.rows());
  for (int i = 0; i < problem.checked; ++i) {
    const Kernel::Point_3 q(problem.queries(i, 0), problem.queries(i, 1), problem.queries(i, 2));
    row.max_error = std::max(row.max_error, std::abs(std::sqrt(CGAL::squared_distance(q, closest[i])) - problem.reference[i]));
  }
  return row;
}

}  // namespace drape::cli::bench

#else

namespace drape::cli::bench {
std::optional<Row> bench_cgal(const Problem&) { return std::nullopt; }
}  // namespace drape::cli::bench

#endif
