#pragma once
// The closest body points the v2v and direction losses need for one sample:
// the ground truth's (with the sign and normal: direction uses the body normal
// there) and the prediction's. Both losses share it, so the work is done once:
//
// - the ground truth's points depend only on the data: they come from the
//   process-wide SurfaceCache after the first time a sample is seen, and are
//   computed exactly as BodySurface::locate finds them otherwise;
// - the prediction's are searched from the face found for the same vertex of
//   the ground truth (NearestTriangles: no normals, a refit of the boxes);
// - the last prediction's points are kept too, keyed by content like the
//   ground truth's, so the second loss that asks for the same sample in the
//   same step finds them.
//
// Everything is in double and gives the same points as BodySurface::locate
// (bit for bit: of faces at the same distance the lowest-numbered wins, whatever
// the search started from, so the cache and the warm starts change no result).
#include <drape/geometry/nearest_triangles.hpp>
#include <drape/geometry/surface_cache.hpp>
#include <drape/mesh.hpp>
#include <drape/tensor.hpp>

#include <memory>
#include <string>
#include <vector>

namespace drape::geometry {

class BodyPoints {
 public:
  using Hits = SurfaceCache::Hits;

  // body: the body mesh whose faces every sample's body shares; who: the
  // caller's name for error messages.
  BodyPoints(const Mesh& body, std::string who);
  ~BodyPoints();

  // The closest points of target sample b on body sample b (with signs and normals).
  std::shared_ptr<const Hits> ground_truth(const Tensor& body, const Tensor& target, int b);
  // The closest points of pred sample b on body sample b (unsigned, no normals),
  // each searched from the face of the same row of `hints` (ground_truth's).
  std::shared_ptr<const Hits> prediction(const Tensor& body, const Tensor& pred, int b, const Hits& hints);

 private:
  void use_body(const Tensor& body, int b, bool with_normals);

  std::string who_;
  std::uint64_t topology_;
  BodySurface surface_;        // signed queries, for the ground truth when it is not cached
  NearestTriangles nearest_;   // unsigned queries, for the prediction
  std::vector<float> surface_body_, nearest_body_;  // the body each holds, as it came
  std::vector<int> last_faces_;                  // the last ground truth's faces: hints for the next
};

// The process-wide cache of the last few predictions' closest points (a ring of
// 64 entries): consumed by the next loss of the same step, useless after it.
class RecentPoints {
 public:
  static RecentPoints& shared();
  std::shared_ptr<const SurfaceCache::Hits> find(const SurfaceKey& key) const;
  void insert(const SurfaceKey& key, std::shared_ptr<const SurfaceCache::Hits> hits);

 private:
  static constexpr int kSize = 64;
  mutable std::mutex mutex_;
  std::vector<std::pair<SurfaceKey, std::shared_ptr<const SurfaceCache::Hits>>> ring_;
  int next_ = 0;
};

}  // namespace drape::geometry
