#pragma once
// IPC's log barrier (Li et al. 2020, eq. 6) on the squared distance s of a
// pair, made dimensionless by the activation distance d_hat (r = s / d_hat^2):
//
//   b(r) = -(r - 1)^2 ln r   for 0 < r < 1,   0 for r >= 1.
//
// b, b' and b'' vanish at r = 1 (the barrier switches on C2-smoothly as a
// pair comes within d_hat) and b -> infinity as r -> 0, so a state whose
// energy is finite has no touching pair, and a line search that never crosses
// (continuous collision detection) keeps it so. Shared by the energies
// barrier (cloth-body) and self_contact (cloth-cloth).
#include <drape/errors.hpp>
#include <drape/params.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace drape {

// The parameter specs of those three settings, written once for both
// contacts; `distance_doc` says which pairs push apart.
inline std::vector<ParamSpec> barrier_param_specs(const std::string& distance_doc) {
  return {{.name = "distance", .type = ParamType::Float, .default_value = "0.001",
           .doc = "d_hat in m: " + distance_doc, .min = 1e-6, .max = 0.1},
          // 0.2 kappa at 0.9 d_hat: 200 Pa, a shirt's pressure over the shoulders.
          {.name = "stiffness", .type = ParamType::Float, .default_value = "1000",
           .doc = "kappa in Pa: the contact pressure scale (0.2 kappa at 0.9 d_hat, 4.3 kappa at d_hat / 2, unbounded at 0)",
           .min = 1e-6},
          {.name = "min_separation", .type = ParamType::Float, .default_value = "0.1",
           .doc = "a move stops where a pair is down to this fraction of its distance (continuous collision check)",
           .min = 1e-3, .max = 0.9}};
}

// The three settings every barrier contact takes, checked once for both
// (a registry-made energy has them range-checked already; this also covers
// an energy built directly): d_hat a positive length, kappa > 0, and the
// continuous collision check's stopping fraction in (0, 1). ConfigError.
inline void check_barrier_settings(double distance, double stiffness, double min_separation) {
  if (!(distance > 0) || !std::isfinite(distance))
    throw ConfigError("distance (d_hat) must be a positive length, got " + std::to_string(distance));
  if (!(stiffness > 0) || !std::isfinite(stiffness))
    throw ConfigError("stiffness must be > 0, got " + std::to_string(stiffness));
  if (!(min_separation > 0 && min_separation < 1)) throw ConfigError("min_separation must be in (0, 1)");
}

struct BarrierValue {
  double b = 0, db = 0, d2b = 0;  // b(r), b'(r), b''(r)
};

inline BarrierValue log_barrier(double r) {
  if (!(r < 1)) return {};
  if (!(r > 0)) return {INFINITY, -INFINITY, INFINITY};
  const double m = r - 1, log_r = std::log(r);
  return {-m * m * log_r, -2 * m * log_r - m * m / r, -2 * log_r - 4 * m / r + m * m / (r * r)};
}

// IPC's edge-edge mollifier (Li et al. 2020, eq. 11) on c = |e0 x e1|^2 with
// threshold eps: (2 - c / eps) c / eps below eps, else 1. It fades an
// edge-edge pair out as the edges turn parallel, where their distance is not
// smooth, while the point-triangle pairs of their endpoints hold the contact.
struct MollifierValue {
  double m = 1, dm = 0, d2m = 0;  // m(c), m'(c), m''(c)
};

inline MollifierValue edge_mollifier(double c, double eps) {
  if (!(c < eps)) return {};
  const double u = c / eps;
  return {(2 - u) * u, (2 - 2 * u) / eps, -2 / (eps * eps)};
}

}  // namespace drape
