// drape::h5::File: opening, creating, flushing and the group structure.
#include "h5_internal.hpp"
#include "h5_seal.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>

#include <algorithm>
#include <memory>
#include <functional>
#include <numeric>

namespace fs = std::filesystem;

namespace drape::h5 {

namespace detail {

void quiet() {
  thread_local bool done = false;
  if (done) return;
  H5::Exception::dontPrint();
  done = true;
}

std::string innermost_error() {
  std::string found;
  // Walking upward starts at the function that failed first: its message says
  // what was wrong ("file signature not found"), the outer ones only "failed".
  auto visit = [](unsigned n, const H5E_error2_t* err, void* data) -> herr_t {
    auto* out = static_cast<std::string*>(data);
    if (n == 0 && err->desc) *out = err->desc;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, visit, &found);
  return found;
}

const H5::PredType& memory_type(DType type) {
  switch (type) {
    case DType::F32: return H5::PredType::NATIVE_FLOAT;
    case DType::F64: return H5::PredType::NATIVE_DOUBLE;
    case DType::I8: return H5::PredType::NATIVE_INT8;
    case DType::U8: return H5::PredType::NATIVE_UINT8;
    case DType::I32: return H5::PredType::NATIVE_INT32;
    case DType::I64: return H5::PredType::NATIVE_INT64;
  }
  throw Error("h5: unknown element type");
}

// Little-endian IEEE and two's complement: what h5py and numpy expect.
const H5::PredType& file_type(DType type) {
  switch (type) {
    case DType::F32: return H5::PredType::IEEE_F32LE;
    case DType::F64: return H5::PredType::IEEE_F64LE;
    case DType::I8: return H5::PredType::STD_I8LE;
    case DType::U8: return H5::PredType::STD_U8LE;
    case DType::I32: return H5::PredType::STD_I32LE;
    case DType::I64: return H5::PredType::STD_I64LE;
  }
  throw Error("h5: unknown element type");
}

}  // namespace detail

using detail::guarded;

const char* to_string(DType type) {
  switch (type) {
    case DType::F32: return "f32";
    case DType::F64: return "f64";
    case DType::I8: return "i8";
    case DType::U8: return "u8";
    case DType::I32: return "i32";
    case DType::I64: return "i64";
  }
  return "?";
}

std::string to_string(const Dims& dims) {
  std::string s = "[";
  for (std::size_t i = 0; i < dims.size(); ++i) s += (i ? ", " : "") + std::to_string(dims[i]);
  return s + "]";
}

std::size_t element_count(const Dims& dims) {
  return std::accumulate(dims.begin(), dims.end(), std::size_t{1}, std::multiplies<>());
}

std::string normalize(const std::string& path) {
  std::string out;
  std::size_t i = 0;
  while (i < path.size()) {
    while (i < path.size() && path[i] == '/') ++i;
    const std::size_t j = std::min(path.find('/', i), path.size());
    if (j > i) out += "/" + path.substr(i, j - i);
    i = j;
  }
  return out.empty() ? "/" : out;
}

bool is_hdf5(const fs::path& path) {
  detail::quiet();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return false;
  return H5Fis_hdf5(path.c_str()) > 0;
}

namespace {
// Whether another process holds a lock on the file that the one HDF5 takes to
// open it (shared to read, exclusive to write) conflicts with.
bool locked_by_another_process(const fs::path& path, bool exclusive) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  bool locked = false;
  if (::flock(fd, (exclusive ? LOCK_EX : LOCK_SH) | LOCK_NB) != 0)
    locked = errno == EWOULDBLOCK;
  else
    ::flock(fd, LOCK_UN);
  ::close(fd);
  return locked;
}
}  // namespace

// --- Impl helpers

bool File::Impl::has(const std::string& path) const {
  const std::string p = normalize(path);
  if (p == "/") return true;
  detail::quiet();
  try {
    // Every prefix must exist, or H5Lexists fails instead of answering no.
    for (std::size_t i = 1; i <= p.size(); ++i)
      if ((i == p.size() || p[i] == '/') && H5Lexists(file.getId(), p.substr(0, i).c_str(), H5P_DEFAULT) <= 0) return false;
    return true;
  } catch (const H5::Exception&) {
    return false;
  }
}

H5::DataSet File::Impl::open_dataset(const std::string& path) const {
  const std::string p = normalize(path);
  if (!open) throw Error(name() + ": reading " + p + ": the file is closed");
  bool found = has(p) && p != "/";
  if (found) found = guarded(*this, true, "cannot look up " + p, [&] { return file.childObjType(p) == H5O_TYPE_DATASET; });
  if (!found) throw ConfigError(name() + ": missing dataset " + p);
  return guarded(*this, true, "cannot open dataset " + p, [&] { return file.openDataSet(p); });
}

Object File::Impl::open_object(const std::string& path) const {
  const std::string p = normalize(path);
  if (!has(p)) throw ConfigError(name() + ": missing object " + p);
  return guarded(*this, true, "cannot open " + p, [&]() -> Object {
    if (p != "/" && file.childObjType(p) == H5O_TYPE_DATASET) return Object{file.openDataSet(p)};
    return Object{file.openGroup(p)};
  });
}

void File::Impl::require_writable(const std::string& what) const {
  if (!open) throw Error(name() + ": " + what + ": the file is closed");
  if (!writable) throw Error(name() + ": " + what + ": the file is open read-only");
}

// --- File

File::File(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
File::File(File&&) noexcept = default;
File& File::operator=(File&&) noexcept = default;
namespace {

// A file HDF5 could not write (its disk full) is closed in memory, not on
// disk: HDF5 1.10 cannot close a file whose last flush fails (it leaves the
// file's identifier registered over structures it already freed), and the
// next close of it -- H5::H5File's destructor, or HDF5's own at exit --
// crashed the process (an outside check: `drape train` on a full disk ended
// in SIGSEGV, and Python's Model.save took the interpreter with it). So the
// descriptor HDF5 writes through is moved onto an in-memory copy of the file
// (memfd), where the close's last writes succeed; the file on disk keeps
// what was written before the failure (a temporary its writer removes, or a
// partial dataset whose checksums tell the samples written whole).
void detach_to_memory(H5::H5File& file) {
  void* handle = nullptr;
  try {
    file.getVFDHandle(&handle);  // the default (sec2) driver hands out an int* file descriptor
  } catch (const H5::Exception&) {
    return;
  }
  if (!handle) return;
  const int fd = *static_cast<int*>(handle);
  const int memory = ::memfd_create("drape-unwritable-hdf5", MFD_CLOEXEC);
  if (memory < 0) return;
  // The bytes written so far, so that what HDF5 reads back while closing is what it wrote.
  char buffer[1 << 16];
  for (off_t at = 0;;) {
    const ssize_t n = ::pread(fd, buffer, sizeof buffer, at);
    if (n <= 0 || ::pwrite(memory, buffer, static_cast<std::size_t>(n), at) != n) break;
    at += n;
  }
  ::dup2(memory, fd);
  ::close(memory);
}

// As a last resort (the close failed even so): the object given up without
// its destructor, and a fresh, empty one in its place.
void abandon(H5::H5File& file) { std::construct_at(&file); }  // (the old one's storage reused: no destructor runs)

// Closes the file; a write to it failed (now, flushing before the close, or
// before): closed in memory (detach_to_memory), and Error saying so.
void close_safely(File::Impl& impl) {
  if (impl.writable && !impl.write_failed) {
    try {
      impl.file.flush(H5F_SCOPE_GLOBAL);
    } catch (const H5::Exception&) {
      impl.write_failed = true;
    }
  }
  if (impl.write_failed) detach_to_memory(impl.file);
  try {
    impl.file.close();
  } catch (const H5::Exception&) {
    abandon(impl.file);
    throw;
  }
  if (impl.write_failed)
    throw Error(impl.name() + ": a write to it failed (a full disk?), so the file is incomplete");
}

}  // namespace

File::~File() {
  if (!impl_ || !impl_->open) return;
  detail::quiet();
  try {
    close_safely(*impl_);
  } catch (...) {  // (H5::Exception is no std::exception)
    // Nothing sensible to do in a destructor; explicit close() reports it.
  }
}

File File::open(const fs::path& path, Access access) {
  detail::quiet();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw ConfigError(path.string() + ": no such file");
  if (fs::is_directory(path, ec)) throw ConfigError(path.string() + ": is a folder, not an HDF5 file");
  // The checksum first: HDF5 must never parse a damaged file (h5_seal.hpp).
  const bool sealed = seal::verify(path);
  if (!is_hdf5(path)) throw ConfigError(path.string() + ": not an HDF5 file");
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->writable = access == Access::ReadWrite;
  if (impl->writable && sealed) {
    // Written to, the checksum goes stale: cleared now, written again by close().
    seal::unseal(path);
    impl->sealed = true;
  }
  // Made to be sealed and not sealed yet (its writer was killed): sealed by
  // this writer's close(), as its first writer's close() would have. (An
  // outside check found a resumed dataset finished without its checksum.)
  if (impl->writable && !sealed && seal::state(path) == seal::State::Pending) impl->sealed = true;
  try {
    guarded(*impl, true, "cannot open the HDF5 file, it is truncated or corrupt", [&] {
      impl->file.openFile(path.string(), impl->writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY);
    });
  } catch (const ConfigError&) {
    // HDF5 locks a file it opens (shared to read, exclusive to write) and
    // fails the open when another process holds a conflicting lock; its
    // message then blames the file. Asked only after a failure: this process's
    // own open files are shared by HDF5 and never conflict.
    if (locked_by_another_process(path, impl->writable))
      throw FileInUse(path.string() + ": the file is in use: another process has it open" +
                      (impl->writable ? "" : " for writing") +
                      " (a drape generate, train or merge still writing it?); wait until it ends or stop it, then "
                      "run this again. The file is not damaged by this");
    throw;
  }
  return File(std::move(impl));
}

File File::create(const fs::path& path) {
  detail::quiet();
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->writable = true;
  impl->sealed = true;
  guarded(*impl, false, "cannot create the HDF5 file", [&] {
    // Room for the checksum close() writes (h5_seal.hpp).
    H5::FileCreatPropList create;
    create.setUserblock(seal::kUserBlock);
    // HDF5 1.8's format: its object headers and the other metadata it
    // parses carry checksums of their own, which the earliest format (HDF5's
    // default) lacks. Not 1.10's: that superblock marks a file open for
    // writing, and a file whose writer was killed would need h5clear.
    H5::FileAccPropList access;
    access.setLibverBounds(H5F_LIBVER_V18, H5F_LIBVER_V18);
    impl->file = H5::H5File(path.string(), H5F_ACC_TRUNC, create, access);
  });
  return File(std::move(impl));
}

const fs::path& File::path() const {
  if (!impl_) throw Error("h5: use of a moved-from file");
  return impl_->path;
}

bool File::is_open() const { return impl_ && impl_->open; }

void File::flush(bool sync_to_disk) {
  impl_->require_writable("flush");
  guarded(*impl_, false, "flush failed", [&] {
    impl_->file.flush(H5F_SCOPE_GLOBAL);
    if (!sync_to_disk) return;
    void* handle = nullptr;
    impl_->file.getVFDHandle(&handle);  // the default (sec2) driver hands out an int* file descriptor
    if (handle && ::fsync(*static_cast<int*>(handle)) != 0) throw Error(impl_->name() + ": fsync failed");
  });
}

void File::close() {
  if (!is_open()) return;
  impl_->open = false;
  guarded(*impl_, false, "closing failed", [&] { close_safely(*impl_); });  // (Error when a write failed: not sealed)
  if (impl_->writable && impl_->sealed) seal::seal(impl_->path);
}

bool File::exists(const std::string& path) const { return impl_->has(path); }

bool File::is_dataset(const std::string& path) const {
  return exists(path) && normalize(path) != "/" &&
         guarded(*impl_, true, "cannot look up " + normalize(path),
                 [&] { return impl_->file.childObjType(normalize(path)) == H5O_TYPE_DATASET; });
}

bool File::is_group(const std::string& path) const {
  if (normalize(path) == "/") return true;
  return exists(path) && guarded(*impl_, true, "cannot look up " + normalize(path),
                                 [&] { return impl_->file.childObjType(normalize(path)) == H5O_TYPE_GROUP; });
}

std::vector<std::string> File::children(const std::string& group) const {
  const std::string p = normalize(group);
  if (!is_group(p)) throw ConfigError(impl_->name() + ": missing group " + p);
  return guarded(*impl_, true, "cannot list " + p, [&] {
    const H5::Group g = impl_->file.openGroup(p);
    std::vector<std::string> names;
    for (hsize_t i = 0; i < g.getNumObjs(); ++i) names.push_back(g.getObjnameByIdx(i));
    std::sort(names.begin(), names.end());
    return names;
  });
}

std::vector<std::string> File::datasets_below(const std::string& group) const {
  std::vector<std::string> out;
  const std::string root = normalize(group);
  std::function<void(const std::string&, const std::string&)> walk = [&](const std::string& abs, const std::string& rel) {
    for (const auto& child : children(abs)) {
      const std::string a = normalize(abs + "/" + child);
      const std::string r = rel.empty() ? child : rel + "/" + child;
      if (is_dataset(a)) out.push_back(r);
      else if (is_group(a)) walk(a, r);
    }
  };
  walk(root, "");
  std::sort(out.begin(), out.end());
  return out;
}

void File::create_group(const std::string& path) {
  const std::string p = normalize(path);
  impl_->require_writable("creating group " + p);
  for (std::size_t i = 1; i <= p.size(); ++i) {
    if (i != p.size() && p[i] != '/') continue;
    const std::string prefix = p.substr(0, i);
    if (is_group(prefix)) continue;
    if (exists(prefix)) throw Error(impl_->name() + ": cannot create group " + p + ": " + prefix + " is a dataset");
    guarded(*impl_, false, "cannot create group " + prefix, [&] { impl_->file.createGroup(prefix); });
  }
}

Dims File::shape(const std::string& dataset) const {
  const H5::DataSet ds = impl_->open_dataset(dataset);
  return guarded(*impl_, true, "cannot read the shape of " + normalize(dataset), [&] {
    const H5::DataSpace space = ds.getSpace();
    const int rank = space.getSimpleExtentNdims();
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
    if (rank > 0) space.getSimpleExtentDims(dims.data());
    return Dims(dims.begin(), dims.end());
  });
}

DType File::dtype(const std::string& dataset) const {
  const std::string p = normalize(dataset);
  const H5::DataSet ds = impl_->open_dataset(p);
  return guarded(*impl_, true, "cannot read the type of " + p, [&] {
    const H5T_class_t cls = ds.getTypeClass();
    if (cls == H5T_FLOAT) {
      const std::size_t size = ds.getFloatType().getSize();
      if (size == 4) return DType::F32;
      if (size == 8) return DType::F64;
    } else if (cls == H5T_INTEGER) {
      const H5::IntType t = ds.getIntType();
      const bool is_signed = t.getSign() != H5T_SGN_NONE;
      switch (t.getSize()) {
        case 1: return is_signed ? DType::I8 : DType::U8;
        case 4: if (is_signed) return DType::I32; break;
        case 8: if (is_signed) return DType::I64; break;
        default: break;
      }
    }
    throw ConfigError(impl_->name() + ": dataset " + p + " has an element type drape does not read");
  });
}

}  // namespace drape::h5
