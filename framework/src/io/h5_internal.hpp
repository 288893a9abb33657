#pragma once
// Private to the HDF5 layer: the handles behind drape::h5::File and the
// translation of HDF5 exceptions into drape errors.
#include <drape/errors.hpp>
#include <drape/io/h5.hpp>
#include <drape/io/write_failure.hpp>

#include <H5Cpp.h>

#include <filesystem>
#include <memory>
#include <cerrno>
#include <cstring>
#include <string>
#include <string_view>
#include <variant>

namespace drape::h5 {

// A group or a dataset (H5Object's destructor is protected, so no unique_ptr<H5Object>).
struct Object {
  std::variant<H5::Group, H5::DataSet> handle;
  H5::H5Object* operator->() {
    return std::visit([](auto& h) -> H5::H5Object* { return &h; }, handle);
  }
};

struct File::Impl {
  std::filesystem::path path;
  H5::H5File file;
  bool writable = false;
  bool open = true;
  bool sealed = false;  // close() writes the file's checksum (h5_seal.hpp)
  // A write to it failed (a full disk): it is closed in memory, not on disk
  // (h5_file.cpp, detach_to_memory): HDF5 crashed closing such a file.
  mutable bool write_failed = false;

  std::string name() const { return path.string(); }
  bool has(const std::string& path) const;  // a link at every level of path
  // ConfigError "<file>: missing dataset /x" unless it exists and is a dataset.
  H5::DataSet open_dataset(const std::string& path) const;
  // A group or a dataset (attributes live on either).
  Object open_object(const std::string& path) const;
  void require_writable(const std::string& what) const;
};

namespace detail {

// HDF5 prints its error stack to stderr unless told not to, once per thread.
void quiet();

// The most specific message on this thread's HDF5 error stack ("" if none).
std::string innermost_error();

const H5::PredType& memory_type(DType type);
const H5::PredType& file_type(DType type);

// Runs fn, turning an H5::Exception into ConfigError (when the user's file is the
// likely culprit: reading) or Error (writing), prefixed with the file and `what`.
template <class F>
auto guarded(const File::Impl& impl, bool user_file, const std::string& what, F&& fn) -> decltype(fn()) {
  quiet();
  try {
    return fn();
  } catch (const H5::Exception& e) {
    const int error = errno;  // (a failed write's: HDF5's stack does not always keep it, e.g. H5Fcreate's)
    std::string detail = innermost_error();
    if (detail.empty()) detail = e.getDetailMsg();
    // A failed system call's account spans lines of times, addresses and
    // byte counts: its operation and the system's message are what count
    // ("file write failed: No space left on device").
    constexpr std::string_view kSystemMessage = "error message = '";
    if (const auto at = detail.find(kSystemMessage); at != std::string::npos) {
      const auto from = at + kSystemMessage.size(), to = detail.find('\'', from);
      detail = detail.substr(0, detail.find(':')) + ": " + detail.substr(from, to == std::string::npos ? to : to - from);
    } else if (!user_file && (error == ENOSPC || error == EDQUOT || error == EFBIG || error == EIO)) {
      detail += std::string(detail.empty() ? "" : ": ") + std::strerror(error);
    }
    const std::string message = impl.name() + ": " + what + (detail.empty() ? "" : " (" + detail + ")");
    if (user_file) throw ConfigError(message);
    impl.write_failed = true;
    // A write that failed: a full disk or a read-only folder says so.
    // (HDF5's own account of it, several lines of buffer addresses and
    // byte counts, adds nothing to that.)
    const std::string cause = write_failure_cause(impl.path);
    throw Error(cause.empty() ? message : cause + ": " + impl.name() + ": " + what);
  }
}

}  // namespace detail
}  // namespace drape::h5
