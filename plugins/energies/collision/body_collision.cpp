#include "body_collision.hpp"

#include "contacts.hpp"
#include "normal_groups.hpp"
#include "smooth_distance.hpp"

#include <drape/energy_input.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/vertex_areas.hpp>
#include <drape/physics/psd_projection.hpp>

#include <algorithm>
#include <string>

namespace drape::collision {

BodyCollision::BodyCollision(const CollisionSettings& settings) : settings_(settings) {
  if (settings.smoothing > 0 && settings.smoothing <= settings.margin)
    throw ConfigError("smoothing (" + std::to_string(settings.smoothing) + " m) must exceed the margin (" +
                      std::to_string(settings.margin) + " m), or be 0 for the exact distance");
  penalty_.margin = settings.margin;
  if (settings.max_depth > 0) penalty_.delta_max = settings.margin + settings.max_depth;
}

void BodyCollision::bind(const EnergyContext& context) {
  if (!context.garment) throw ConfigError("no garment is bound");
  if (!context.body)
    throw ConfigError(
        "no body is bound; the collision energy keeps the garment outside a body, so the scene or "
        "solver must provide one (EnergyContext::body, e.g. a geometry::BodySurface)");
  if (context.garment->mesh.num_vertices() == 0) throw ConfigError("the garment has no vertices");
  area_ = geometry::vertex_areas(*context.garment);
  body_ = context.body;
  surface_ = dynamic_cast<const geometry::BodySurface*>(body_);
  {
    std::lock_guard<std::mutex> lock(cache_.mutex);
    cache_.contacts.reset();
    cache_.reference.resize(0, 3);
  }
  face_group_.clear();
  if (settings_.creases && !(settings_.smoothing > 0) && surface_) face_group_ = normal_groups(*surface_);
  if (settings_.smoothing > 0 && !surface_)
    throw ConfigError("smoothing needs the body's vertices and normals (a geometry::BodySurface); this body "
                      "only answers closest-point queries: set smoothing to 0");
}

std::vector<Contact> BodyCollision::contacts(const Eigen::MatrixX3d& x) const {
  if (!(settings_.smoothing > 0)) return surface_ ? exact_contacts(x) : body_contacts(*body_, x, true);
  std::vector<char> covered;
  std::vector<Contact> out =
      smooth_contacts(surface_->vertices(), surface_->vertex_normals(), x, settings_.smoothing, true, covered);
  // The exact closest point only where no body vertex was within R.
  std::vector<Eigen::Index> rest;
  for (std::size_t v = 0; v < covered.size(); ++v)
    if (!covered[v]) rest.push_back(static_cast<Eigen::Index>(v));
  if (rest.empty()) return out;
  Eigen::MatrixX3d far(static_cast<Eigen::Index>(rest.size()), 3);
  for (std::size_t i = 0; i < rest.size(); ++i) far.row(static_cast<Eigen::Index>(i)) = x.row(rest[i]);
  const std::vector<Contact> exact = body_contacts(*body_, far, true);
  for (std::size_t i = 0; i < rest.size(); ++i) out[static_cast<std::size_t>(rest[i])] = exact[i];
  return out;
}

// Most of a drape's vertices hang beyond the margin, where the penalty and all
// its derivatives are zero, and the search for their closest body point is the
// slowest (the ball it must clear is large). The signed distance is
// 1-Lipschitz and changes sign only through zero on a closed body, so a vertex
// that was d_ref outside and has moved m since, on the same body, is still at
// least d_ref - m outside: beyond the margin when d_ref - m > margin. Such a
// vertex gets that lower bound as its distance (a zero penalty, exactly what
// the full query gives) and is not searched. Between time steps of a morph
// the body changes and every vertex is searched again. (Starting each search
// from the vertex's last closest face was tried as well: no faster.)
std::vector<Contact> BodyCollision::exact_contacts(const Eigen::MatrixX3d& x) const {
  const Eigen::Index n = x.rows();
  // The record is read and updated in place, so the lock is held throughout
  // (the search itself runs in parallel inside).
  std::lock_guard<std::mutex> lock(cache_.mutex);
  Eigen::MatrixX3d& reference = cache_.reference;
  Eigen::VectorXd& reference_distance = cache_.reference_distance;
  const bool bounded = reference.rows() == n && cache_.reference_revision == surface_->revision();
  if (!bounded) {  // every vertex is searched below and fills its row
    reference.resize(n, 3);
    reference_distance.resize(n);
    cache_.reference_revision = surface_->revision();
  }

  std::vector<Contact> out(static_cast<std::size_t>(n));
  std::vector<Eigen::Index> search;
  search.reserve(static_cast<std::size_t>(n));
  for (Eigen::Index v = 0; v < n; ++v) {
    const double lower = bounded ? reference_distance[v] - (x.row(v) - reference.row(v)).norm() : 0.0;
    if (bounded && lower > settings_.margin)
      out[static_cast<std::size_t>(v)].distance = lower;
    else
      search.push_back(v);
  }
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(search.size()), 3);
  for (std::size_t i = 0; i < search.size(); ++i) points.row(static_cast<Eigen::Index>(i)) = x.row(search[i]);
  const std::vector<Contact> found = body_contacts(*surface_, points, true);
  for (std::size_t i = 0; i < search.size(); ++i) {
    const Eigen::Index v = search[i];
    out[static_cast<std::size_t>(v)] = found[i];
    reference.row(v) = x.row(v);
    reference_distance[v] = found[i].distance;
  }
  if (!face_group_.empty()) add_crease_terms(x, search, out);
  return out;
}

void BodyCollision::add_crease_terms(const Eigen::MatrixX3d& x, const std::vector<Eigen::Index>& searched,
                                     std::vector<Contact>& contacts) const {
  const auto n = static_cast<std::ptrdiff_t>(searched.size());
#pragma omp parallel for schedule(dynamic, 16)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const Eigen::Index v = searched[static_cast<std::size_t>(i)];
    Contact& contact = contacts[static_cast<std::size_t>(v)];
    if (!(penalty_.delta(contact.distance) > 0) || contact.face < 0) continue;
    contact.crease = crease_at(x.row(v).transpose(), contact, v);
  }
}

CreaseTerm BodyCollision::crease_at(const Eigen::Vector3d& p, const Contact& contact, Eigen::Index v) const {
  const double coefficient = settings_.stiffness * area_[v];
  const std::array<int, 3>& across = surface_->face_neighbours()[static_cast<std::size_t>(contact.face)];
  CreaseTerm sum;
  for (const int face : across)
    if (face >= 0)
      sum += crease_term(p, contact.closest, closest_point_on_face(*surface_, p, face), penalty_, coefficient,
                         kNeighbourRamp);
  const geometry::SurfacePoint far =
      surface_->locate_excluding(p, face_group_, face_group_[static_cast<std::size_t>(contact.face)], settings_.margin);
  // A far wall across an edge of the near face is counted above already.
  if (far.face >= 0 && std::find(across.begin(), across.end(), far.face) == across.end())
    sum += crease_term(p, contact.closest, closest_point_of(*surface_, far), penalty_, coefficient, kFarWallRamp);
  return sum;
}

std::shared_ptr<const std::vector<Contact>> BodyCollision::cached_contacts(const Eigen::MatrixX3d& x) const {
  if (!surface_) return std::make_shared<const std::vector<Contact>>(contacts(x));
  {
    std::lock_guard<std::mutex> lock(cache_.mutex);
    if (cache_.contacts && cache_.revision == surface_->revision() && cache_.x.rows() == x.rows() && cache_.x == x)
      return cache_.contacts;
  }
  auto fresh = std::make_shared<const std::vector<Contact>>(contacts(x));
  std::lock_guard<std::mutex> lock(cache_.mutex);
  cache_.x = x;
  cache_.revision = surface_->revision();
  cache_.contacts = fresh;
  return fresh;
}

Eigen::Vector3d BodyCollision::push_gradient(Eigen::Index v, double delta, const Eigen::Vector3d& normal) const {
  // d delta / dx = -n: the energy falls as the vertex moves out.
  return -settings_.stiffness * area_[v] * penalty_.slope(delta) * normal;
}

void BodyCollision::check(const Eigen::MatrixX3d& x) const {
  if (!body_) throw Error("bind() was not called");
  check_energy_input(x, area_.size());
}

double BodyCollision::value(const Eigen::MatrixX3d& x) const {
  check(x);
  const auto cached = cached_contacts(x);
  const std::vector<Contact>& contacts = *cached;
  double energy = 0;
  double crease = 0;
  for (std::size_t v = 0; v < contacts.size(); ++v) {
    energy += area_[static_cast<Eigen::Index>(v)] * penalty_.value(penalty_.delta(contacts[v].distance));
    crease += contacts[v].crease.value;
  }
  return settings_.stiffness * energy + crease;
}

double BodyCollision::add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const {
  check(x);
  if (g.rows() != x.rows()) throw Error("the gradient has " + std::to_string(g.rows()) + " rows, x has " +
                                        std::to_string(x.rows()));
  const auto cached = cached_contacts(x);
  const std::vector<Contact>& contacts = *cached;
  double energy = 0;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const auto v = static_cast<Eigen::Index>(i);
    const double delta = penalty_.delta(contacts[i].distance);
    if (delta <= 0) continue;
    energy += settings_.stiffness * area_[v] * penalty_.value(delta) + contacts[i].crease.value;
    g.row(v) += (push_gradient(v, delta, contacts[i].normal) + contacts[i].crease.gradient).transpose();
  }
  return energy;
}

Eigen::Matrix3d BodyCollision::vertex_hessian(Eigen::Index v, const Contact& contact, bool project_psd) const {
  const double delta = penalty_.delta(contact.distance);
  Eigen::Matrix3d block = Eigen::Matrix3d::Zero();
  if (delta > 0) {
    const double c = settings_.stiffness * area_[v];
    block = c * penalty_.curvature(delta) * contact.normal * contact.normal.transpose();
    if (settings_.smoothing > 0) {
      // The smooth distance's Hessian has no structure to exploit: project the whole block.
      block -= c * penalty_.slope(delta) * contact.distance_hessian;
      if (project_psd) project_to_psd(block);
    } else if (!project_psd || contact.distance < 0) {
      // -c phi' D is negative semi-definite outside the body (D = P / d with
      // d > 0) and positive semi-definite inside: the projection keeps it there only.
      block -= c * penalty_.slope(delta) * contact.distance_hessian;
    }
    if (contact.crease.value > 0) {
      block += contact.crease.hessian;
      if (project_psd) project_to_psd(block);
    }
  }
  return block;
}

void BodyCollision::add_hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd) const {
  hessian(x, h, project_psd, false);
}

void BodyCollision::add_hessian_lower(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd) const {
  hessian(x, h, project_psd, true);
}

void BodyCollision::hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd, bool lower) const {
  check(x);
  const auto cached = cached_contacts(x);
  const std::vector<Contact>& contacts = *cached;
  h.reserve(h.size() + (lower ? 6 : 9) * contacts.size());
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const auto v = static_cast<Eigen::Index>(i);
    const Eigen::Matrix3d block = vertex_hessian(v, contacts[i], project_psd);
    const int base = 3 * static_cast<int>(v);
    for (int r = 0; r < 3; ++r)
      for (int col = 0; col <= (lower ? r : 2); ++col) h.emplace_back(base + r, base + col, block(r, col));
  }
}

void BodyCollision::vertex_gradient_samples(const Eigen::MatrixX3d& x, int vertex, double radius,
                                            std::vector<Eigen::Vector3d>& samples) const {
  if (!has_kinks()) return;
  // One vertex's check, not check(x): the solver asks once per contact vertex.
  if (!body_) throw Error("bind() was not called");
  if (x.rows() != area_.size() || vertex < 0 || vertex >= x.rows())
    throw Error("vertex " + std::to_string(vertex) + " of " + std::to_string(x.rows()) +
                " given, the bound garment has " + std::to_string(area_.size()));
  if (!x.row(vertex).allFinite()) throw Error("garment vertex " + std::to_string(vertex) + " is not finite");
  for (int axis = 0; axis < 3; ++axis)
    for (const double sign : {-1.0, 1.0}) {
      Eigen::Vector3d p = x.row(vertex).transpose();
      p[axis] += sign * radius;
      const Contact contact = body_contact(*body_, p, false);
      const double delta = penalty_.delta(contact.distance);
      Eigen::Vector3d sample = Eigen::Vector3d::Zero();
      if (delta > 0) {
        sample = push_gradient(vertex, delta, contact.normal);
        if (!face_group_.empty()) sample += crease_at(p, contact, vertex).gradient;
      }
      samples.push_back(sample);
    }
}

}  // namespace drape::collision
