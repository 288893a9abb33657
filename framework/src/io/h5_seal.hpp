#pragma once
// Private to the HDF5 layer: a CRC-32 of the whole file, kept in the file's
// 512-byte HDF5 user block (which HDF5 and h5py skip), and checked before
// HDF5 parses anything. A bit flipped in the metadata can send HDF5's parser
// into an endless loop (a variable-length string's heap, for one); a flip in
// the weights changes a model's predictions silently. Both are caught here.
//
// The block starts with the text "drape sealed hdf5 1\n" and one line
//   "length <payload bytes> crc32 <hex> check <hex>\n"
// (check: the CRC of "length ... crc32 <hex>"), then zeros: `head -c 80 f.h5`
// shows it. A block of zeros is a file whose writer has not sealed it yet (or
// was killed first): it opens unchecked, like any file without a block.
#include <filesystem>

namespace drape::h5::seal {

constexpr std::size_t kUserBlock = 512;

enum class State {
  Unsealed,  // no user block
  Pending,   // a user block of zeros: made to be sealed, its writer not finished (or killed first)
  Sealed,    // the magic line is there
  Damaged,   // a user block that is neither
};

State state(const std::filesystem::path& path);

// ConfigError naming the file when it is sealed and its bytes, length or
// header do not match. True for a sealed file that matches, false for an
// unsealed or pending one.
bool verify(const std::filesystem::path& path);

// Writes the header of a closed file created with a user block; fsyncs.
void seal(const std::filesystem::path& path);

// Zeros the header of a file verify() found sealed (before it is opened for writing).
void unseal(const std::filesystem::path& path);

}  // namespace drape::h5::seal
