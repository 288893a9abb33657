// The barrier contact's friction: IPC's lagged friction (barrier.hpp), its own
// potential (friction.hpp).
#include "friction.hpp"

#include "barrier_state.hpp"

#include <drape/element_assembly.hpp>
#include <drape/geometry/ccd.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/physics/barrier_function.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace drape::barrier {

namespace {

// f0 of IPC's friction (barrier.hpp) and the two factors of its derivatives:
// f1(y) / y and (f1'(y) y - f1(y)) / y^3, finite at y = 0.
struct SlipFunction {
  double f0 = 0, f1_over_y = 0, curvature = 0;
};

SlipFunction slip_function(double y, double eps) {
  if (y >= eps) return {y, 1.0 / y, -1.0 / (y * y * y)};
  // Below eps: f0 = -y^3 / (3 eps^2) + y^2 / eps + eps / 3, f1 = 2 y / eps - y^2 / eps^2.
  return {-y * y * y / (3 * eps * eps) + y * y / eps + eps / 3, 2.0 / eps - y / (eps * eps),
          y > 0 ? -1.0 / (eps * eps * y) : 0.0};
}

// An orthonormal basis of the plane normal to the unit vector n.
Eigen::Matrix<double, 3, 2> tangent_basis(const Eigen::Vector3d& n) {
  Eigen::Index axis = 0;
  n.cwiseAbs().minCoeff(&axis);
  const Eigen::Vector3d t1 = n.cross(Eigen::Vector3d::Unit(axis)).normalized();
  Eigen::Matrix<double, 3, 2> t;
  t.col(0) = t1;
  t.col(1) = n.cross(t1);
  return t;
}

}  // namespace

BarrierContact::Contact BarrierContact::contact(const ContactPair& pair, const BodyState& body,
                                                const Eigen::MatrixX3d& x) const {
  const Topology& t = *topology_;
  const std::array<Eigen::Vector3d, 4> p = pair_points(pair, x);
  Contact c;
  c.count = pair_vertices(pair, c.vertex);
  Eigen::Vector3d on_garment, on_body;
  double mollifier = 1;
  switch (pair.kind) {
    case PairKind::GarmentVertexBodyFace: {
      c.weight = {1.0, 0.0, 0.0};
      on_garment = p[0];
      on_body = geometry::closest_point_on_triangle(p[0], p[1], p[2], p[3]).point;
      break;
    }
    case PairKind::BodyVertexGarmentFace: {
      const geometry::TrianglePoint hit = geometry::closest_point_on_triangle(p[0], p[1], p[2], p[3]);
      c.weight = {hit.barycentric[0], hit.barycentric[1], hit.barycentric[2]};
      on_garment = hit.point;
      on_body = p[0];
      break;
    }
    case PairKind::GarmentEdgeBodyEdge: {
      const geometry::SegmentPoints hit = geometry::closest_points_on_segments(p[0], p[1], p[2], p[3]);
      c.weight = {1.0 - hit.s, hit.s, 0.0};
      on_garment = hit.on_a;
      on_body = hit.on_b;
      const double cross2 = (p[1] - p[0]).cross(p[3] - p[2]).squaredNorm();
      mollifier = edge_mollifier(cross2, 1e-3 * t.garment_edge_rest2[pair.garment] * body.edge_length2[pair.body]).m;
      break;
    }
  }
  const Eigen::Vector3d gap = on_garment - on_body;
  const double d = gap.norm();
  if (!(d > 0)) return c;  // touching: no direction (the barrier refuses such a state anyway)
  c.normal = gap / d;
  // E_pair = kappa d_hat w m b(d^2 / d_hat^2): its push |dE/dd|.
  const double dhat2 = settings_.distance * settings_.distance;
  const double db = log_barrier(d * d / dhat2).db;
  c.normal_force = std::abs(settings_.stiffness * settings_.distance * pair_area(pair, body) * mollifier * db * 2 * d / dhat2);
  return c;
}

Dissipation* BarrierContact::dissipation() { return friction_.get(); }

void BarrierContact::Friction::begin_step(const Eigen::MatrixX3d& x_start, double time_step) {
  contacts_.clear();
  x_start_ = x_start;
  epsilon_ = barrier_.settings_.slip_velocity * time_step;
  const auto set = barrier_.cached_pairs(x_start);
  for (const ContactPair& pair : set->pairs) {
    LaggedContact f;
    f.contact = barrier_.contact(pair, *set->body, x_start);
    f.limit = barrier_.settings_.friction * f.contact.normal_force;
    if (!(f.limit > 0)) continue;
    f.tangent = tangent_basis(f.contact.normal);
    contacts_.push_back(f);
  }
}

Eigen::Vector2d BarrierContact::Friction::slip(const LaggedContact& f, const Eigen::MatrixX3d& x) const {
  Eigen::Vector3d move = Eigen::Vector3d::Zero();
  for (int k = 0; k < f.contact.count; ++k) {
    const int v = f.contact.vertex[static_cast<std::size_t>(k)];
    move += f.contact.weight[static_cast<std::size_t>(k)] * (x.row(v) - x_start_.row(v)).transpose();
  }
  return f.tangent.transpose() * move;
}

double BarrierContact::Friction::value(const Eigen::MatrixX3d& x) const {
  barrier_.check(x);
  double total = 0;
  for (const LaggedContact& f : contacts_) total += f.limit * slip_function(slip(f, x).norm(), epsilon_).f0;
  return total;
}

void BarrierContact::Friction::add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const {
  barrier_.check(x);
  for (const LaggedContact& f : contacts_) {
    const Eigen::Vector2d u = slip(f, x);
    const Eigen::Vector3d force = f.limit * slip_function(u.norm(), epsilon_).f1_over_y * (f.tangent * u);
    for (int k = 0; k < f.contact.count; ++k)
      g.row(f.contact.vertex[static_cast<std::size_t>(k)]) += f.contact.weight[static_cast<std::size_t>(k)] * force.transpose();
  }
}

void BarrierContact::Friction::add_hessian_lower(const Eigen::MatrixX3d& x, Triplets& h) const {
  barrier_.check(x);
  for (const LaggedContact& f : contacts_) {
    const Eigen::Vector2d u = slip(f, x);
    const SlipFunction s = slip_function(u.norm(), epsilon_);
    // d2 f0(|u|) / du2 = f1/y I + (f1' y - f1) / y^3 u u^T: positive semidefinite
    // for this f0 (eigenvalues f1/y and f1', both >= 0).
    const Eigen::Matrix2d m = s.f1_over_y * Eigen::Matrix2d::Identity() + s.curvature * u * u.transpose();
    const Eigen::Matrix3d block = f.limit * f.tangent * m * f.tangent.transpose();
    auto write = [&](auto size) {
      constexpr int K = decltype(size)::value;
      Eigen::Matrix<double, 3 * K, 3 * K> element;
      for (int a = 0; a < K; ++a)
        for (int b = 0; b < K; ++b)
          element.template block<3, 3>(3 * a, 3 * b) =
              f.contact.weight[static_cast<std::size_t>(a)] * f.contact.weight[static_cast<std::size_t>(b)] * block;
      const std::size_t start = h.size();
      h.resize(start + hessian_entries<K>(true));
      write_element_hessian<K>(element, f.contact.vertex.data(), true, h.data() + start);
    };
    switch (f.contact.count) {
      case 1: write(std::integral_constant<int, 1>{}); break;
      case 2: write(std::integral_constant<int, 2>{}); break;
      default: write(std::integral_constant<int, 3>{}); break;
    }
  }
}

double BarrierContact::Friction::slip_ratio(const Eigen::MatrixX3d& x) const {
  barrier_.check(x);
  double largest = 0;
  for (const LaggedContact& f : contacts_) largest = std::max(largest, slip(f, x).norm() / epsilon_);
  return largest;
}

}  // namespace drape::barrier
