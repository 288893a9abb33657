#include <drape/geometry/topology.hpp>

#include <drape/errors.hpp>

#include <algorithm>
#include <numeric>
#include <sstream>
#include <vector>

namespace drape::geometry {
namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      int& p = parent[static_cast<std::size_t>(x)];
      p = parent[static_cast<std::size_t>(p)];  // path halving
      x = p;
    }
    return x;
  }
  bool unite(int a, int b) {
    a = find(a), b = find(b);
    if (a == b) return false;
    parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    return true;
  }
};

// A directed half-edge with the face it belongs to; sorted by undirected key.
struct HalfEdge {
  int lo, hi;  // undirected key
  bool forward;  // runs lo -> hi in its face
  bool operator<(const HalfEdge& o) const { return lo != o.lo ? lo < o.lo : hi < o.hi; }
};

}  // namespace

std::string TopologyReport::str() const {
  std::ostringstream s;
  s << "V=" << num_vertices << " F=" << num_faces << " E=" << num_edges << " boundary_edges=" << boundary_edges
    << " boundary_loops=" << boundary_loops << " nonmanifold_edges=" << nonmanifold_edges
    << " nonmanifold_vertices=" << nonmanifold_vertices << " misoriented_edges=" << misoriented_edges
    << " unreferenced_vertices=" << unreferenced_vertices << " euler=" << euler_characteristic;
  return s.str();
}

TopologyReport check_topology(const Eigen::MatrixX3i& faces, int num_vertices) {
  TopologyReport r;
  r.num_vertices = num_vertices;
  r.num_faces = static_cast<int>(faces.rows());
  if (faces.size() > 0 && (faces.minCoeff() < 0 || faces.maxCoeff() >= num_vertices))
    throw Error("check_topology: a face refers to a vertex outside [0, " + std::to_string(num_vertices) + ")");

  std::vector<HalfEdge> half;
  half.reserve(static_cast<std::size_t>(faces.rows()) * 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int u = faces(f, k), v = faces(f, (k + 1) % 3);
      half.push_back({std::min(u, v), std::max(u, v), u < v});
    }
  std::sort(half.begin(), half.end());

  UnionFind boundary(static_cast<std::size_t>(num_vertices));
  std::vector<char> on_boundary(static_cast<std::size_t>(num_vertices), 0);
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i;
    int forward = 0;
    while (j < half.size() && half[j].lo == half[i].lo && half[j].hi == half[i].hi) forward += half[j++].forward;
    const std::size_t count = j - i;
    ++r.num_edges;
    if (count == 1) {
      ++r.boundary_edges;
      boundary.unite(half[i].lo, half[i].hi);
      on_boundary[static_cast<std::size_t>(half[i].lo)] = on_boundary[static_cast<std::size_t>(half[i].hi)] = 1;
    } else if (count > 2) {
      if (r.nonmanifold_edges++ == 0) r.first_nonmanifold_edge = {half[i].lo, half[i].hi};
    } else if (forward != 1) {
      ++r.misoriented_edges;
    }
    i = j;
  }
  for (int v = 0; v < num_vertices; ++v)
    if (on_boundary[static_cast<std::size_t>(v)] && boundary.find(v) == v) ++r.boundary_loops;

  // A vertex is manifold when its faces form one fan: the edges opposite to it
  // (its link) must be connected.
  std::vector<int> start(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++start[static_cast<std::size_t>(faces(f, k)) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> incident(static_cast<std::size_t>(start.back()));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) incident[static_cast<std::size_t>(fill[static_cast<std::size_t>(faces(f, k))]++)] = static_cast<int>(f);
  std::vector<int> link;
  for (int v = 0; v < num_vertices; ++v) {
    const int b = start[static_cast<std::size_t>(v)], e = start[static_cast<std::size_t>(v) + 1];
    if (b == e) {
      ++r.unreferenced_vertices;
      continue;
    }
    link.clear();
    for (int i = b; i < e; ++i)
      for (int k = 0; k < 3; ++k)
        if (faces(incident[static_cast<std::size_t>(i)], k) != v) link.push_back(faces(incident[static_cast<std::size_t>(i)], k));
    std::sort(link.begin(), link.end());
    link.erase(std::unique(link.begin(), link.end()), link.end());
    UnionFind uf(link.size());
    int components = static_cast<int>(link.size());
    auto slot = [&](int x) { return static_cast<int>(std::lower_bound(link.begin(), link.end(), x) - link.begin()); };
    for (int i = b; i < e; ++i) {
      int other[2], n = 0;
      for (int k = 0; k < 3; ++k)
        if (faces(incident[static_cast<std::size_t>(i)], k) != v && n < 2) other[n++] = faces(incident[static_cast<std::size_t>(i)], k);
      if (n == 2 && uf.unite(slot(other[0]), slot(other[1]))) --components;
    }
    if (components != 1) ++r.nonmanifold_vertices;
  }
  r.euler_characteristic = num_vertices - r.num_edges + r.num_faces;
  return r;
}

}  // namespace drape::geometry
