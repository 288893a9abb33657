// Sealed HDF5 files: drape's files carry a CRC-32 of themselves in the HDF5
// user block, checked before HDF5 parses them, so a damaged model, checkpoint
// or dataset is refused with one line instead of hanging the reader (HDF5 can
// loop forever on a damaged variable-length string) or loading silently
// changed weights. Every flipped bit of a checkpoint is tried here; ctest's
// timeout on this program is what catches a hang.
#include <catch2/catch.hpp>

#include "test_support.hpp"

#include <drape/io/checkpoint.hpp>
#include <drape/io/h5.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <random>

using namespace drape;
using drape::test::TempDir;
using drape::test::message_of;
namespace fs = std::filesystem;

namespace {

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// A small checkpoint: two weight matrices, the graph text and metadata as
// string attributes, an optimiser scalar.
void save_small_checkpoint(const fs::path& path, Weight& a, Weight& b) {
  a.value = Tensor(1, 7, 5);
  b.value = Tensor(1, 1, 5);
  for (int i = 0; i < 35; ++i) a.value.data()[i] = 0.01f * static_cast<float>(i) - 0.1f;
  for (int i = 0; i < 5; ++i) b.value.data()[i] = -0.5f + static_cast<float>(i);
  a.grad = Tensor(1, 7, 5);
  b.grad = Tensor(1, 1, 5);
  Checkpoint c;
  c.graph = "nodes:\n  enc: {plugin: dense, width: 5}\n";
  c.meta = {{"epoch", "12"}, {"seed", "3"}, {"note", ""}};
  c.history["train_loss"] = {0.5, 0.25, 0.125};
  save_checkpoint(path, NamedWeights{{"enc/w", &a}, {"enc/b", &b}}, c);
}

// Loads everything the checkpoint holds; true when it equals what was saved.
bool loads_as_saved(const fs::path& path, const Weight& a, const Weight& b) {
  Weight la, lb;
  la.value = Tensor(1, 7, 5);
  lb.value = Tensor(1, 1, 5);
  load_weights(path, NamedWeights{{"enc/w", &la}, {"enc/b", &lb}});
  const Checkpoint c = read_checkpoint(path);
  return la.value.vec() == a.value.vec() && lb.value.vec() == b.value.vec() &&
         c.graph == "nodes:\n  enc: {plugin: dense, width: 5}\n" && c.meta.at("epoch") == "12" && c.meta.at("note").empty() &&
         c.history.at("train_loss") == std::vector<double>{0.5, 0.25, 0.125};
}

}  // namespace

TEST_CASE("h5 seal: a written file carries its checksum and round-trips", "[hdf5][seal]") {
  TempDir dir;
  Weight a, b;
  save_small_checkpoint(dir / "m.h5", a, b);
  const std::string bytes = read_bytes(dir / "m.h5");
  REQUIRE(bytes.size() > 512);
  CHECK(bytes.rfind("drape sealed hdf5 1\nlength ", 0) == 0);
  // The HDF5 signature sits after the 512-byte user block.
  CHECK(bytes.substr(512, 8) == std::string("\x89HDF\r\n\x1a\n", 8));
  CHECK(h5::is_hdf5(dir / "m.h5"));
  CHECK(loads_as_saved(dir / "m.h5", a, b));
}

TEST_CASE("h5 seal: every single flipped bit of a checkpoint is refused or harmless", "[hdf5][seal]") {
  TempDir dir;
  Weight a, b;
  save_small_checkpoint(dir / "m.h5", a, b);
  const std::string good = read_bytes(dir / "m.h5");
  // Every byte of the user block and the first 4 KiB (superblock, root
  // group, attributes), then a random sample of the rest; one random bit each.
  std::vector<std::size_t> positions;
  for (std::size_t i = 0; i < std::min<std::size_t>(good.size(), 4096); i += 3) positions.push_back(i);
  std::mt19937 rng(11);
  std::uniform_int_distribution<std::size_t> anywhere(0, good.size() - 1);
  for (int k = 0; k < 300; ++k) positions.push_back(anywhere(rng));
  std::uniform_int_distribution<int> bit(0, 7);
  int refused = 0, harmless = 0;
  for (const std::size_t at : positions) {
    std::string bad = good;
    bad[at] = static_cast<char>(bad[at] ^ (1 << bit(rng)));
    write_bytes(dir / "bad.h5", bad);
    bool same = false;
    const std::string error = message_of([&] { same = loads_as_saved(dir / "bad.h5", a, b); });
    INFO("byte " << at << ": " << error);
    if (error == "(no exception)") {
      // Only the header's zero padding may change without the checksum noticing.
      CHECK(same);
      CHECK(at < 512);
      ++harmless;
    } else {
      CHECK(error.find((dir / "bad.h5").string()) != std::string::npos);
      CHECK(error.find("corrupt") != std::string::npos);
      ++refused;
    }
  }
  CHECK(refused > 600);
  INFO(refused << " refused, " << harmless << " harmless");
}

TEST_CASE("h5 seal: truncated, grown and damaged-header files are refused naming the file", "[hdf5][seal]") {
  TempDir dir;
  Weight a, b;
  save_small_checkpoint(dir / "m.h5", a, b);
  const std::string good = read_bytes(dir / "m.h5");
  write_bytes(dir / "short.h5", good.substr(0, good.size() - 1));
  CHECK_THAT(message_of([&] { read_checkpoint(dir / "short.h5"); }), Catch::Contains("short.h5: is corrupt: truncated"));
  write_bytes(dir / "long.h5", good + "x");
  CHECK_THAT(message_of([&] { read_checkpoint(dir / "long.h5"); }), Catch::Contains("long.h5: is corrupt: grown"));
  std::string header = good;
  header[30] = static_cast<char>(header[30] ^ 1);  // a digit of the length
  write_bytes(dir / "header.h5", header);
  CHECK_THAT(message_of([&] { read_checkpoint(dir / "header.h5"); }), Catch::Contains("checksum header is damaged"));
  std::string block = good;
  block[0] = 'D';  // the magic itself: a user block that is neither sealed nor blank
  write_bytes(dir / "block.h5", block);
  CHECK_THAT(message_of([&] { read_checkpoint(dir / "block.h5"); }), Catch::Contains("checksum header is damaged"));
}

TEST_CASE("h5 seal: a file opened for writing is resealed on close, and a killed writer's file still opens", "[hdf5][seal]") {
  TempDir dir;
  {
    h5::File f = h5::File::create(dir / "d.h5");
    f.write("/x", std::vector<double>{1, 2, 3});
    f.close();
  }
  {
    h5::File f = h5::File::open(dir / "d.h5", h5::Access::ReadWrite);
    // Open for writing, the stale checksum is cleared: readers meanwhile see an unsealed file.
    CHECK(read_bytes(dir / "d.h5").substr(0, 20) == std::string(20, '\0'));
    f.write("/y", std::vector<double>{4, 5});
    f.close();
  }
  CHECK(read_bytes(dir / "d.h5").rfind("drape sealed hdf5 1\n", 0) == 0);
  CHECK(h5::File::open(dir / "d.h5").read<double>("/y") == std::vector<double>{4, 5});

  // A writer killed before close leaves a blank user block: the file opens
  // (the 1.8 format marks no "open for writing" flag that would need h5clear).
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    try {
      h5::File f = h5::File::create(dir / "killed.h5");
      f.write("/x", std::vector<double>{7, 8});
      f.flush(true);
    } catch (...) {
      _exit(3);
    }
    _exit(0);  // no destructor, no close: as if killed
  }
  int status = 0;
  waitpid(child, &status, 0);
  REQUIRE(WIFEXITED(status));
  REQUIRE(WEXITSTATUS(status) == 0);
  CHECK(read_bytes(dir / "killed.h5").substr(0, 20) == std::string(20, '\0'));
  CHECK(h5::File::open(dir / "killed.h5").read<double>("/x") == std::vector<double>{7, 8});
}
