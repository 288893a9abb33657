// Self contact: settings, pairs, value, gradient, Hessian (self_contact.hpp).
#include "self_contact.hpp"
#include "self_pairs.hpp"

#include <drape/element_assembly.hpp>
#include <drape/element_energy.hpp>
#include <drape/energy_input.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/box_pairs.hpp>
#include <drape/physics/barrier_function.hpp>
#include <drape/physics/psd_projection.hpp>
#include <drape/warnings.hpp>

#include <cmath>
#include <limits>
#include <mutex>
#include <set>
#include <string>
#include <utility>

namespace drape::self_contact {

namespace {

std::string describe(const SelfPair& p) {
  return p.kind == PairKind::VertexFace ? "vertex " + std::to_string(p.a) + " and face " + std::to_string(p.b)
                                        : "edges " + std::to_string(p.a) + " and " + std::to_string(p.b);
}

[[noreturn]] void touching(const SelfPair& p) {
  throw Error("garment " + describe(p) + " touch (distance 0): the cloth is not separated from itself");
}

// A rest garment that already crosses itself (some of the larger tshirt
// sizes, as dressed on the mean body) cannot be unwound by a barrier; those
// places are left out (self_pairs.cpp). Said once per garment and process:
// a dataset binds the same garment for every sample.
void warn_tangle_once(int vertices, int faces) {
  static std::mutex mutex;
  static std::set<std::pair<int, int>> told;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (!told.insert({vertices, faces}).second) return;
  }
  warn("the rest garment (" + std::to_string(vertices) + " vertices) already passes through itself at " +
       std::to_string(faces) + " faces, as its template dressed it; those places and one ring around them are left "
       "out of the self-contact, which guards the rest (docs/scenes.md, \"Cloth that never crosses itself\")");
}

}  // namespace

SelfContact::SelfContact(const SelfContactSettings& settings) : settings_(settings), topology_(std::make_unique<SelfTopology>()) {
  check_barrier_settings(settings_.distance, settings_.stiffness, settings_.min_separation);
  if (!(settings_.rest_exclusion >= 0) || !std::isfinite(settings_.rest_exclusion))
    throw ConfigError("rest_exclusion must be >= 0");
}

SelfContact::~SelfContact() = default;

void SelfContact::bind(const EnergyContext& context) {
  const Garment& garment = checked_garment(context);
  auto topology = std::make_unique<SelfTopology>(make_topology(garment, settings_.rest_exclusion * settings_.distance,
                                                                settings_.thin_rest_neighbours ? settings_.distance : 0.0));
  if (topology->tangled_faces > 0) warn_tangle_once(garment.mesh.num_vertices(), topology->tangled_faces);
  std::lock_guard<std::mutex> lock(cache_.mutex);
  topology_ = std::move(topology);
  cache_.pairs.reset();
  cache_.candidates_x.resize(0, 3);
}

void SelfContact::check(const Eigen::MatrixX3d& x) const {
  if (topology_->vertices == 0) throw Error("bind() was not called");
  check_energy_input(x, topology_->vertices);
}

std::shared_ptr<const std::vector<SelfPair>> SelfContact::cached_pairs(const Eigen::MatrixX3d& x) const {
  check(x);
  std::lock_guard<std::mutex> lock(cache_.mutex);
  if (cache_.pairs && cache_.x == x) return cache_.pairs;
  // Broad phase: boxes grown by d_hat / 2 + skin, so two primitives within
  // d_hat + 2 skin on every axis are candidates; kept while no coordinate has
  // moved by more than the skin since (a Verlet list), as then every pair
  // within d_hat now was a candidate. Line-search trials and the next Newton
  // iterations move the cloth by less than that.
  const double skin = candidate_skin();
  if (!(cache_.candidates_x.rows() == x.rows() && (x - cache_.candidates_x).cwiseAbs().maxCoeff() <= skin)) {
    cache_.candidates = candidate_pairs(*topology_, x, nullptr, 0.5 * settings_.distance + skin);
    cache_.candidates_x = x;
  }
  cache_.pairs = std::make_shared<const std::vector<SelfPair>>(
      close_pairs(*topology_, x, cache_.candidates, settings_.distance * settings_.distance));
  cache_.x = x;
  return cache_.pairs;
}

std::optional<std::vector<SelfPair>> SelfContact::candidates_covering(const Eigen::MatrixX3d& x,
                                                                       const Eigen::MatrixX3d& dx) const {
  std::lock_guard<std::mutex> lock(cache_.mutex);
  // Both primitives' swept boxes lie inside their boxes at candidates_x grown
  // by d_hat / 2 + skin, which overlapped for every candidate.
  if (!geometry::sweep_within(cache_.candidates_x, x, dx, 0.5 * settings_.distance + candidate_skin())) return std::nullopt;
  return cache_.candidates;
}

template <class S>
S SelfContact::pair_energy(const SelfPair& pair, const std::array<Vec3<S>, 4>& q) const {
  const SelfTopology& t = *topology_;
  const double dhat = pair.dhat > 0 ? pair.dhat : settings_.distance, dhat2 = dhat * dhat;
  const S s = geometry::typed_distance2(pair.type, q);
  const BarrierValue bv = log_barrier(primal(s) / dhat2);
  S e = chain(s, bv.b, bv.db / dhat2, bv.d2b / (dhat2 * dhat2));
  // The area the pair stands for: the vertex's of a vertex-face pair, the
  // two edges' mean (symmetric in them) of an edge-edge one. (pair.a is an
  // edge there: the vertex's area was read for both, past the end of
  // vertex_area for an edge numbered beyond the vertices; valgrind found
  // the read, and it crashed 2 of 8 resumed optimisations.)
  const bool edges = pair.kind == PairKind::EdgeEdge;
  const double area = edges ? 0.5 * (t.edge_area[pair.a] + t.edge_area[pair.b]) : t.vertex_area[pair.a];
  if (edges) {
    const Vec3<S> n = cross(q[1] - q[0], q[3] - q[2]);
    const S c = dot(n, n);
    const MollifierValue mv = edge_mollifier(primal(c), 1e-3 * t.edge_rest2[pair.a] * t.edge_rest2[pair.b]);
    if (mv.m != 1) e = chain(c, mv.m, mv.dm, mv.d2m) * e;
  }
  // A thin pair keeps the scale of the others (kappa d_hat): its barrier, as
  // thin as its rest distance allows, pushes harder where it acts.
  return (settings_.stiffness * settings_.distance * area) * e;
}

template <class D>
D SelfContact::pair_dual(const SelfPair& pair, const Eigen::MatrixX3d& x) const {
  const std::array<int, 4> v = topology_->vertices_of(pair.kind, pair.a, pair.b);
  std::array<Vec3<D>, 4> q;
  for (std::size_t k = 0; k < 4; ++k) q[k] = variable_point<D>(x.row(v[k]).transpose(), 3 * static_cast<int>(k));
  return pair_energy(pair, q);
}

double SelfContact::value(const Eigen::MatrixX3d& x) const {
  const auto pairs = cached_pairs(x);
  for (const SelfPair& p : *pairs)
    if (!(p.distance2 > 0)) return std::numeric_limits<double>::infinity();
  return deterministic_sum(static_cast<int>(pairs->size()), [&](int i) {
    const SelfPair& pair = (*pairs)[static_cast<std::size_t>(i)];
    const std::array<int, 4> v = topology_->vertices_of(pair.kind, pair.a, pair.b);
    std::array<Vec3<double>, 4> q;
    for (std::size_t k = 0; k < 4; ++k) q[k] = plain_point(x.row(v[k]).transpose());
    return pair_energy(pair, q);
  });
}

double SelfContact::add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const {
  const auto pairs = cached_pairs(x);
  const int n = static_cast<int>(pairs->size());
  for (const SelfPair& p : *pairs)
    if (!(p.distance2 > 0)) touching(p);
  // Per-pair gradients in parallel, gathered in pair order (deterministic).
  std::vector<Eigen::Matrix<double, 12, 1>> grads(static_cast<std::size_t>(n));
  std::vector<double> values(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static) if (n >= 1024)
  for (int i = 0; i < n; ++i) {
    const auto e = pair_dual<Dual<12, 1>>((*pairs)[static_cast<std::size_t>(i)], x);  // first order: no Hessian work
    grads[static_cast<std::size_t>(i)] = e.g;
    values[static_cast<std::size_t>(i)] = e.v;
  }
  double total = 0;
  for (int i = 0; i < n; ++i) {
    const SelfPair& p = (*pairs)[static_cast<std::size_t>(i)];
    const std::array<int, 4> v = topology_->vertices_of(p.kind, p.a, p.b);
    for (int k = 0; k < 4; ++k) g.row(v[static_cast<std::size_t>(k)]) += grads[static_cast<std::size_t>(i)].segment<3>(3 * k).transpose();
    total += values[static_cast<std::size_t>(i)];
  }
  return total;
}

void SelfContact::hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd, bool lower) const {
  const auto pairs = cached_pairs(x);
  const int n = static_cast<int>(pairs->size());
  for (const SelfPair& p : *pairs)
    if (!(p.distance2 > 0)) touching(p);
  // Every pair has four vertices: its blocks go at fixed offsets.
  const std::size_t start = h.size(), per_pair = hessian_entries<4>(lower);
  h.resize(start + per_pair * static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static) if (n >= 512)
  for (int i = 0; i < n; ++i) {
    const SelfPair& p = (*pairs)[static_cast<std::size_t>(i)];
    const std::array<int, 4> v = topology_->vertices_of(p.kind, p.a, p.b);
    Eigen::Matrix<double, 12, 12> block = pair_dual<Dual<12, 2>>(p, x).h;
    if (project_psd) project_to_psd<12>(block);
    write_element_hessian<4>(block, v.data(), lower, h.data() + start + per_pair * static_cast<std::size_t>(i));
  }
}

void SelfContact::add_hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd) const {
  hessian(x, h, project_psd, false);
}
void SelfContact::add_hessian_lower(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd) const {
  hessian(x, h, project_psd, true);
}

}  // namespace drape::self_contact
