#pragma once
// A thin layer over HDF5 for the rest of drape: files, numeric arrays of any
// rank, string attributes h5py reads as `str`, and datasets written row by row
// (sample by sample) that may grow along their first axis.
//
// The interface uses plain C++ types only: H5Cpp.h is heavy and plugins must
// not need HDF5. HDF5's own error printing is switched off; failures become
//   ConfigError  for the user's files: missing, not HDF5, truncated or corrupt,
//                a missing dataset or attribute ("model.h5: missing dataset /weights/encoder/w")
//   Error        for everything else (a write that fails, a full disk).
// Paths inside a file are written "/group/dataset" (the leading '/' is optional).
// The HDF5 build is thread-safe, but one File must not be used by two threads at once.
#include <drape/errors.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace drape::h5 {

enum class DType { F32, F64, I8, U8, I32, I64 };
const char* to_string(DType type);  // "f32", "f64", "i8", "u8", "i32", "i64"

template <class T> struct DTypeOf;
template <> struct DTypeOf<float> { static constexpr DType value = DType::F32; };
template <> struct DTypeOf<double> { static constexpr DType value = DType::F64; };
template <> struct DTypeOf<std::int8_t> { static constexpr DType value = DType::I8; };
template <> struct DTypeOf<std::uint8_t> { static constexpr DType value = DType::U8; };
template <> struct DTypeOf<std::int32_t> { static constexpr DType value = DType::I32; };
template <> struct DTypeOf<std::int64_t> { static constexpr DType value = DType::I64; };

using Dims = std::vector<std::size_t>;
std::string to_string(const Dims& dims);  // "[2, 3]"
std::size_t element_count(const Dims& dims);

enum class Access { ReadOnly, ReadWrite };

// File::open of a file another process holds HDF5's lock on (a writer still
// at work, or readers when this one wants to write): the file is busy, not
// damaged, and the message says so.
class FileInUse : public ConfigError {
 public:
  using ConfigError::ConfigError;
};

// How a dataset is laid out on disk when it is created with File::create.
struct CreateOptions {
  // Growable along the first axis (chunked storage). Otherwise contiguous, which
  // lets row writes change raw bytes only, never the file's metadata.
  bool extendible = false;
  std::size_t chunk_rows = 0;  // extendible only; 0 chooses ~256 KiB chunks
  // Reserve the whole dataset in the file now, so later row writes allocate
  // nothing (contiguous only; sparse on disk when no fill value is written).
  bool preallocate = false;
  // Value of elements never written (converted to the dataset's type). Without
  // one, unwritten elements are unspecified (HDF5 writes no fill at all).
  std::optional<double> fill{};
};

class File {
 public:
  // Opens an existing file. ConfigError when it is missing, not an HDF5 file or
  // unreadable; FileInUse when another process has it locked.
  static File open(const std::filesystem::path& path, Access access = Access::ReadOnly);
  // Creates a file, replacing any file of that name.
  static File create(const std::filesystem::path& path);

  File(File&&) noexcept;
  File& operator=(File&&) noexcept;
  ~File();

  const std::filesystem::path& path() const;
  bool is_open() const;
  // Pushes HDF5's buffers to the operating system; with sync_to_disk also fsyncs
  // (survives a power loss, not only a killed process).
  void flush(bool sync_to_disk = false);
  void close();

  // --- structure
  bool exists(const std::string& path) const;      // a group or dataset
  bool is_dataset(const std::string& path) const;
  bool is_group(const std::string& path) const;
  std::vector<std::string> children(const std::string& group) const;  // names, sorted
  // Every dataset below a group, as paths relative to it ("encoder/w"), sorted.
  std::vector<std::string> datasets_below(const std::string& group) const;
  void create_group(const std::string& path);  // with its parents; no-op when it exists
  Dims shape(const std::string& dataset) const;  // ConfigError "missing dataset" when absent
  DType dtype(const std::string& dataset) const;

  // --- whole arrays. write creates the dataset (and parent groups) or overwrites
  // an existing one of the same shape. read converts between numeric types.
  template <class T> void write(const std::string& dataset, const Dims& shape, const T* data) {
    write_raw(dataset, shape, DTypeOf<T>::value, data);
  }
  template <class T> void write(const std::string& dataset, const std::vector<T>& data) {
    write(dataset, Dims{data.size()}, data.data());
  }
  template <class T> std::vector<T> read(const std::string& dataset, Dims* shape = nullptr) const {
    const Dims dims = this->shape(dataset);
    std::vector<T> out(element_count(dims));
    read_raw(dataset, dims, DTypeOf<T>::value, out.data());
    if (shape) *shape = dims;
    return out;
  }
  // Reads into a caller's buffer; ConfigError naming the dataset when its shape is not `expected`.
  template <class T> void read(const std::string& dataset, const Dims& expected, T* out) const {
    read_raw(dataset, expected, DTypeOf<T>::value, out);
  }

  // --- datasets written row by row (a row is everything below the first axis)
  void create(const std::string& dataset, DType type, const Dims& shape, const CreateOptions& options = {});
  template <class T> void create(const std::string& dataset, const Dims& shape, const CreateOptions& options = {}) {
    create(dataset, DTypeOf<T>::value, shape, options);
  }
  void resize_rows(const std::string& dataset, std::size_t rows);  // extendible only
  template <class T> void write_rows(const std::string& dataset, std::size_t first, std::size_t count, const T* data) {
    rows_raw(dataset, first, count, DTypeOf<T>::value, const_cast<T*>(data), true);
  }
  template <class T> void read_rows(const std::string& dataset, std::size_t first, std::size_t count, T* out) const {
    const_cast<File*>(this)->rows_raw(dataset, first, count, DTypeOf<T>::value, out, false);
  }
  // Grows an extendible dataset by `count` rows and writes them; returns the first new row.
  template <class T> std::size_t append_rows(const std::string& dataset, std::size_t count, const T* data) {
    const std::size_t first = shape(dataset).at(0);
    resize_rows(dataset, first + count);
    write_rows(dataset, first, count, data);
    return first;
  }

  // --- attributes of "/" or of any group or dataset. Strings are variable-length
  // UTF-8 (h5py gives str); numbers are f64 scalars. Setting replaces.
  void set_attribute(const std::string& object, const std::string& name, const std::string& value);
  void set_attribute(const std::string& object, const std::string& name, const char* value) {
    set_attribute(object, name, std::string(value));
  }
  void set_attribute(const std::string& object, const std::string& name, double value);
  bool has_attribute(const std::string& object, const std::string& name) const;
  std::vector<std::string> attribute_names(const std::string& object) const;  // sorted
  // nullopt when absent; ConfigError when present with another type.
  std::optional<std::string> string_attribute(const std::string& object, const std::string& name) const;
  std::optional<double> number_attribute(const std::string& object, const std::string& name) const;
  // ConfigError "file: missing attribute 'name' of /object" when absent.
  std::string require_string_attribute(const std::string& object, const std::string& name) const;

  struct Impl;  // opaque: holds the HDF5 handles

 private:
  explicit File(std::unique_ptr<Impl> impl);
  void write_raw(const std::string& dataset, const Dims& shape, DType type, const void* data);
  void read_raw(const std::string& dataset, const Dims& expected, DType type, void* out) const;
  void rows_raw(const std::string& dataset, std::size_t first, std::size_t count, DType type, void* data, bool write);
  std::unique_ptr<Impl> impl_;
};

// True when the file exists and starts with the HDF5 signature.
bool is_hdf5(const std::filesystem::path& path);

// "/a/b" for "a/b", "/a/b/" and "/a//b"; "/" for "" and "/".
std::string normalize(const std::string& path);

}  // namespace drape::h5
