// drape::h5 seals: a checksum of the whole file in its HDF5 user block,
// checked before HDF5 parses a byte of it (h5_seal.hpp).
#include "h5_seal.hpp"

#include <drape/errors.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace drape::h5::seal {

namespace {

constexpr char kMagic[] = "drape sealed hdf5 1\n";
constexpr std::size_t kMagicLength = sizeof(kMagic) - 1;
constexpr unsigned char kSignature[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};

// A file descriptor closed on every path.
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

std::string system_error(const std::filesystem::path& path, const std::string& what) {
  return path.string() + ": " + what + ": " + std::strerror(errno);
}

bool read_exactly(int fd, void* buffer, std::size_t count, off_t offset) {
  auto* p = static_cast<unsigned char*>(buffer);
  while (count > 0) {
    const ssize_t n = ::pread(fd, p, count, offset);
    if (n <= 0) return false;
    p += n;
    count -= static_cast<std::size_t>(n);
    offset += n;
  }
  return true;
}

void write_exactly(int fd, const void* buffer, std::size_t count, off_t offset, const std::filesystem::path& path) {
  const auto* p = static_cast<const unsigned char*>(buffer);
  while (count > 0) {
    const ssize_t n = ::pwrite(fd, p, count, offset);
    if (n <= 0) throw Error(system_error(path, "writing its checksum failed"));
    p += n;
    count -= static_cast<std::size_t>(n);
    offset += n;
  }
}

// CRC-32 (zlib's) of bytes [from, from + length) of the file.
std::uint32_t crc_of(int fd, off_t from, std::uint64_t length, const std::filesystem::path& path) {
  std::vector<unsigned char> buffer(1 << 20);
  uLong crc = crc32(0L, Z_NULL, 0);
  std::uint64_t left = length;
  off_t at = from;
  while (left > 0) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(left, buffer.size()));
    if (!read_exactly(fd, buffer.data(), n, at)) throw ConfigError(path.string() + ": is truncated (shorter than its checksum says)");
    crc = crc32(crc, buffer.data(), static_cast<uInt>(n));
    left -= n;
    at += static_cast<off_t>(n);
  }
  return static_cast<std::uint32_t>(crc);
}

// The header line "length <bytes> crc32 <hex> check <hex>\n" after the magic;
// `check` is the CRC of the line before it, so a flip in the numbers is told
// apart from a flip in the payload.
std::string header_fields(std::uint64_t length, std::uint32_t crc) {
  char line[96];
  std::snprintf(line, sizeof line, "length %llu crc32 %08x", static_cast<unsigned long long>(length), crc);
  return line;
}

std::uint32_t crc_of_text(const std::string& text) {
  return static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(text.data()),
                                          static_cast<uInt>(text.size())));
}

}  // namespace

State state(const std::filesystem::path& path) {
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (f.fd < 0) return State::Unsealed;  // File::open reports missing files itself
  std::array<unsigned char, kUserBlock + sizeof kSignature> head{};
  const bool whole = read_exactly(f.fd, head.data(), head.size(), 0);
  // The magic first: a flip in the HDF5 signature after it, or a sealed file
  // cut short, is damage too (verify() says which).
  if (std::memcmp(head.data(), kMagic, kMagicLength) == 0) return State::Sealed;
  if (!whole) return State::Unsealed;
  if (std::memcmp(head.data() + kUserBlock, kSignature, sizeof kSignature) != 0) return State::Unsealed;
  // A user block of zeros is a sealed-format file whose writer has not
  // finished (or was killed): as valid as any unsealed file.
  for (std::size_t i = 0; i < kUserBlock; ++i)
    if (head[i] != 0) return State::Damaged;
  return State::Pending;
}

bool verify(const std::filesystem::path& path) {
  const State s = state(path);
  if (s == State::Unsealed || s == State::Pending) return false;
  const std::string corrupt = path.string() + ": is corrupt: ";
  if (s == State::Damaged) throw ConfigError(corrupt + "its checksum header is damaged");
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (f.fd < 0) throw ConfigError(system_error(path, "cannot open"));
  std::array<char, kUserBlock> block{};
  if (!read_exactly(f.fd, block.data(), block.size(), 0)) throw ConfigError(corrupt + "too short");
  const std::string text(block.data() + kMagicLength, strnlen(block.data() + kMagicLength, kUserBlock - kMagicLength));
  unsigned long long length = 0;
  unsigned crc = 0, check = 0;
  if (std::sscanf(text.c_str(), "length %llu crc32 %8x check %8x", &length, &crc, &check) != 3 ||
      crc_of_text(header_fields(length, crc)) != check)
    throw ConfigError(corrupt + "its checksum header is damaged");
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) throw ConfigError(system_error(path, "cannot stat"));
  const auto size = static_cast<unsigned long long>(st.st_size);
  if (size != kUserBlock + length)
    throw ConfigError(corrupt + (size < kUserBlock + length ? "truncated: " : "grown: ") + std::to_string(size) +
                      " bytes, its checksum covers " + std::to_string(kUserBlock + length));
  if (crc_of(f.fd, kUserBlock, length, path) != crc)
    throw ConfigError(corrupt + "its contents do not match the checksum written with it (damaged on disk or in transfer)");
  return true;
}

void seal(const std::filesystem::path& path) {
  Fd f{::open(path.c_str(), O_RDWR | O_CLOEXEC)};
  if (f.fd < 0) throw Error(system_error(path, "cannot open to write its checksum"));
  struct stat st {};
  if (::fstat(f.fd, &st) != 0 || static_cast<std::size_t>(st.st_size) < kUserBlock)
    throw Error(path.string() + ": cannot write its checksum: the file has no user block");
  const std::uint64_t length = static_cast<std::uint64_t>(st.st_size) - kUserBlock;
  const std::uint32_t crc = crc_of(f.fd, kUserBlock, length, path);
  const std::string fields = header_fields(length, crc);
  char check[16];
  std::snprintf(check, sizeof check, "%08x", crc_of_text(fields));
  const std::string header = std::string(kMagic) + fields + " check " + check + "\n";
  std::array<char, kUserBlock> block{};
  std::memcpy(block.data(), header.data(), header.size());
  write_exactly(f.fd, block.data(), block.size(), 0, path);
  if (::fsync(f.fd) != 0) throw Error(system_error(path, "fsync after writing its checksum failed"));
}

void unseal(const std::filesystem::path& path) {
  Fd f{::open(path.c_str(), O_RDWR | O_CLOEXEC)};
  if (f.fd < 0) throw Error(system_error(path, "cannot open to clear its checksum"));
  const std::array<char, kUserBlock> zeros{};
  write_exactly(f.fd, zeros.data(), zeros.size(), 0, path);
}

}  // namespace drape::h5::seal
