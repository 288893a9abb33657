// Barrier contact: pairs, value, gradient, Hessian (barrier.hpp).
#include "barrier.hpp"
#include "friction.hpp"

#include "barrier_state.hpp"

#include <drape/element_assembly.hpp>
#include <drape/element_energy.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/box_pairs.hpp>
#include <drape/geometry/ccd.hpp>
#include <drape/geometry/pair_distance.hpp>
#include <drape/geometry/vertex_areas.hpp>
#include <drape/energy_input.hpp>
#include <drape/physics/barrier_function.hpp>
#include <drape/physics/psd_projection.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

namespace drape::barrier {

using geometry::Box;
using geometry::MeshBoxes;
using geometry::mesh_boxes;
using geometry::edge_edge_type;
using geometry::point_triangle_type;
using geometry::typed_distance2;

namespace {

std::array<int, 3> face(const Eigen::MatrixX3i& faces, int f) { return {faces(f, 0), faces(f, 1), faces(f, 2)}; }

double median(Eigen::VectorXd values) {
  if (values.size() == 0) return 0;
  auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// Which of a pair's 4 points are garment vertices (the variables).
bool is_variable(PairKind kind, int point) {
  switch (kind) {
    case PairKind::GarmentVertexBodyFace: return point == 0;
    case PairKind::BodyVertexGarmentFace: return point >= 1;
    case PairKind::GarmentEdgeBodyEdge: break;
  }
  return point <= 1;
}

// Calls f(std::integral_constant<int, K>{}) with K the number of garment
// vertices of a pair of this kind (1, 3 or 2): the size of its stencil.
template <class F>
void with_stencil_size(PairKind kind, F&& f) {
  switch (kind) {
    case PairKind::GarmentVertexBodyFace: f(std::integral_constant<int, 1>{}); return;
    case PairKind::BodyVertexGarmentFace: f(std::integral_constant<int, 3>{}); return;
    case PairKind::GarmentEdgeBodyEdge: f(std::integral_constant<int, 2>{}); return;
  }
}

[[noreturn]] void touching(const ContactPair& p) {
  throw Error("garment " +
              std::string(p.kind == PairKind::GarmentVertexBodyFace   ? "vertex " :
                          p.kind == PairKind::BodyVertexGarmentFace ? "face " : "edge ") +
              std::to_string(p.garment) + " touches the body (distance 0): the state is not separated from the body");
}

}  // namespace

BarrierContact::BarrierContact(const BarrierSettings& settings) : settings_(settings), topology_(std::make_unique<Topology>()) {
  check_barrier_settings(settings_.distance, settings_.stiffness, settings_.min_separation);
  if (!(settings_.friction >= 0) || !std::isfinite(settings_.friction))
    throw ConfigError("friction must be >= 0, got " + std::to_string(settings_.friction));
  if (!(settings_.slip_velocity > 0) || !std::isfinite(settings_.slip_velocity))
    throw ConfigError("slip_velocity must be a positive speed, got " + std::to_string(settings_.slip_velocity));
  if (settings_.friction > 0) friction_ = std::make_unique<Friction>(*this);
}

BarrierContact::~BarrierContact() = default;

void BarrierContact::bind(const EnergyContext& context) {
  const Garment& garment = checked_garment(context);
  body_ = dynamic_cast<const geometry::BodySurface*>(context.body);
  if (!body_) throw ConfigError("needs the body as a triangle mesh (a BodySurface); none was given");
  Topology& t = *topology_;
  t.garment_faces = garment.mesh.faces;
  t.garment_vertices = garment.mesh.num_vertices();
  t.garment_edges = geometry::edge_list(t.garment_faces);
  t.garment_vertex_area = geometry::vertex_areas(garment);
  geometry::EdgeWeights edges = geometry::edge_weights(garment, t.garment_edges);
  t.garment_edge_area = std::move(edges.area);
  t.garment_edge_rest2 = std::move(edges.length2);
  t.body_faces = body_->faces();
  t.body_edges = geometry::edge_list(t.body_faces);
  std::lock_guard<std::mutex> lock(cache_.mutex);
  cache_.body.reset();
  cache_.pairs.reset();
}

void BarrierContact::check(const Eigen::MatrixX3d& x) const {
  if (!body_) throw Error("bind() was not called");
  check_energy_input(x, topology_->garment_vertices);
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

template <class S>
S BarrierContact::pair_energy(const ContactPair& pair, const BodyState& body, const std::array<Vec3<S>, 4>& q) const {
  const Topology& t = *topology_;
  const double dhat2 = settings_.distance * settings_.distance;
  const S s = typed_distance2(pair.type, q);
  const BarrierValue bv = log_barrier(primal(s) / dhat2);
  S e = chain(s, bv.b, bv.db / dhat2, bv.d2b / (dhat2 * dhat2));
  if (pair.kind == PairKind::GarmentEdgeBodyEdge) {
    const Vec3<S> n = cross(q[1] - q[0], q[3] - q[2]);
    const S c = dot(n, n);
    const MollifierValue mv = edge_mollifier(primal(c), 1e-3 * t.garment_edge_rest2[pair.garment] * body.edge_length2[pair.body]);
    if (mv.m != 1) e = chain(c, mv.m, mv.dm, mv.d2m) * e;
  }
  return (settings_.stiffness * settings_.distance * pair_area(pair, body)) * e;
}

double BarrierContact::pair_area(const ContactPair& pair, const BodyState& body) const {
  switch (pair.kind) {
    case PairKind::GarmentVertexBodyFace: return topology_->garment_vertex_area[pair.garment];
    case PairKind::BodyVertexGarmentFace: return body.vertex_area[pair.body];
    case PairKind::GarmentEdgeBodyEdge: break;
  }
  return topology_->garment_edge_area[pair.garment];
}

template <class D>
D BarrierContact::pair_dual(const ContactPair& pair, const BodyState& body, const Eigen::MatrixX3d& x) const {
  const std::array<Eigen::Vector3d, 4> p = pair_points(pair, x);
  std::array<Vec3<D>, 4> q;
  int next = 0;
  for (std::size_t k = 0; k < 4; ++k)
    q[k] = is_variable(pair.kind, static_cast<int>(k)) ? variable_point<D>(p[k], 3 * next++) : constant_point<D>(p[k]);
  return pair_energy(pair, body, q);
}

std::shared_ptr<const BarrierContact::BodyState> BarrierContact::body_state_locked() const {
  const std::uint64_t revision = body_->revision();
  if (cache_.body && cache_.body->revision == revision) return cache_.body;
  const Topology& t = *topology_;
  const Eigen::MatrixX3d& body = body_->vertices();
  auto state = std::make_shared<BodyState>();
  state->revision = revision;
  state->vertex_area = Eigen::VectorXd::Zero(body.rows());
  for (Eigen::Index f = 0; f < t.body_faces.rows(); ++f) {
    const auto v = face(t.body_faces, static_cast<int>(f));
    const Eigen::Vector3d a = body.row(v[0]), b = body.row(v[1]), c = body.row(v[2]);
    const double third = (b - a).cross(c - a).norm() / 6.0;
    for (int k : v) state->vertex_area[k] += third;
  }
  state->edge_length2.resize(static_cast<Eigen::Index>(t.body_edges.size()));
  for (std::size_t e = 0; e < t.body_edges.size(); ++e)
    state->edge_length2[static_cast<Eigen::Index>(e)] = (body.row(t.body_edges[e][0]) - body.row(t.body_edges[e][1])).squaredNorm();
  // Grid cells as large as the typical garment or body edge, whichever is
  // longer: cells of the body's (shorter) edges alone made each garment box
  // visit dozens of cells, and the queries took a sixth of a drape.
  const double cell = std::sqrt(std::max(median(t.garment_edge_rest2), median(state->edge_length2)));
  MeshBoxes boxes = mesh_boxes(body, nullptr, t.body_faces, t.body_edges, 0.0);
  state->points = geometry::BoxGrid(std::move(boxes.points), cell);
  state->faces = geometry::BoxGrid(std::move(boxes.faces), cell);
  state->edges = geometry::BoxGrid(std::move(boxes.edges), cell);
  cache_.body = state;
  return state;
}

std::shared_ptr<const BarrierContact::BodyState> BarrierContact::body_state() const {
  std::lock_guard<std::mutex> lock(cache_.mutex);
  return body_state_locked();
}

std::shared_ptr<const BarrierContact::PairSet> BarrierContact::cached_pairs(const Eigen::MatrixX3d& x) const {
  check(x);
  std::lock_guard<std::mutex> lock(cache_.mutex);
  const std::shared_ptr<const BodyState> body = body_state_locked();
  if (cache_.pairs && cache_.pairs->body == body && cache_.x == x) return cache_.pairs;

  // Broad phase: the garment's boxes grown by d_hat + skin against the body's,
  // per kind, kept while no garment coordinate has moved more than the skin
  // since (a Verlet list): a pair within d_hat now was within d_hat + skin of
  // overlapping then. The line search's trials and the next iterations move
  // the cloth by less than that, and rebuilding the candidates for each cost
  // a sixth of a drape. The narrow phase below keeps exactly the pairs within
  // d_hat, in candidate order, which is the (garment, body) order of every
  // kind whatever the skin, so the pairs are those a fresh search finds.
  const double skin = candidate_skin();
  if (!(cache_.candidates_body == body && cache_.candidates_x.rows() == x.rows() &&
        (x - cache_.candidates_x).cwiseAbs().maxCoeff() <= skin)) {
    const Topology& t = *topology_;
    const MeshBoxes garment = mesh_boxes(x, nullptr, t.garment_faces, t.garment_edges, settings_.distance + skin);
    cache_.candidates.clear();
    for (auto [g, b] : body->faces.overlapping(garment.points))
      cache_.candidates.push_back({PairKind::GarmentVertexBodyFace, g, b, {}, 0});
    for (auto [g, b] : body->points.overlapping(garment.faces))
      cache_.candidates.push_back({PairKind::BodyVertexGarmentFace, g, b, {}, 0});
    for (auto [g, b] : body->edges.overlapping(garment.edges))
      cache_.candidates.push_back({PairKind::GarmentEdgeBodyEdge, g, b, {}, 0});
    cache_.candidates_x = x;
    cache_.candidates_body = body;
  }
  const double dhat2 = settings_.distance * settings_.distance;
  std::vector<ContactPair> candidates = cache_.candidates;

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
  auto set = std::make_shared<PairSet>();
  set->body = body;
  for (int i = 0; i < n; ++i)
    if (keep[static_cast<std::size_t>(i)]) set->pairs.push_back(candidates[static_cast<std::size_t>(i)]);
  cache_.x = x;
  cache_.pairs = set;
  return set;
}

double BarrierContact::value(const Eigen::MatrixX3d& x) const {
  const auto set = cached_pairs(x);
  const std::vector<ContactPair>& pairs = set->pairs;
  for (const ContactPair& p : pairs)
    if (!(p.distance2 > 0)) return std::numeric_limits<double>::infinity();
  return deterministic_sum(static_cast<int>(pairs.size()), [&](int i) {
    const ContactPair& pair = pairs[static_cast<std::size_t>(i)];
    const std::array<Eigen::Vector3d, 4> p = pair_points(pair, x);
    return pair_energy(pair, *set->body, std::array<Vec3<double>, 4>{plain_point(p[0]), plain_point(p[1]), plain_point(p[2]), plain_point(p[3])});
  });
}

double BarrierContact::add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const {
  const auto set = cached_pairs(x);
  const std::vector<ContactPair>& pairs = set->pairs;
  const int n = static_cast<int>(pairs.size());
  for (const ContactPair& p : pairs)
    if (!(p.distance2 > 0)) touching(p);
  // Per-pair gradients in parallel, gathered in pair order (deterministic).
  std::vector<Eigen::Matrix<double, 9, 1>> grads(static_cast<std::size_t>(n));
  std::vector<double> values(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static) if (n >= 1024)
  for (int i = 0; i < n; ++i) {
    const ContactPair& p = pairs[static_cast<std::size_t>(i)];
    with_stencil_size(p.kind, [&](auto size) {
      constexpr int N = 3 * decltype(size)::value;
      const auto e = pair_dual<Dual<N, 1>>(p, *set->body, x);  // first order: no Hessian work
      grads[static_cast<std::size_t>(i)].template head<N>() = e.g;
      values[static_cast<std::size_t>(i)] = e.v;
    });
  }
  double total = 0;
  std::array<int, 3> vertex{};
  for (int i = 0; i < n; ++i) {
    const int k = pair_vertices(pairs[static_cast<std::size_t>(i)], vertex);
    for (int j = 0; j < k; ++j) g.row(vertex[static_cast<std::size_t>(j)]) += grads[static_cast<std::size_t>(i)].segment<3>(3 * j).transpose();
    total += values[static_cast<std::size_t>(i)];
  }
  return total;
}

void BarrierContact::hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd, bool lower) const {
  const auto set = cached_pairs(x);
  const std::vector<ContactPair>& pairs = set->pairs;
  const int n = static_cast<int>(pairs.size());
  for (const ContactPair& p : pairs)
    if (!(p.distance2 > 0)) touching(p);
  // Slots: each pair writes its blocks at a fixed offset (prefix sum).
  std::vector<std::size_t> offset(static_cast<std::size_t>(n) + 1, h.size());
  for (int i = 0; i < n; ++i)
    with_stencil_size(pairs[static_cast<std::size_t>(i)].kind, [&](auto size) {
      offset[static_cast<std::size_t>(i) + 1] = offset[static_cast<std::size_t>(i)] + hessian_entries<decltype(size)::value>(lower);
    });
  h.resize(offset.back());
#pragma omp parallel for schedule(static) if (n >= 512)
  for (int i = 0; i < n; ++i) {
    const ContactPair& p = pairs[static_cast<std::size_t>(i)];
    std::array<int, 3> v{};
    pair_vertices(p, v);
    with_stencil_size(p.kind, [&](auto size) {
      constexpr int K = decltype(size)::value;
      Eigen::Matrix<double, 3 * K, 3 * K> block = pair_dual<Dual<3 * K, 2>>(p, *set->body, x).h;
      if (project_psd) project_to_psd<3 * K>(block);
      write_element_hessian<K>(block, v.data(), lower, h.data() + offset[static_cast<std::size_t>(i)]);
    });
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
  if (dx.rows() != x.rows()) throw Error("max_step's move has the wrong vertex count");
  if (!dx.allFinite()) throw ConfigError("max_step's move has a non-finite coordinate");
  const Topology& t = *topology_;
  const Eigen::MatrixX3d& b0 = body_from ? *body_from : body_->vertices();
  const Eigen::MatrixX3d& b1 = body_to ? *body_to : b0;
  if (b0.rows() != body_->vertices().rows() || b1.rows() != b0.rows())
    throw Error("max_step's body motion has the wrong vertex count");
  if (!b0.allFinite() || !b1.allFinite()) throw ConfigError("max_step's body motion has a non-finite coordinate");
  const Eigen::MatrixX3d x1 = x + dx;
  const Eigen::MatrixX3d db = b1 - b0;

  // Candidates: swept boxes that overlap (a pair whose boxes never meet
  // cannot touch). A standing body's boxes are those of its state.
  const MeshBoxes garment = mesh_boxes(x, &x1, t.garment_faces, t.garment_edges, 0.0);
  std::vector<std::pair<int, int>> pt, tp, ee;
  if (body_from || body_to) {
    const MeshBoxes moving = mesh_boxes(b0, &b1, t.body_faces, t.body_edges, 0.0);
    pt = geometry::overlapping_boxes(garment.points, moving.faces);
    tp = geometry::overlapping_boxes(garment.faces, moving.points);
    ee = geometry::overlapping_boxes(garment.edges, moving.edges);
  } else {
    // A standing body: when the move stays inside the reach of the pairs'
    // Verlet list (cached_pairs), every pair whose swept boxes overlap is
    // on it, and the list's pairs filtered by the same box test are the
    // pairs the grids would return (in another order; the step is their
    // minimum). Settling steps mostly do: the grids cost a fifth of a drape.
    std::shared_ptr<const BodyState> state;
    std::vector<ContactPair> listed;
    bool covered = false;
    {
      std::lock_guard<std::mutex> lock(cache_.mutex);
      state = body_state_locked();
      covered = cache_.candidates_body == state &&
                geometry::sweep_within(cache_.candidates_x, x, dx, settings_.distance + candidate_skin());
      if (covered) listed = cache_.candidates;
    }
    if (covered) {
      for (const ContactPair& c : listed) {
        const auto g = static_cast<std::size_t>(c.garment), b = static_cast<std::size_t>(c.body);
        switch (c.kind) {
          case PairKind::GarmentVertexBodyFace:
            if (geometry::boxes_overlap(garment.points[g], state->faces.boxes()[b])) pt.emplace_back(c.garment, c.body);
            break;
          case PairKind::BodyVertexGarmentFace:
            if (geometry::boxes_overlap(garment.faces[g], state->points.boxes()[b])) tp.emplace_back(c.garment, c.body);
            break;
          case PairKind::GarmentEdgeBodyEdge:
            if (geometry::boxes_overlap(garment.edges[g], state->edges.boxes()[b])) ee.emplace_back(c.garment, c.body);
            break;
        }
      }
    } else {
      pt = state->faces.overlapping(garment.points);
      tp = state->points.overlapping(garment.faces);
      ee = state->edges.overlapping(garment.edges);
    }
  }
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
