#pragma once
// The closest body points the v2v and direction losses need for one sample:
// the ground truth's (with the sign and normal: direction uses the body normal
// there) and the prediction's. Both losses share it, so the work is done once:
//
// - the ground truth's points depend only on the data: they come from the
//   process-wide SurfaceCache after the first time a sample is seen, and are
//   computed exactly as BodySurface::locate finds them otherwise;
// - the prediction's are found among the faces nearest the ground-truth
//   vertex of the same row (NearbyFaces: made with the ground truth's points
//   and kept in the same SurfaceCache entry), the tree searched only when the
//   prediction is too far from the ground truth for those faces to prove the
//   answer (NearestTriangles: no normals, a refit of the boxes);
// - the last prediction's points are kept too, keyed by content like the
//   ground truth's, so the second loss that asks for the same sample in the
//   same step finds them.
//
// Everything is in double and gives the same points as BodySurface::locate
// (bit for bit: of faces at the same distance the lowest-numbered wins, whatever
// the search started from, so the cache and the warm starts change no result).
#include <drape/geometry/nearest_triangles.hpp>
#include <drape/geometry/pseudo_normals.hpp>
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
  // The closest points of pred sample b on body sample b (unsigned, no normals);
  // truth: ground_truth's points of target sample b.
  std::shared_ptr<const Hits> prediction(const Tensor& body, const Tensor& pred, const Tensor& target, int b,
                                         const Hits& truth);
  // The same points with their signs and normals, as BodySurface::locate
  // gives them (PseudoNormals: only the features the points lie on).
  Hits signed_prediction(const Tensor& body, const Tensor& pred, const Tensor& target, int b, const Hits& truth);

  // The nearby lists hold the faces within the ground truth's distance plus
  // this of each ground-truth vertex, at most kNearbyFaces of them: enough to
  // prove the answer while the prediction is within about half of it
  // (measured: see docs/training.md).
  static constexpr double kNearbySlack = 0.02;
  static constexpr int kNearbyFaces = 16;

 private:
  void use_body(const Tensor& body, int b, bool with_normals);
  // The nearby lists of target sample b from the cache (made by ground_truth
  // with the points); null when the cache did not keep them.
  std::shared_ptr<const NearbyFaces> nearby_faces(const Tensor& body, const Tensor& target, int b, const Hits& truth);

  std::string who_;
  std::uint64_t topology_;
  BodySurface surface_;        // signed queries, for the ground truth when it is not cached
  NearestTriangles nearest_;   // unsigned queries, for the prediction
  PseudoNormals signs_;        // signs for signed_prediction
  std::vector<float> surface_body_, nearest_body_;  // the body each holds, as it came
  std::vector<int> last_faces_;                  // the last ground truth's faces: hints for the next
  std::shared_ptr<const Hits> last_truth_;       // the last ground truth returned (held: its address stays its own)
  SurfaceKey last_truth_key_;                    // and its key
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
