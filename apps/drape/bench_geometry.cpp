// `drape bench geometry`: closest-point queries against a body-sized closed
// mesh, timed for the methods one could use (the project's BVH, a nanoflann
// kd-tree over vertices, CGAL's AABB tree when installed) on the same queries,
// each checked against exhaustive search.
#include "bench.hpp"
#include "bench_geometry.hpp"

#include <drape/errors.hpp>
#include <drape/geometry/closed_shapes.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/io/mesh_io.hpp>

#include <nanoflann.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <random>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

using bench::best_ms;
using bench::Problem;
using bench::Row;

// A torso-like closed tube: a torus stretched upright with bumps (concave and
// saddle regions, uneven triangles), so no method profits from a perfect shape.
Mesh tube_body(int ring, int tube) {
  Mesh m = geometry::torus(0.3, 0.11, ring, tube);
  for (int i = 0; i < m.num_vertices(); ++i) {
    Eigen::Vector3d p = m.vertices.row(i);
    p.x() *= 2.6;
    p *= 1 + 0.06 * std::sin(9 * p.x()) * std::cos(7 * p.z() + 0.5);
    m.vertices.row(i) = p;
  }
  return m;
}

// The body after a smooth morph (what update() sees between simulation steps).
Eigen::MatrixX3d morph(const Eigen::MatrixX3d& v, double amount) {
  Eigen::MatrixX3d out = v;
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    const Eigen::Vector3d p = v.row(i);
    out.row(i) = p * (1 + amount * std::sin(4 * p.x() + 3 * p.z()));
  }
  return out;
}

double exhaustive_distance(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f, const Eigen::Vector3d& p) {
  double best = INFINITY;
  for (Eigen::Index t = 0; t < f.rows(); ++t)
    best = std::min(best, (geometry::closest_point_on_triangle(p, v.row(f(t, 0)), v.row(f(t, 1)), v.row(f(t, 2))).point - p)
                              .squaredNorm());
  return std::sqrt(best);
}

// BodySurface's other ways to meet a moved body: its batch query, a tree
// built without normals, an update that leaves the normals to the queries,
// and queries started from the face each point was closest to before the
// body moved (what a push-out of one garment over many bodies does).
struct BvhExtras {
  double batch_us = 0, tree_only_ms = 0, on_demand_update_ms = 0, on_demand_query_us = 0, hinted_query_us = 0;
};

Row bench_bvh(const Problem& pb, BvhExtras& extras) {
  Row row;
  row.method = "drape BodySurface (BVH, median split, refit)";
  row.update_kind = "refit";
  row.build_ms = best_ms(pb.repeats, [&] { geometry::BodySurface s(pb.vertices, pb.faces); });
  geometry::BodySurface surface(pb.vertices, pb.faces);
  // Alternate between the two shapes so every update really moves the vertices.
  int flip = 0;
  row.update_ms = best_ms(pb.repeats, [&] { surface.update(++flip % 2 ? pb.vertices : pb.moved); });
  surface.update(pb.moved);
  extras.tree_only_ms = best_ms(pb.repeats, [&] { surface.rebuild(); });
  const double per_query = 1e3 / static_cast<double>(pb.queries.rows());
  std::vector<geometry::SurfacePoint> hits(pb.queries.rows());
  const double ms = best_ms(pb.repeats, [&] {
    for (Eigen::Index i = 0; i < pb.queries.rows(); ++i) hits[i] = surface.locate(pb.queries.row(i).transpose());
  });
  row.query_us = per_query * ms;
  extras.batch_us = per_query * best_ms(pb.repeats, [&] { hits = surface.locate_all(pb.queries); });

  geometry::BodySurface on_demand(pb.vertices, pb.faces);
  std::vector<int> before(static_cast<std::size_t>(pb.queries.rows()));  // each point's closest face before the morph
  for (Eigen::Index i = 0; i < pb.queries.rows(); ++i)
    before[static_cast<std::size_t>(i)] = on_demand.locate(pb.queries.row(i).transpose()).face;
  extras.on_demand_update_ms = best_ms(pb.repeats, [&] {
    on_demand.update(++flip % 2 ? pb.vertices : pb.moved, geometry::BodySurface::Normals::on_demand);
  });
  on_demand.update(pb.moved, geometry::BodySurface::Normals::on_demand);
  std::vector<geometry::SurfacePoint> same(pb.queries.rows());
  extras.on_demand_query_us = per_query * best_ms(pb.repeats, [&] {
    for (Eigen::Index i = 0; i < pb.queries.rows(); ++i) same[i] = on_demand.locate(pb.queries.row(i).transpose());
  });
  extras.hinted_query_us = per_query * best_ms(pb.repeats, [&] {
    for (Eigen::Index i = 0; i < pb.queries.rows(); ++i)
      same[i] = on_demand.locate_near(pb.queries.row(i).transpose(), before[static_cast<std::size_t>(i)]);
  });
  for (Eigen::Index i = 0; i < pb.queries.rows(); ++i)  // the same answers, or the rows above time another question
    if (same[i].signed_distance != hits[i].signed_distance)
      throw Error("bench geometry: a query with normals on demand and a hint answered differently at point " + std::to_string(i));
  for (int i = 0; i < pb.checked; ++i)
    row.max_error = std::max(row.max_error, std::abs(std::abs(hits[i].signed_distance) - pb.reference[i]));
  return row;
}

// Candidate triangles from a kd-tree over the vertices. A triangle at distance t
// has all its corners within t + L (L = longest edge of the mesh), so after a
// first guess d from the nearest vertex's faces, every triangle that can beat d
// touches a vertex within d + L: a radius search finds them all.
Row bench_kdtree(const Problem& pb) {
  using KdTree = nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixX3d, 3>;
  Row row;
  row.method = "nanoflann kd-tree over vertices + radius-bounded faces";
  row.update_kind = "rebuild";
  const Eigen::Index nv = pb.vertices.rows();
  std::vector<std::vector<int>> faces_of(nv);
  for (Eigen::Index f = 0; f < pb.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) faces_of[pb.faces(f, k)].push_back(static_cast<int>(f));
  auto longest_edge = [&](const Eigen::MatrixX3d& v) {
    double l = 0;
    for (Eigen::Index f = 0; f < pb.faces.rows(); ++f)
      for (int k = 0; k < 3; ++k) l = std::max(l, (v.row(pb.faces(f, k)) - v.row(pb.faces(f, (k + 1) % 3))).norm());
    return l;
  };
  row.build_ms = best_ms(pb.repeats, [&] {
    KdTree tree(3, std::cref(pb.vertices), 10);
    (void)longest_edge(pb.vertices);
  });
  std::unique_ptr<KdTree> tree;
  double edge = 0;
  row.update_ms = best_ms(pb.repeats, [&] {
    tree = std::make_unique<KdTree>(3, std::cref(pb.moved), 10);
    edge = longest_edge(pb.moved);
  });
  const Eigen::MatrixX3d& v = pb.moved;
  std::vector<double> distance(pb.queries.rows());
  std::vector<std::pair<KdTree::IndexType, double>> found;
  std::vector<int> seen(pb.faces.rows(), -1);
  int stamp = 0;
  const double ms = best_ms(pb.repeats, [&] {
    for (Eigen::Index i = 0; i < pb.queries.rows(); ++i) {
      const Eigen::Vector3d p = pb.queries.row(i);
      ++stamp;
      double best = INFINITY;
      auto try_faces = [&](KdTree::IndexType vertex) {
        for (int f : faces_of[vertex]) {
          if (seen[f] == stamp) continue;
          seen[f] = stamp;
          best = std::min(best, (geometry::closest_point_on_triangle(p, v.row(pb.faces(f, 0)), v.row(pb.faces(f, 1)),
                                                                     v.row(pb.faces(f, 2))).point - p).squaredNorm());
        }
      };
      KdTree::IndexType nearest = 0;
      double d2 = 0;
      tree->query(p.data(), 1, &nearest, &d2);
      try_faces(nearest);
      const double radius = std::sqrt(best) + edge;
      found.clear();
      tree->index->radiusSearch(p.data(), radius * radius, found, nanoflann::SearchParams());
      for (const auto& item : found) try_faces(item.first);
      distance[i] = std::sqrt(best);
    }
  });
  row.query_us = 1e3 * ms / static_cast<double>(pb.queries.rows());
  for (int i = 0; i < pb.checked; ++i) row.max_error = std::max(row.max_error, std::abs(distance[i] - pb.reference[i]));
  return row;
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape bench geometry");
  opts.add_options()("ring", po::value<int>()->default_value(112), "segments around the tube body")(
      "tube", po::value<int>()->default_value(58), "segments across the tube (vertices = ring * tube)")(
      "queries", po::value<int>()->default_value(4000), "query points within --band of the surface")(
      "band", po::value<double>()->default_value(0.02), "largest query offset from the surface, m")(
      "check", po::value<int>()->default_value(200), "queries verified by exhaustive search")(
      "repeats", po::value<int>()->default_value(3), "timings are the best of this many runs")(
      "body", po::value<std::string>(), "a mesh file to use as the body instead of the tube (e.g. a `drape body` output)");
  po::variables_map vm;
  if (!parse("drape bench geometry [--body FILE | --ring N --tube N] [--queries N] [--band M] [--check N] [--repeats N]", args, opts,
             {}, vm))
    return 0;
  const int ring = vm["ring"].as<int>(), tube = vm["tube"].as<int>(), nq = vm["queries"].as<int>();
  if (ring < 3 || tube < 3) throw UsageError("--ring and --tube must be at least 3");
  if (nq < 1 || vm["repeats"].as<int>() < 1) throw UsageError("--queries and --repeats must be positive");

  const Mesh body = vm.count("body") ? read_mesh(vm["body"].as<std::string>()) : tube_body(ring, tube);
  Problem pb;
  pb.vertices = body.vertices;
  pb.faces = body.faces;
  pb.moved = morph(body.vertices, 0.03);
  pb.repeats = vm["repeats"].as<int>();
  // Queries: random points of the morphed surface pushed in or out along the face normal.
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(0, 1);
  std::uniform_int_distribution<int> face(0, body.num_faces() - 1);
  const double band = vm["band"].as<double>();
  if (!(band >= 0 && band <= 1)) throw UsageError("--band " + std::to_string(band) + ": expected 0 to 1 m");
  pb.queries.resize(nq, 3);
  for (int i = 0; i < nq; ++i) {
    const int f = face(rng);
    double u = unit(rng), w = unit(rng);
    if (u + w > 1) u = 1 - u, w = 1 - w;
    const Eigen::Vector3d a = pb.moved.row(pb.faces(f, 0)), b = pb.moved.row(pb.faces(f, 1)), c = pb.moved.row(pb.faces(f, 2));
    pb.queries.row(i) = a + u * (b - a) + w * (c - a) + band * (2 * unit(rng) - 1) * (b - a).cross(c - a).normalized();
  }
  pb.checked = std::min(nq, vm["check"].as<int>());
  pb.reference.resize(pb.checked);
  for (int i = 0; i < pb.checked; ++i) pb.reference[i] = exhaustive_distance(pb.moved, pb.faces, pb.queries.row(i).transpose());

  std::cout << "body: " << (vm.count("body") ? vm["body"].as<std::string>() : "closed bumpy tube") << ", " << body.num_vertices() << " vertices, " << body.num_faces() << " triangles; "
            << nq << " queries within " << band << " m of the morphed surface; best of " << pb.repeats << " runs\n\n";
  BvhExtras extras;
  std::vector<Row> rows = {bench_bvh(pb, extras), bench_kdtree(pb)};
  if (auto cgal = bench::bench_cgal(pb)) rows.push_back(*cgal);
  std::cout << std::left << std::setw(52) << "method" << std::right << std::setw(11) << "build ms" << std::setw(11)
            << "update ms" << std::setw(9) << "update" << std::setw(12) << "query us/pt" << std::setw(11) << "max error\n";
  for (const Row& r : rows)
    std::cout << std::left << std::setw(52) << r.method << std::right << std::fixed << std::setprecision(2) << std::setw(11)
              << r.build_ms << std::setw(11) << r.update_ms << std::setw(9) << r.update_kind << std::setw(12)
              << std::setprecision(3) << r.query_us << std::setw(11) << std::scientific << std::setprecision(1)
              << r.max_error << std::defaultfloat << "\n";
  if (rows.size() < 3) std::cout << "(CGAL not found at build time: install libcgal-dev for its row)\n";
  std::cout << "\nBodySurface rows include the inside/outside sign and normal; the others give the closest point only.\n"
            << "BodySurface::locate_all (OpenMP, all cores): " << std::fixed << std::setprecision(3) << extras.batch_us
            << " us per point\n"
            << "BodySurface build without normals and edge pairing (BodySurface::rebuild): " << extras.tree_only_ms << " ms\n"
            << "BodySurface update leaving the normals to the queries (Normals::on_demand): " << extras.on_demand_update_ms
            << " ms; its queries " << std::setprecision(3) << extras.on_demand_query_us << " us per point, "
            << extras.hinted_query_us << " started at each point's closest face before the morph (locate_near)\n";
  return 0;
}

const RegisterBench registration{{"geometry", "time closest-point queries on a body-sized mesh (BVH vs kd-tree vs CGAL)", run}};

}  // namespace
}  // namespace drape::cli
