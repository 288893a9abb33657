#pragma once
// Closest body points that depend only on the data, kept across training
// steps. The v2v and direction losses need the ground truth's closest points on
// its own body at every step, though neither ever changes: the first step that
// meets a sample computes them, every later epoch finds them here.
//
// Entries are keyed by the contents (a 128-bit hash of the body and the query
// points, and the body topology), so any caller gets its own data back, however
// batches are drawn and whichever replica or loss asks. Process-wide and
// thread-safe. Memory is bounded: beyond the budget new entries are not kept
// (nothing is evicted: with shuffled epochs every sample is as likely to come
// back, so a full cache keeps its hit rate). The budget is
// $DRAPE_SURFACE_CACHE_MIB (MiB, default 2048; 0 turns the cache off).
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/nearby_faces.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <unordered_map>
#include <utility>
#include <vector>

namespace drape::geometry {

struct SurfaceKey {
  std::uint64_t a = 0, b = 0;
  bool operator==(const SurfaceKey& o) const { return a == o.a && b == o.b; }
};

// A hash of the mesh topology (the faces), computed once per mesh.
std::uint64_t topology_hash(const Eigen::MatrixX3i& faces);
// The key of the closest points of `points` (n floats) on the body `body` (m floats) of that topology.
SurfaceKey surface_key(std::uint64_t topology, const float* body, std::size_t m, const float* points, std::size_t n);

// What is kept for one sample: the closest points, and the faces listed near
// each point (empty when the caller made none), both data only.
struct SurfaceEntry {
  std::vector<SurfacePoint> hits;
  NearbyFaces nearby;
  std::size_t bytes() const { return sizeof(SurfacePoint) * hits.size() + nearby.bytes() + 64; }
};

class SurfaceCache {
 public:
  using Hits = std::vector<SurfacePoint>;
  using Entries = std::vector<std::pair<SurfaceKey, std::shared_ptr<const SurfaceEntry>>>;

  explicit SurfaceCache(std::size_t budget_bytes) : budget_(budget_bytes) {}
  // The process-wide cache, its budget from $DRAPE_SURFACE_CACHE_MIB.
  static SurfaceCache& shared();

  // Null when the key is not there.
  std::shared_ptr<const Hits> find(const SurfaceKey& key) const;
  // The entry's nearby lists; null when the key is not there or has none.
  std::shared_ptr<const NearbyFaces> find_nearby(const SurfaceKey& key) const;
  // Keeps the entry under key when the budget allows; returns its hits either way.
  std::shared_ptr<const Hits> insert(const SurfaceKey& key, SurfaceEntry entry);
  std::shared_ptr<const Hits> insert(const SurfaceKey& key, Hits hits) { return insert(key, SurfaceEntry{std::move(hits), {}}); }

  // The entries this process computed and kept (insert) since the last call:
  // what a data-parallel rank shares with the others, so that every rank's
  // cache fills in one epoch instead of one sample at a time over many.
  Entries take_computed();
  // Keeps an entry another process computed (when the budget allows); it is
  // not reported by take_computed.
  void adopt(const SurfaceKey& key, SurfaceEntry entry);

  std::size_t bytes() const;
  std::size_t entries() const;
  std::size_t budget() const { return budget_; }

 private:
  struct KeyHash {
    std::size_t operator()(const SurfaceKey& k) const { return static_cast<std::size_t>(k.a ^ (k.b * 0x9E3779B97F4A7C15ull)); }
  };
  std::size_t budget_;
  std::size_t bytes_ = 0;
  mutable std::shared_mutex mutex_;
  std::unordered_map<SurfaceKey, std::shared_ptr<const SurfaceEntry>, KeyHash> entries_;
  std::vector<SurfaceKey> computed_;  // kept by insert since the last take_computed
  bool keep(const SurfaceKey& key, const std::shared_ptr<const SurfaceEntry>& entry);
};

// The bytes an entry packs into: 40 + 88 per point, and with nearby lists
// 8 per point + 8 per listed face + 4.
std::size_t packed_entry_bytes(const SurfaceEntry& entry);
// Entries as bytes, to send to another process of the same program (raw
// SurfacePoints: the same binary reads them), and back. unpack throws Error on
// a buffer that does not parse.
std::vector<std::uint8_t> pack_surface_entries(const SurfaceCache::Entries& entries);
std::vector<std::pair<SurfaceKey, SurfaceEntry>> unpack_surface_entries(const std::uint8_t* data, std::size_t size);

}  // namespace drape::geometry
