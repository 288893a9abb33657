#include <drape/geometry/surface_cache.hpp>

#include <drape/errors.hpp>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>

namespace drape::geometry {
namespace {

constexpr std::uint64_t kP1 = 0x9E3779B185EBCA87ull, kP2 = 0xC2B2AE3D27D4EB4Full, kP3 = 0x165667B19E3779F9ull,
                        kP4 = 0x85EBCA77C2B2AE63ull;

std::uint64_t rotl(std::uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }

std::uint64_t avalanche(std::uint64_t h) {
  h ^= h >> 33;
  h *= kP2;
  h ^= h >> 29;
  h *= kP3;
  return h ^ (h >> 32);
}

// Two independent 64-bit hashes over the bytes, so that two different samples
// share a key with probability ~2^-128. Each is xxHash's round on four
// interleaved accumulators (32 bytes a round): the chains do not wait on each
// other, which makes hashing a sample's body and garment ~4x faster than one
// chain (it ran at ~1.2 GB/s, a few ms of every training step).
struct Hasher {
  std::uint64_t a[4], b[4];
  explicit Hasher(std::uint64_t seed) {
    for (int k = 0; k < 4; ++k) a[k] = seed + kP1 * (k + 1), b[k] = (seed ^ kP4) + kP2 * (k + 1);
  }
  void add(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    std::size_t i = 0;
    for (; i + 32 <= size; i += 32)
      for (int k = 0; k < 4; ++k) {
        std::uint64_t w;
        std::memcpy(&w, bytes + i + 8 * k, 8);
        a[k] = rotl(a[k] + w * kP2, 31) * kP1;
        b[k] = rotl(b[k] ^ (w * kP3), 27) * kP4 + kP1;
      }
    for (; i + 8 <= size; i += 8) {
      std::uint64_t w;
      std::memcpy(&w, bytes + i, 8);
      a[0] = rotl(a[0] + w * kP2, 31) * kP1;
      b[0] = rotl(b[0] ^ (w * kP3), 27) * kP4 + kP1;
    }
    std::uint64_t tail = size;
    for (; i < size; ++i) tail = (tail << 8) | bytes[i];
    a[1] = rotl(a[1] + tail * kP2, 31) * kP1;
    b[1] = rotl(b[1] ^ (tail * kP3), 27) * kP4 + kP1;
  }
  // The four accumulators of each hash folded into one word.
  std::uint64_t first() const { return rotl(a[0], 1) + rotl(a[1], 7) + rotl(a[2], 12) + rotl(a[3], 18); }
  std::uint64_t second() const { return rotl(b[0], 3) ^ rotl(b[1], 11) ^ rotl(b[2], 23) ^ rotl(b[3], 41); }
};

std::size_t budget_from_environment() {
  const char* v = std::getenv("DRAPE_SURFACE_CACHE_MIB");
  if (!v || !*v) return std::size_t{2048} << 20;
  char* end = nullptr;
  const double mib = std::strtod(v, &end);
  if (end == v || mib < 0) return std::size_t{2048} << 20;
  return static_cast<std::size_t>(mib * 1048576.0);
}

}  // namespace

std::uint64_t topology_hash(const Eigen::MatrixX3i& faces) {
  Hasher h(static_cast<std::uint64_t>(faces.rows()));
  h.add(faces.data(), sizeof(int) * static_cast<std::size_t>(faces.size()));
  return avalanche(h.first() ^ rotl(h.second(), 17));
}

SurfaceKey surface_key(std::uint64_t topology, const float* body, std::size_t m, const float* points, std::size_t n) {
  Hasher h(topology);
  h.add(&m, sizeof m);
  h.add(body, sizeof(float) * m);
  h.add(&n, sizeof n);
  h.add(points, sizeof(float) * n);
  return {avalanche(h.first()), avalanche(h.second() ^ topology)};
}

SurfaceCache& SurfaceCache::shared() {
  static SurfaceCache cache(budget_from_environment());
  return cache;
}

std::shared_ptr<const SurfaceCache::Hits> SurfaceCache::find(const SurfaceKey& key) const {
  std::shared_lock lock(mutex_);
  const auto it = entries_.find(key);
  if (it == entries_.end()) return nullptr;
  return std::shared_ptr<const Hits>(it->second, &it->second->hits);
}

std::shared_ptr<const NearbyFaces> SurfaceCache::find_nearby(const SurfaceKey& key) const {
  std::shared_lock lock(mutex_);
  const auto it = entries_.find(key);
  if (it == entries_.end() || it->second->nearby.points() == 0) return nullptr;
  return std::shared_ptr<const NearbyFaces>(it->second, &it->second->nearby);
}

bool SurfaceCache::keep(const SurfaceKey& key, const std::shared_ptr<const SurfaceEntry>& entry) {
  const std::size_t size = entry->bytes();
  if (bytes_ + size > budget_) return false;
  bytes_ += size;
  entries_.emplace(key, entry);
  return true;
}

std::shared_ptr<const SurfaceCache::Hits> SurfaceCache::insert(const SurfaceKey& key, SurfaceEntry entry) {
  auto kept = std::make_shared<const SurfaceEntry>(std::move(entry));
  std::unique_lock lock(mutex_);
  if (const auto it = entries_.find(key); it != entries_.end()) kept = it->second;
  else if (keep(key, kept)) computed_.push_back(key);
  return std::shared_ptr<const Hits>(kept, &kept->hits);
}

void SurfaceCache::adopt(const SurfaceKey& key, SurfaceEntry entry) {
  auto kept = std::make_shared<const SurfaceEntry>(std::move(entry));
  std::unique_lock lock(mutex_);
  if (entries_.count(key) == 0) keep(key, kept);
}

SurfaceCache::Entries SurfaceCache::take_computed() {
  std::unique_lock lock(mutex_);
  Entries out;
  out.reserve(computed_.size());
  for (const SurfaceKey& key : computed_) out.emplace_back(key, entries_.at(key));
  computed_.clear();
  return out;
}

namespace {

// A point as it travels: face and feature (two 32-bit words), then barycentric,
// point, normal and signed distance (ten doubles), 88 bytes, in this machine's
// byte order (the ranks of one run share the machine type and the binary).
constexpr std::size_t kPointBytes = 2 * sizeof(std::int32_t) + 10 * sizeof(double);
static_assert(kPointBytes == 88, "packed_entry_bytes in the header says 88");

void put_point(const SurfacePoint& p, std::uint8_t* at) {
  const std::int32_t ints[2] = {p.face, static_cast<std::int32_t>(p.feature)};
  double reals[10];
  for (int k = 0; k < 3; ++k) reals[k] = p.barycentric[k], reals[3 + k] = p.point[k], reals[6 + k] = p.normal[k];
  reals[9] = p.signed_distance;
  std::memcpy(at, ints, sizeof ints);
  std::memcpy(at + sizeof ints, reals, sizeof reals);
}

SurfacePoint get_point(const std::uint8_t* at) {
  std::int32_t ints[2];
  double reals[10];
  std::memcpy(ints, at, sizeof ints);
  std::memcpy(reals, at + sizeof ints, sizeof reals);
  SurfacePoint p;
  p.face = ints[0];
  p.feature = static_cast<TriangleFeature>(ints[1]);
  for (int k = 0; k < 3; ++k) p.barycentric[k] = reals[k], p.point[k] = reals[3 + k], p.normal[k] = reals[6 + k];
  p.signed_distance = reals[9];
  return p;
}

}  // namespace

std::size_t packed_entry_bytes(const SurfaceEntry& entry) {
  const NearbyFaces& near = entry.nearby;
  std::size_t size = 5 * sizeof(std::uint64_t) + kPointBytes * entry.hits.size();
  if (near.points() > 0) size += sizeof(float) * (near.complete.size() + near.reach.size()) + sizeof(std::int32_t) * (near.start.size() + near.face.size());
  return size;
}

namespace {

template <class T>
void put_array(const std::vector<T>& v, std::uint8_t*& at) {
  if (!v.empty()) std::memcpy(at, v.data(), sizeof(T) * v.size());
  at += sizeof(T) * v.size();
}

template <class T>
void get_array(std::vector<T>& v, std::size_t count, const std::uint8_t*& at) {
  v.resize(count);
  if (count) std::memcpy(v.data(), at, sizeof(T) * count);
  at += sizeof(T) * count;
}

}  // namespace

std::vector<std::uint8_t> pack_surface_entries(const SurfaceCache::Entries& entries) {
  // Per entry five 64-bit words: key.a, key.b, the number of points, whether
  // nearby lists follow and how many faces they list; then the points; then
  // the lists (start, face, reach, complete).
  std::size_t size = 0;
  for (const auto& [key, entry] : entries) size += packed_entry_bytes(*entry);
  std::vector<std::uint8_t> out(size);
  std::uint8_t* at = out.data();
  for (const auto& [key, entry] : entries) {
    const NearbyFaces& near = entry->nearby;
    const bool lists = near.points() > 0;
    const std::uint64_t head[5] = {key.a, key.b, entry->hits.size(), lists ? 1u : 0u, near.face.size()};
    std::memcpy(at, head, sizeof head);
    at += sizeof head;
    for (const SurfacePoint& p : entry->hits) put_point(p, at), at += kPointBytes;
    if (!lists) continue;
    put_array(near.start, at);
    put_array(near.face, at);
    put_array(near.reach, at);
    put_array(near.complete, at);
  }
  return out;
}

std::vector<std::pair<SurfaceKey, SurfaceEntry>> unpack_surface_entries(const std::uint8_t* data, std::size_t size) {
  std::vector<std::pair<SurfaceKey, SurfaceEntry>> out;
  const std::uint8_t* at = data;
  const std::uint8_t* const end = data + size;
  auto left = [&] { return static_cast<std::size_t>(end - at); };
  while (at < end) {
    std::uint64_t head[5];
    if (left() < sizeof head) throw Error("surface cache entries: " + std::to_string(left()) + " bytes left, not an entry");
    std::memcpy(head, at, sizeof head);
    at += sizeof head;
    const std::uint64_t points = head[2], listed = head[4];
    const bool lists = head[3] == 1;
    if (head[3] > 1 || points > left() / kPointBytes)
      throw Error("surface cache entries: an entry of " + std::to_string(points) + " points runs past the end");
    SurfaceEntry entry;
    entry.hits.resize(points);
    for (auto& p : entry.hits) p = get_point(at), at += kPointBytes;
    if (lists) {
      if (listed > left() / 8 || 8 * points + 4 > left() - 8 * listed)
        throw Error("surface cache entries: nearby lists of " + std::to_string(listed) + " faces run past the end");
      NearbyFaces& near = entry.nearby;
      get_array(near.start, points + 1, at);
      get_array(near.face, listed, at);
      get_array(near.reach, listed, at);
      get_array(near.complete, points, at);
      if (near.start.front() != 0 || static_cast<std::uint64_t>(near.start.back()) != listed ||
          !std::is_sorted(near.start.begin(), near.start.end()))
        throw Error("surface cache entries: nearby lists whose offsets do not add up");
    }
    out.emplace_back(SurfaceKey{head[0], head[1]}, std::move(entry));
  }
  return out;
}

std::size_t SurfaceCache::bytes() const {
  std::shared_lock lock(mutex_);
  return bytes_;
}

std::size_t SurfaceCache::entries() const {
  std::shared_lock lock(mutex_);
  return entries_.size();
}

}  // namespace drape::geometry
