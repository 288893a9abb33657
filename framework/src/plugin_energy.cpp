// PluginEnergy (plugin_energy.hpp).
#include "plugin_energy.hpp"

#include <drape/error_context.hpp>

namespace drape {

PluginEnergy::PluginEnergy(std::string name, std::unique_ptr<Energy> energy)
    : name_(std::move(name)), energy_(std::move(energy)) {}

void PluginEnergy::bind(const EnergyContext& context) {
  in_context(name_, [&] { energy_->bind(context); });
}

double PluginEnergy::value(const Eigen::MatrixX3d& x) const {
  return in_context(name_, [&] { return energy_->value(x); });
}

double PluginEnergy::add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const {
  return in_context(name_, [&] { return energy_->add_gradient(x, g); });
}

void PluginEnergy::add_hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd) const {
  in_context(name_, [&] { energy_->add_hessian(x, h, project_psd); });
}

void PluginEnergy::add_hessian_lower(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd) const {
  in_context(name_, [&] { energy_->add_hessian_lower(x, h, project_psd); });
}

double PluginEnergy::max_step(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& dx, const Eigen::MatrixX3d* body_from,
                              const Eigen::MatrixX3d* body_to) const {
  return in_context(name_, [&] { return energy_->max_step(x, dx, body_from, body_to); });
}

void PluginEnergy::vertex_gradient_samples(const Eigen::MatrixX3d& x, int vertex, double radius,
                                           std::vector<Eigen::Vector3d>& samples) const {
  in_context(name_, [&] { energy_->vertex_gradient_samples(x, vertex, radius, samples); });
}

}  // namespace drape
