#pragma once
// The last bodies made, by their exact shape vector. A process asks for
// the same body again and again (the BMI solve evaluates the shape it then
// returns, and the caller makes that body; the mean body serves every size's
// fit, the size chart and the assets), and each costs a template fit onto the
// implicit surface. Keys compare byte for byte, so a hit is the body the fit
// would give, bit for bit. Safe to share between threads.
#include <Eigen/Core>

#include <cstring>
#include <list>
#include <mutex>
#include <optional>
#include <utility>

namespace drape::parametric {

class BodyMemo {
 public:
  explicit BodyMemo(std::size_t capacity) : capacity_(capacity) {}

  std::optional<Eigen::MatrixX3d> find(const Eigen::VectorXd& shape) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = entries_.begin(); it != entries_.end(); ++it)
      if (same(it->first, shape)) {
        entries_.splice(entries_.begin(), entries_, it);  // most recent first
        return entries_.front().second;
      }
    return std::nullopt;
  }

  void add(const Eigen::VectorXd& shape, const Eigen::MatrixX3d& vertices) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& e : entries_)
      if (same(e.first, shape)) return;  // another thread made it meanwhile
    entries_.emplace_front(shape, vertices);
    if (entries_.size() > capacity_) entries_.pop_back();
  }

 private:
  static bool same(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    return a.size() == b.size() &&
           std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0;
  }

  std::size_t capacity_;
  mutable std::mutex mutex_;
  mutable std::list<std::pair<Eigen::VectorXd, Eigen::MatrixX3d>> entries_;
};

}  // namespace drape::parametric
