// A full disk and a read-only folder are named as such, with the user's file
// (issue 58: "H5Dwrite failed" named a temporary file). Needs root to mount a
// 4 MiB tmpfs; skipped with a message elsewhere.
#include <drape/io/atomic_file.hpp>
#include <drape/errors.hpp>
#include <drape/io/write_failure.hpp>

#include <catch2/catch.hpp>

#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

TEST_CASE("a full disk and a read-only file system are named, with the user's file", "[io][write-failure]") {
  test::TempDir dir;
  const fs::path mnt = dir / "small";
  fs::create_directories(mnt);
  if (::getuid() != 0 || ::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=4m") != 0) {
    WARN("skipped: mounting a 4 MiB tmpfs needs root and a kernel that lets it (the checks of write_failure_cause are untested here)");
    return;
  }
  struct Unmount {
    fs::path at;
    ~Unmount() { ::umount(at.c_str()); }
  } unmount{mnt};
  CHECK(write_failure_cause(mnt / "a.txt") == "");
  {
    std::ofstream fill(mnt / "fill");
    const std::string block(4096, 'x');
    for (int k = 0; k < 1024 && fill; ++k) fill << block << std::flush;  // until the 4 MiB are full
  }
  const std::string cause = write_failure_cause(mnt / "model.h5");
  CHECK_THAT(cause, Catch::Contains("no space left on '" + mnt.string() + "'"));
  CHECK_THROWS_WITH(check_writable_output(mnt / "model.h5", "--out"),
                    Catch::Contains("--out " + (mnt / "model.h5").string() + ": no space left on"));
  // Refused before writing on a full disk...
  CHECK_THROWS_WITH(write_text_atomically(mnt / "report.txt", "x"), Catch::Contains("report.txt': no space left on"));
  // ... and a disk that fills during the write: the user's file named, not the temporary one.
  fs::resize_file(mnt / "fill", 2u << 20);  // 2 MiB of 4 left free
  try {
    write_atomically(mnt / "report.bin", [](const fs::path& tmp) {
      std::ofstream f(tmp, std::ios::binary);
      const std::string block(1 << 16, 'y');
      for (int k = 0; k < 64 && f; ++k) f << block << std::flush;  // 4 MiB
      if (!f) throw Error("writing " + tmp.string() + " failed");
    });
    FAIL("4 MiB written in 2 MiB");
  } catch (const Error& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK_THAT(what, Catch::Contains("report.bin': no space left on") && !Catch::Contains(".tmp"));
  }
  CHECK_FALSE(fs::exists(mnt / "report.bin"));
  fs::remove(mnt / "fill");
  REQUIRE(::mount("tmpfs", mnt.c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, "size=4m") == 0);
  CHECK_THAT(write_failure_cause(mnt / "g.obj"), Catch::Contains("cannot write in '" + mnt.string() + "' (read-only file system)"));
  CHECK_THROWS_AS(check_writable_output(mnt / "g.obj", "--out"), ConfigError);
}

TEST_CASE("a missing folder is a usage error naming the folder", "[io][write-failure]") {
  test::TempDir dir;
  CHECK_THAT(write_failure_cause(dir / "nope" / "x.h5"), Catch::Contains("folder '" + (dir / "nope").string() + "' does not exist"));
  CHECK_THROWS_AS(write_text_atomically(dir / "nope" / "x.txt", "a"), ConfigError);
  CHECK_THROWS_WITH(check_writable_output(dir.path(), "--out"), Catch::Contains("is a folder"));
}

TEST_CASE("an output folder that is a file or lies under one is refused before the work", "[io][write-failure]") {
  // hierarchy --out and assets --cache-dir failed after the work with "filesystem error: cannot create directories".
  test::TempDir dir;
  std::ofstream(dir / "afile.txt") << "x";
  CHECK_THROWS_WITH(check_output_folder(dir / "afile.txt", "--out"), Catch::Contains("--out " + (dir / "afile.txt").string() + ": is a file, not a folder"));
  CHECK_THROWS_WITH(check_output_folder(dir / "afile.txt" / "sub", "--out"), Catch::Contains("is a file, not a folder"));
  CHECK_NOTHROW(check_output_folder(dir.path(), "--out"));
  CHECK_NOTHROW(check_output_folder(dir / "new" / "deeper", "--out"));  // made when the job writes
  CHECK_FALSE(std::filesystem::exists(dir / "new"));                    // (not by the check)
  // /proc has no blocks: not "no space left", which it said.
  if (std::filesystem::is_directory("/proc/self"))
    CHECK_THAT(write_failure_cause("/proc/x.html"), Catch::Contains("a virtual file system"));
}

TEST_CASE("an output named by a link is written through it, and a device or pipe is refused", "[io][write-failure]") {
  // An outside check: the rename over the output replaced a symbolic link with a file (the link's target left
  // as it was, and a job on the link and one on its target took different locks), and a device node made with
  // mknod with a regular file (as root, --out /dev/null would replace the system's /dev/null).
  test::TempDir dir;
  std::ofstream(dir / "real.obj") << "old";
  fs::create_symlink(dir / "real.obj", dir / "link.obj");
  write_text_atomically(dir / "link.obj", "new");
  CHECK(fs::is_symlink(dir / "link.obj"));
  CHECK(test::read_file(dir / "real.obj") == "new");
  CHECK(output_target(dir / "link.obj") == fs::weakly_canonical(dir / "real.obj"));
  CHECK(output_target(dir / "real.obj") == dir / "real.obj");
  // A link to a file not yet made: written as that file.
  fs::create_symlink(dir / "later.obj", dir / "to_later.obj");
  write_text_atomically(dir / "to_later.obj", "made");
  CHECK(fs::is_symlink(dir / "to_later.obj"));
  CHECK(test::read_file(dir / "later.obj") == "made");
  // A pipe (no root needed, unlike a device node) and a character device.
  REQUIRE(::mkfifo((dir / "pipe.obj").c_str(), 0644) == 0);
  CHECK_THROWS_WITH(write_text_atomically(dir / "pipe.obj", "x"),
                    Catch::Contains("pipe.obj': it is a device, a pipe or a socket, not a file"));
  CHECK(fs::is_fifo(dir / "pipe.obj"));
  CHECK_THROWS_AS(output_target("/dev/null"), ConfigError);
}
