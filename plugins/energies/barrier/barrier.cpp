// Barrier contact: pairs, value, gradient, Hessian (barrier.hpp).
#include "barrier.hpp"

#include "barrier_function.hpp"

#include <drape/element_assembly.hpp>
#include <drape/element_energy.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/box_pairs.hpp>
#include <drape/geometry/ccd.hpp>
#include <drape/geometry/vertex_areas.hpp>
#include <drape/psd_projection.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

namespace drape::barrier {

using geometry::Box;

// The garment's primitives (fixed at bind) and the body's (its faces fixed,
// its per-vertex quantities recomputed when it moves).
struct BarrierContact::Topology {
  Eigen::MatrixX3i garment_faces;
  std::vector<std::array<int, 2>> garment_edges;
  Eigen::VectorXd garment_vertex_area;   // m^2, material space
  Eigen::VectorXd garment_edge_area;     // m^2: a third of each adjacent face's material area
  Eigen::VectorXd garment_edge_rest2;    // m^2: squared material-space length (the mollifier's scale)
  int garment_vertices = 0;

  Eigen::MatrixX3i body_faces;
  std::vector<std::array<int, 2>> body_edges;
  // Of the body at `body_revision`: vertex areas, squared edge lengths, face and edge boxes.
  std::uint64_t body_revision = std::numeric_limits<std::uint64_t>::max();
  Eigen::VectorXd body_vertex_area;
  Eigen::VectorXd body_edge_length2;
  std::vector<Box> body_face_boxes, body_edge_boxes;
};

namespace {

std::vector<std::array<int, 2>> unique_edges(const Eigen::MatrixX3i& faces) {
  std::vector<std::array<int, 2>> edges;
  edges.reserve(static_cast<std::size_t>(faces.rows()) * 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

Box point_box(const Eigen::Vector3d& p, double inflate) {
  return {(p.array() - inflate).matrix(), (p.array() + inflate).matrix()};
}

void grow(Box& box, const Eigen::Vector3d& p) {
  box.lo = box.lo.cwiseMin(p);
  box.hi = box.hi.cwiseMax(p);
}

template <std::size_t K>
Box primitive_box(const std::array<int, K>& v, const Eigen::MatrixX3d& x, const Eigen::MatrixX3d* x_end, double inflate) {
  Box box = point_box(x.row(v[0]).transpose(), inflate);
  for (std::size_t k = 0; k < K; ++k) {
    const Eigen::Vector3d p = x.row(v[k]).transpose();
    grow(box, (p.array() - inflate).matrix());
    grow(box, (p.array() + inflate).matrix());
    if (x_end) {
      const Eigen::Vector3d q = x_end->row(v[k]).transpose();
      grow(box, (q.array() - inflate).matrix());
      grow(box, (q.array() + inflate).matrix());
    }
  }
  return box;
}

std::array<int, 3> face(const Eigen::MatrixX3i& faces, int f) { return {faces(f, 0), faces(f, 1), faces(f, 2)}; }

// Which of a pair's 4 points are garment vertices (the variables).
bool is_variable(PairKind kind, int point) {
  switch (kind) {
    case PairKind::GarmentVertexBodyFace: return point == 0;
    case PairKind::BodyVertexGarmentFace: return point >= 1;
    case PairKind::GarmentEdgeBodyEdge: break;
  }
  return point <= 1;
}

}  // namespace

BarrierContact::BarrierContact(const BarrierSettings& settings) : settings_(settings), topology_(std::make_unique<Topology>()) {
  if (!(settings_.distance > 0) || !std::isfinite(settings_.distance))
    throw ConfigError("barrier: distance (d_hat) must be a positive length, got " + std::to_string(settings_.distance));
  if (!(settings_.stiffness > 0) || !std::isfinite(settings_.stiffness))
    throw ConfigError("barrier: stiffness must be > 0, got " + std::to_string(settings_.stiffness));
  if (!(settings_.min_separation > 0 && settings_.min_separation < 1))
    throw ConfigError("barrier: min_separation must be in (0, 1)");
}

BarrierContact::~BarrierContact() = default;

void BarrierContact::bind(const EnergyContext& context) {
  const Garment& garment = checked_garment(context, "barrier");
  body_ = dynamic_cast<const geometry::BodySurface*>(context.body);
  if (!body_) throw ConfigError("barrier: needs the body as a triangle mesh (a BodySurface); none was given");
  Topology& t = *topology_;
  t.garment_faces = garment.mesh.faces;
  t.garment_vertices = garment.mesh.num_vertices();
  t.garment_edges = unique_edges(t.garment_faces);
  t.garment_vertex_area = geometry::vertex_areas(garment);
  // Each face's material area, a third to each of its edges.
  std::map<std::array<int, 2>, int> edge_index;
  for (std::size_t e = 0; e < t.garment_edges.size(); ++e) edge_index[t.garment_edges[e]] = static_cast<int>(e);
  t.garment_edge_area = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(t.garment_edges.size()));
  t.garment_edge_rest2 = Eigen::VectorXd::Zero(t.garment_edge_area.size());
  const Mesh& mesh = garment.mesh;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector2d uv[3] = {mesh.uv.row(mesh.uv_faces(f, 0)), mesh.uv.row(mesh.uv_faces(f, 1)),
                                   mesh.uv.row(mesh.uv_faces(f, 2))};
    const Eigen::Vector2d e1 = uv[1] - uv[0], e2 = uv[2] - uv[0];
    const double third = std::abs(e1.x() * e2.y() - e1.y() * e2.x()) / 6.0;
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      const int e = edge_index.at({std::min(a, b), std::max(a, b)});
      t.garment_edge_area[e] += third;
      t.garment_edge_rest2[e] = (uv[(k + 1) % 3] - uv[k]).squaredNorm();
    }
  }
  t.body_faces = body_->faces();
  t.body_edges = unique_edges(t.body_faces);
  t.body_revision = std::numeric_limits<std::uint64_t>::max();
  std::lock_guard<std::mutex> lock(cache_.mutex);
  cache_.pairs.reset();
}

void BarrierContact::check(const Eigen::MatrixX3d& x) const {
  if (!body_) throw Error("barrier: bind() was not called");
  if (x.rows() != topology_->garment_vertices)
    throw Error("barrier: " + std::to_string(x.rows()) + " vertices given, the bound garment has " +
                std::to_string(topology_->garment_vertices));
}

std::array<Eigen::Vector3d, 4> BarrierContact::pair_points(const ContactPair& pair, const Eigen::MatrixX3d& x) const {
  const Topology& t = *topology_;
  const Eigen::MatrixX3d& b = body_->vertices();
  auto gx = [&](int v) -> Eigen::Vector3d { return x.row(v).transpose(); };
  auto bx = [&](int v) -> Eigen::Vector3d { return b.row(v).transpose(); };
  switch (pair.kind) {
    case PairKind::GarmentVertexBodyFace:
      return {gx(pair.garment), bx(t.body_faces(pair.body, 0)), bx(t.body_faces(pair.body, 1)), bx(t.body_faces(pair.body, 2))};
    case PairKind::BodyVertexGarmentFace:
      return {bx(pair.body), gx(t.garment_faces(pair.garment, 0)), gx(t.garment_faces(pair.garment, 1)),
              gx(t.garment_faces(pair.garment, 2))};
    case PairKind::GarmentEdgeBodyEdge: break;
  }
  const auto& ge = t.garment_edges[static_cast<std::size_t>(pair.garment)];
  const auto& be = t.body_edges[static_cast<std::size_t>(pair.body)];
  return {gx(ge[0]), gx(ge[1]), bx(be[0]), bx(be[1])};
}

int BarrierContact::pair_vertices(const ContactPair& pair, std::array<int, 3>& vertex) const {
  const Topology& t = *topology_;
  switch (pair.kind) {
    case PairKind::GarmentVertexBodyFace: vertex[0] = pair.garment; return 1;
    case PairKind::BodyVertexGarmentFace: vertex = face(t.garment_faces, pair.garment); return 3;
    case PairKind::GarmentEdgeBodyEdge: break;
  }
  const auto& e = t.garment_edges[static_cast<std::size_t>(pair.garment)];
  vertex[0] = e[0];
  vertex[1] = e[1];
  return 2;
}

template <int N>
double BarrierContact::pair_derivatives(const ContactPair& pair, const Eigen::MatrixX3d& x, Eigen::Matrix<double, N, 1>& g,
                                        Eigen::Matrix<double, N, N>* h) const {
  const Topology& t = *topology_;
  const std::array<Eigen::Vector3d, 4> p = pair_points(pair, x);
  std::array<Vec3<Dual<N>>, 4> q;
  int next = 0;
  for (int k = 0; k < 4; ++k)
    q[static_cast<std::size_t>(k)] = is_variable(pair.kind, k) ? variable_point<N>(p[static_cast<std::size_t>(k)], 3 * next++)
                                                               : constant_point<N>(p[static_cast<std::size_t>(k)]);
  const double dhat2 = settings_.distance * settings_.distance;
  const Dual<N> s = typed_distance2(pair.type, q);
  const BarrierValue bv = log_barrier(s.v / dhat2);
  Dual<N> e = chain(s, bv.b, bv.db / dhat2, bv.d2b / (dhat2 * dhat2));
  double weight = 0;
  switch (pair.kind) {
    case PairKind::GarmentVertexBodyFace: weight = t.garment_vertex_area[pair.garment]; break;
    case PairKind::BodyVertexGarmentFace: weight = t.body_vertex_area[pair.body]; break;
    case PairKind::GarmentEdgeBodyEdge: {
      weight = t.garment_edge_area[pair.garment];
      const Vec3<Dual<N>> n = cross(q[1] - q[0], q[3] - q[2]);
      const Dual<N> c = dot(n, n);
      const double eps = 1e-3 * t.garment_edge_rest2[pair.garment] * t.body_edge_length2[pair.body];
      const MollifierValue mv = edge_mollifier(c.v, eps);
      if (mv.m != 1) e = chain(c, mv.m, mv.dm, mv.d2m) * e;
      break;
    }
  }
  const double scale = settings_.stiffness * settings_.distance * weight;
  g = scale * e.g;
  if (h) *h = scale * e.h;
  return scale * e.v;
}

double BarrierContact::pair_value(const ContactPair& pair, const Eigen::MatrixX3d& x) const {
  const Topology& t = *topology_;
  const std::array<Eigen::Vector3d, 4> p = pair_points(pair, x);
  const std::array<Vec3<double>, 4> q{plain_point(p[0]), plain_point(p[1]), plain_point(p[2]), plain_point(p[3])};
  const double dhat2 = settings_.distance * settings_.distance;
  double e = log_barrier(typed_distance2(pair.type, q) / dhat2).b;
  double weight = 0;
  switch (pair.kind) {
    case PairKind::GarmentVertexBodyFace: weight = t.garment_vertex_area[pair.garment]; break;
    case PairKind::BodyVertexGarmentFace: weight = t.body_vertex_area[pair.body]; break;
    case PairKind::GarmentEdgeBodyEdge: {
      weight = t.garment_edge_area[pair.garment];
      const Vec3<double> n = cross(q[1] - q[0], q[3] - q[2]);
      e *= edge_mollifier(dot(n, n), 1e-3 * t.garment_edge_rest2[pair.garment] * t.body_edge_length2[pair.body]).m;
      break;
    }
  }
  return settings_.stiffness * settings_.distance * weight * e;
}

std::shared_ptr<const std::vector<ContactPair>> BarrierContact::cached_pairs(const Eigen::MatrixX3d& x) const {
  check(x);
  std::lock_guard<std::mutex> lock(cache_.mutex);
  Topology& t = *topology_;
  const std::uint64_t revision = body_->revision();
  if (cache_.pairs && cache_.revision == revision && cache_.x.rows() == x.rows() && cache_.x == x) return cache_.pairs;

  const Eigen::MatrixX3d& body = body_->vertices();
  if (t.body_revision != revision) {
    // Body quantities: lumped face areas, edge lengths, boxes (faces, edges).
    const Eigen::Index nb = body.rows();
    t.body_vertex_area = Eigen::VectorXd::Zero(nb);
    t.body_face_boxes.resize(static_cast<std::size_t>(t.body_faces.rows()));
    for (Eigen::Index f = 0; f < t.body_faces.rows(); ++f) {
      const auto v = face(t.body_faces, static_cast<int>(f));
      const Eigen::Vector3d a = body.row(v[0]), b = body.row(v[1]), c = body.row(v[2]);
      const double third = (b - a).cross(c - a).norm() / 6.0;
      for (int k : v) t.body_vertex_area[k] += third;
      t.body_face_boxes[static_cast<std::size_t>(f)] = primitive_box(v, body, nullptr, 0.0);
    }
    t.body_edge_length2.resize(static_cast<Eigen::Index>(t.body_edges.size()));
    t.body_edge_boxes.resize(t.body_edges.size());
    for (std::size_t e = 0; e < t.body_edges.size(); ++e) {
      t.body_edge_length2[static_cast<Eigen::Index>(e)] = (body.row(t.body_edges[e][0]) - body.row(t.body_edges[e][1])).squaredNorm();
      t.body_edge_boxes[e] = primitive_box(t.body_edges[e], body, nullptr, 0.0);
    }
    t.body_revision = revision;
  }

  // Broad phase: garment boxes grown by d_hat against the body's, per kind.
  const double dhat = settings_.distance, dhat2 = dhat * dhat;
  std::vector<Box> garment_points(static_cast<std::size_t>(x.rows())), garment_faces(static_cast<std::size_t>(t.garment_faces.rows())),
      garment_edges(t.garment_edges.size()), body_points(static_cast<std::size_t>(body.rows()));
  for (Eigen::Index v = 0; v < x.rows(); ++v) garment_points[static_cast<std::size_t>(v)] = point_box(x.row(v).transpose(), dhat);
  for (Eigen::Index f = 0; f < t.garment_faces.rows(); ++f)
    garment_faces[static_cast<std::size_t>(f)] = primitive_box(face(t.garment_faces, static_cast<int>(f)), x, nullptr, dhat);
  for (std::size_t e = 0; e < t.garment_edges.size(); ++e) garment_edges[e] = primitive_box(t.garment_edges[e], x, nullptr, dhat);
  for (Eigen::Index v = 0; v < body.rows(); ++v) body_points[static_cast<std::size_t>(v)] = point_box(body.row(v).transpose(), 0.0);

  std::vector<ContactPair> candidates;
  for (auto [g, b] : geometry::overlapping_boxes(garment_points, t.body_face_boxes))
    candidates.push_back({PairKind::GarmentVertexBodyFace, g, b, {}, 0});
  for (auto [g, b] : geometry::overlapping_boxes(garment_faces, body_points))
    candidates.push_back({PairKind::BodyVertexGarmentFace, g, b, {}, 0});
  for (auto [g, b] : geometry::overlapping_boxes(garment_edges, t.body_edge_boxes))
    candidates.push_back({PairKind::GarmentEdgeBodyEdge, g, b, {}, 0});

  // Narrow phase: exact distances and types, in parallel; kept in candidate order.
  const int n = static_cast<int>(candidates.size());
  std::vector<char> keep(static_cast<std::size_t>(n), 0);
#pragma omp parallel for schedule(static) if (n >= 4096)
  for (int i = 0; i < n; ++i) {
    ContactPair& c = candidates[static_cast<std::size_t>(i)];
    const std::array<Eigen::Vector3d, 4> p = pair_points(c, x);
    if (c.kind == PairKind::GarmentEdgeBodyEdge) {
      c.distance2 = geometry::edge_edge_distance2(p[0], p[1], p[2], p[3]);
      if (c.distance2 < dhat2) c.type = edge_edge_type(p[0], p[1], p[2], p[3]);
    } else {
      c.distance2 = geometry::point_triangle_distance2(p[0], p[1], p[2], p[3]);
      if (c.distance2 < dhat2) c.type = point_triangle_type(p[0], p[1], p[2], p[3]);
    }
    keep[static_cast<std::size_t>(i)] = c.distance2 < dhat2;
  }
  auto pairs = std::make_shared<std::vector<ContactPair>>();
  for (int i = 0; i < n; ++i)
    if (keep[static_cast<std::size_t>(i)]) pairs->push_back(candidates[static_cast<std::size_t>(i)]);
  cache_.x = x;
  cache_.revision = revision;
  cache_.pairs = pairs;
  return pairs;
}

std::vector<ContactPair> BarrierContact::pairs(const Eigen::MatrixX3d& x) const { return *cached_pairs(x); }

double BarrierContact::min_distance(const Eigen::MatrixX3d& x) const {
  double d2 = std::numeric_limits<double>::infinity();
  for (const ContactPair& p : *cached_pairs(x)) d2 = std::min(d2, p.distance2);
  return std::sqrt(d2);
}

double BarrierContact::value(const Eigen::MatrixX3d& x) const {
  const auto pairs = cached_pairs(x);
  for (const ContactPair& p : *pairs)
    if (!(p.distance2 > 0)) return std::numeric_limits<double>::infinity();
  return deterministic_sum(static_cast<int>(pairs->size()), [&](int i) { return pair_value((*pairs)[static_cast<std::size_t>(i)], x); });
}

namespace {

[[noreturn]] void touching(const ContactPair& p) {
  throw Error("barrier: garment " +
              std::string(p.kind == PairKind::GarmentVertexBodyFace   ? "vertex " :
                          p.kind == PairKind::BodyVertexGarmentFace ? "face " : "edge ") +
              std::to_string(p.garment) + " touches the body (distance 0): the state is not separated from the body");
}

}  // namespace

double BarrierContact::add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const {
  const auto pairs = cached_pairs(x);
  const int n = static_cast<int>(pairs->size());
  for (const ContactPair& p : *pairs)
    if (!(p.distance2 > 0)) touching(p);
  // Per-pair gradients in parallel, gathered in pair order (deterministic).
  std::vector<Eigen::Matrix<double, 9, 1>> grads(static_cast<std::size_t>(n));
  std::vector<double> values(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static) if (n >= 1024)
  for (int i = 0; i < n; ++i) {
    const ContactPair& p = (*pairs)[static_cast<std::size_t>(i)];
    auto& out = grads[static_cast<std::size_t>(i)];
    out.setZero();
    double v = 0;
    switch (p.kind) {
      case PairKind::GarmentVertexBodyFace: {
        Eigen::Matrix<double, 3, 1> ge;
        v = pair_derivatives<3>(p, x, ge, nullptr);
        out.head<3>() = ge;
        break;
      }
      case PairKind::BodyVertexGarmentFace: {
        Eigen::Matrix<double, 9, 1> ge;
        v = pair_derivatives<9>(p, x, ge, nullptr);
        out = ge;
        break;
      }
      case PairKind::GarmentEdgeBodyEdge: {
        Eigen::Matrix<double, 6, 1> ge;
        v = pair_derivatives<6>(p, x, ge, nullptr);
        out.head<6>() = ge;
        break;
      }
    }
    values[static_cast<std::size_t>(i)] = v;
  }
  double total = 0;
  std::array<int, 3> vertex{};
  for (int i = 0; i < n; ++i) {
    const int k = pair_vertices((*pairs)[static_cast<std::size_t>(i)], vertex);
    for (int j = 0; j < k; ++j) g.row(vertex[static_cast<std::size_t>(j)]) += grads[static_cast<std::size_t>(i)].segment<3>(3 * j).transpose();
    total += values[static_cast<std::size_t>(i)];
  }
  return total;
}

void BarrierContact::hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd, bool lower) const {
  const auto pairs = cached_pairs(x);
  const int n = static_cast<int>(pairs->size());
  for (const ContactPair& p : *pairs)
    if (!(p.distance2 > 0)) touching(p);
  // Slots: each pair writes its blocks at a fixed offset (prefix sum).
  std::vector<std::size_t> offset(static_cast<std::size_t>(n) + 1, h.size());
  std::array<int, 3> vertex{};
  for (int i = 0; i < n; ++i) {
    const int k = pair_vertices((*pairs)[static_cast<std::size_t>(i)], vertex);
    const std::size_t entries = k == 1 ? hessian_entries<1>(lower) : k == 2 ? hessian_entries<2>(lower) : hessian_entries<3>(lower);
    offset[static_cast<std::size_t>(i) + 1] = offset[static_cast<std::size_t>(i)] + entries;
  }
  h.resize(offset.back());
#pragma omp parallel for schedule(static) if (n >= 512)
  for (int i = 0; i < n; ++i) {
    const ContactPair& p = (*pairs)[static_cast<std::size_t>(i)];
    std::array<int, 3> v{};
    pair_vertices(p, v);
    Eigen::Triplet<double>* out = h.data() + offset[static_cast<std::size_t>(i)];
    switch (p.kind) {
      case PairKind::GarmentVertexBodyFace: {
        Eigen::Matrix<double, 3, 1> g;
        Eigen::Matrix<double, 3, 3> block;
        pair_derivatives<3>(p, x, g, &block);
        if (project_psd) project_to_psd<3>(block);
        write_element_hessian<1>(block, v.data(), lower, out);
        break;
      }
      case PairKind::BodyVertexGarmentFace: {
        Eigen::Matrix<double, 9, 1> g;
        Eigen::Matrix<double, 9, 9> block;
        pair_derivatives<9>(p, x, g, &block);
        if (project_psd) project_to_psd<9>(block);
        write_element_hessian<3>(block, v.data(), lower, out);
        break;
      }
      case PairKind::GarmentEdgeBodyEdge: {
        Eigen::Matrix<double, 6, 1> g;
        Eigen::Matrix<double, 6, 6> block;
        pair_derivatives<6>(p, x, g, &block);
        if (project_psd) project_to_psd<6>(block);
        write_element_hessian<2>(block, v.data(), lower, out);
        break;
      }
    }
  }
}

void BarrierContact::add_hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd) const {
  hessian(x, h, project_psd, false);
}
void BarrierContact::add_hessian_lower(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd) const {
  hessian(x, h, project_psd, true);
}

double BarrierContact::max_step(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& dx, const Eigen::MatrixX3d* body_from,
                                const Eigen::MatrixX3d* body_to) const {
  check(x);
  if (dx.rows() != x.rows()) throw Error("barrier: max_step's move has the wrong vertex count");
  const Topology& t = *topology_;
  const Eigen::MatrixX3d& b0 = body_from ? *body_from : body_->vertices();
  const Eigen::MatrixX3d& b1 = body_to ? *body_to : b0;
  if (b0.rows() != body_->vertices().rows() || b1.rows() != b0.rows())
    throw Error("barrier: max_step's body motion has the wrong vertex count");
  const Eigen::MatrixX3d x1 = x + dx;
  const Eigen::MatrixX3d db = b1 - b0;

  // Candidates: swept boxes that overlap (a pair whose boxes never meet cannot touch).
  std::vector<Box> gp(static_cast<std::size_t>(x.rows())), gf(static_cast<std::size_t>(t.garment_faces.rows())),
      ge(t.garment_edges.size()), bp(static_cast<std::size_t>(b0.rows())), bf(static_cast<std::size_t>(t.body_faces.rows())),
      be(t.body_edges.size());
  for (Eigen::Index v = 0; v < x.rows(); ++v) gp[static_cast<std::size_t>(v)] = primitive_box(std::array<int, 1>{static_cast<int>(v)}, x, &x1, 0.0);
  for (Eigen::Index f = 0; f < t.garment_faces.rows(); ++f)
    gf[static_cast<std::size_t>(f)] = primitive_box(face(t.garment_faces, static_cast<int>(f)), x, &x1, 0.0);
  for (std::size_t e = 0; e < ge.size(); ++e) ge[e] = primitive_box(t.garment_edges[e], x, &x1, 0.0);
  for (Eigen::Index v = 0; v < b0.rows(); ++v) bp[static_cast<std::size_t>(v)] = primitive_box(std::array<int, 1>{static_cast<int>(v)}, b0, &b1, 0.0);
  for (Eigen::Index f = 0; f < t.body_faces.rows(); ++f)
    bf[static_cast<std::size_t>(f)] = primitive_box(face(t.body_faces, static_cast<int>(f)), b0, &b1, 0.0);
  for (std::size_t e = 0; e < be.size(); ++e) be[e] = primitive_box(t.body_edges[e], b0, &b1, 0.0);

  const auto pt = geometry::overlapping_boxes(gp, bf);
  const auto tp = geometry::overlapping_boxes(gf, bp);
  const auto ee = geometry::overlapping_boxes(ge, be);
  const double s = settings_.min_separation;
  auto g0 = [&](int v) -> Eigen::Vector3d { return x.row(v).transpose(); };
  auto gd = [&](int v) -> Eigen::Vector3d { return dx.row(v).transpose(); };
  auto c0 = [&](int v) -> Eigen::Vector3d { return b0.row(v).transpose(); };
  auto cd = [&](int v) -> Eigen::Vector3d { return db.row(v).transpose(); };

  double alpha = 1.0;
  const int npt = static_cast<int>(pt.size()), ntp = static_cast<int>(tp.size()), nee = static_cast<int>(ee.size());
#pragma omp parallel for schedule(dynamic, 256) reduction(min : alpha)
  for (int i = 0; i < npt; ++i) {
    const auto [v, f] = pt[static_cast<std::size_t>(i)];
    const auto c = face(t.body_faces, f);
    alpha = std::min(alpha, geometry::point_triangle_ccd(g0(v), gd(v), c0(c[0]), cd(c[0]), c0(c[1]), cd(c[1]), c0(c[2]), cd(c[2]), s));
  }
#pragma omp parallel for schedule(dynamic, 256) reduction(min : alpha)
  for (int i = 0; i < ntp; ++i) {
    const auto [f, v] = tp[static_cast<std::size_t>(i)];
    const auto c = face(t.garment_faces, f);
    alpha = std::min(alpha, geometry::point_triangle_ccd(c0(v), cd(v), g0(c[0]), gd(c[0]), g0(c[1]), gd(c[1]), g0(c[2]), gd(c[2]), s));
  }
#pragma omp parallel for schedule(dynamic, 256) reduction(min : alpha)
  for (int i = 0; i < nee; ++i) {
    const auto [eg, eb] = ee[static_cast<std::size_t>(i)];
    const auto& a = t.garment_edges[static_cast<std::size_t>(eg)];
    const auto& b = t.body_edges[static_cast<std::size_t>(eb)];
    alpha = std::min(alpha, geometry::edge_edge_ccd(g0(a[0]), gd(a[0]), g0(a[1]), gd(a[1]), c0(b[0]), cd(b[0]), c0(b[1]), cd(b[1]), s));
  }
  return alpha;
}

}  // namespace drape::barrier
