#include <drape/geometry/body_points.hpp>

#include <drape/errors.hpp>

#include <cstring>
#include <string>
#include <utility>

namespace drape::geometry {

BodyPoints::BodyPoints(const Mesh& body, std::string who)
    : who_(std::move(who)),
      topology_(topology_hash(body.faces)),
      surface_(body),
      nearest_(body.vertices, body.faces),
      signs_(body.faces) {}

BodyPoints::~BodyPoints() = default;

void BodyPoints::use_body(const Tensor& body, int b, bool with_normals) {
  // The body each structure was last fitted to is kept as it came (floats):
  // comparing with it costs a memcmp, where a hash of it cost 0.1 ms a call.
  const std::size_t n = static_cast<std::size_t>(body.rows()) * body.cols();
  const float* data = body.data() + static_cast<std::size_t>(b) * n;
  std::vector<float>& held = with_normals ? surface_body_ : nearest_body_;
  if (held.size() == n && std::memcmp(held.data(), data, n * sizeof(float)) == 0) return;
  const Eigen::MatrixX3d vertices = body.mat(b).cast<double>();
  if (with_normals)
    surface_.update(vertices);
  else
    nearest_.update(vertices);
  held.assign(data, data + n);
}

std::shared_ptr<const BodyPoints::Hits> BodyPoints::ground_truth(const Tensor& body, const Tensor& target, int b) {
  const std::size_t nb = static_cast<std::size_t>(body.rows()) * body.cols();
  const std::size_t nt = static_cast<std::size_t>(target.rows()) * target.cols();
  const SurfaceKey key = surface_key(topology_, body.data() + b * nb, nb, target.data() + b * nt, nt);
  SurfaceCache& cache = SurfaceCache::shared();
  if (auto hit = cache.find(key)) {
    last_truth_ = hit;
    last_truth_key_ = key;
    return hit;
  }
  const Eigen::MatrixX3d y = target.mat(b).cast<double>();
  if (!y.allFinite()) throw Error(who_ + ": sample " + std::to_string(b) + " has non-finite target vertices");
  use_body(body, b, true);
  Hits hits(static_cast<std::size_t>(y.rows()));
  const bool hinted = static_cast<Eigen::Index>(last_faces_.size()) == y.rows();
  for (Eigen::Index i = 0; i < y.rows(); ++i)
    hits[i] = surface_.locate_near(y.row(i).transpose(), hinted ? last_faces_[static_cast<std::size_t>(i)] : -1);
  last_faces_.resize(hits.size());
  for (std::size_t i = 0; i < hits.size(); ++i) last_faces_[i] = hits[i].face;
  SurfaceEntry entry{std::move(hits), {}};
  // The faces near each vertex, for the prediction's searches at every later
  // step: made with the points, so that they are shared with them (data-parallel
  // ranks exchange whole entries), when the cache has room to keep them.
  const std::size_t estimate = entry.bytes() + static_cast<std::size_t>(y.rows()) * (8 * kNearbyFaces + 8);
  if (cache.bytes() + estimate <= cache.budget()) {
    use_body(body, b, false);
    entry.nearby = nearest_.nearby(y, entry.hits, kNearbySlack, kNearbyFaces);
  }
  last_truth_ = cache.insert(key, std::move(entry));
  last_truth_key_ = key;
  return last_truth_;
}

std::shared_ptr<const BodyPoints::Hits> BodyPoints::prediction(const Tensor& body, const Tensor& pred,
                                                               const Tensor& target, int b, const Hits& truth) {
  const std::size_t nb = static_cast<std::size_t>(body.rows()) * body.cols();
  const std::size_t np = static_cast<std::size_t>(pred.rows()) * pred.cols();
  const SurfaceKey key = surface_key(~topology_, body.data() + b * nb, nb, pred.data() + b * np, np);
  RecentPoints& recent = RecentPoints::shared();
  if (auto hit = recent.find(key)) return hit;
  const Eigen::MatrixX3d x = pred.mat(b).cast<double>();
  if (!x.allFinite()) throw Error(who_ + ": sample " + std::to_string(b) + " has non-finite pred vertices");
  if (static_cast<Eigen::Index>(truth.size()) != x.rows() || target.rows() != x.rows())
    throw Error(who_ + ": " + std::to_string(truth.size()) + " ground-truth points for " + std::to_string(x.rows()) +
                " predicted points");
  use_body(body, b, false);
  auto hits = std::make_shared<Hits>(static_cast<std::size_t>(x.rows()));
  if (const auto near = nearby_faces(body, target, b, truth)) {
    const Eigen::MatrixX3d y = target.mat(b).cast<double>();
    for (Eigen::Index i = 0; i < x.rows(); ++i)
      (*hits)[i] = nearest_.nearest_from(x.row(i).transpose(), y.row(i).transpose(), *near, static_cast<int>(i));
  } else {
    // No room to keep the lists: each search starts from the ground truth's
    // face of the same vertex.
    for (Eigen::Index i = 0; i < x.rows(); ++i)
      (*hits)[i] = nearest_.nearest(x.row(i).transpose(), truth[static_cast<std::size_t>(i)].face);
  }
  recent.insert(key, hits);
  return hits;
}

BodyPoints::Hits BodyPoints::signed_prediction(const Tensor& body, const Tensor& pred, const Tensor& target, int b,
                                               const Hits& truth) {
  Hits hits = *prediction(body, pred, target, b, truth);
  const Eigen::MatrixX3d vertices = body.mat(b).cast<double>();
  const double tolerance = on_surface_tolerance(vertices);
  const auto x = pred.mat(b);
  for (std::size_t i = 0; i < hits.size(); ++i)
    hits[i] = signs_.sign(vertices, x.row(static_cast<Eigen::Index>(i)).transpose().cast<double>(), hits[i], tolerance);
  return hits;
}

std::shared_ptr<const NearbyFaces> BodyPoints::nearby_faces(const Tensor& body, const Tensor& target, int b,
                                                           const Hits& truth) {
  if (last_truth_.get() == &truth) return SurfaceCache::shared().find_nearby(last_truth_key_);
  const std::size_t nb = static_cast<std::size_t>(body.rows()) * body.cols();
  const std::size_t nt = static_cast<std::size_t>(target.rows()) * target.cols();
  return SurfaceCache::shared().find_nearby(surface_key(topology_, body.data() + b * nb, nb, target.data() + b * nt, nt));
}

RecentPoints& RecentPoints::shared() {
  static RecentPoints recent;
  return recent;
}

std::shared_ptr<const SurfaceCache::Hits> RecentPoints::find(const SurfaceKey& key) const {
  std::lock_guard lock(mutex_);
  for (const auto& [k, hits] : ring_)
    if (k == key) return hits;
  return nullptr;
}

void RecentPoints::insert(const SurfaceKey& key, std::shared_ptr<const SurfaceCache::Hits> hits) {
  std::lock_guard lock(mutex_);
  if (static_cast<int>(ring_.size()) < kSize) {
    ring_.emplace_back(key, std::move(hits));
    return;
  }
  ring_[static_cast<std::size_t>(next_)] = {key, std::move(hits)};
  next_ = (next_ + 1) % kSize;
}

}  // namespace drape::geometry
