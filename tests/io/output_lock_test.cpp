// OutputLock: one writer per output, refused with the holder named; released
// when the holder ends.
#include <drape/errors.hpp>
#include <drape/io/output_lock.hpp>

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <fstream>

#include <filesystem>
#include <memory>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

TEST_CASE("a second writer of an output is refused, naming the first, and the lock goes with its holder", "[io][lock]") {
  test::TempDir dir;
  const fs::path out = dir / "model.h5";
  auto first = std::make_unique<OutputLock>(out, "drape train");
  CHECK(fs::exists(OutputLock::lock_file(out)));
  // A separate open file description: as another process would hold it.
  try {
    OutputLock second(out, "drape train --force");
    FAIL("the second lock was granted");
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    CHECK_THAT(what, Catch::Contains("model.h5 is in use") &&
                         Catch::Contains("pid " + std::to_string(::getpid()) + ", drape train)") &&
                         Catch::Contains("--force included"));
  }
  first.reset();
  CHECK_FALSE(fs::exists(OutputLock::lock_file(out)));
  const OutputLock again(out, "drape train");
  CHECK(fs::exists(OutputLock::lock_file(out)));
}

TEST_CASE("an output in a missing folder is refused before the lock is taken", "[io][lock]") {
  test::TempDir dir;
  CHECK_THROWS_WITH(OutputLock(dir / "missing" / "m.h5", "drape train"), Catch::Contains("folder") && Catch::Contains("does not exist"));
  CHECK_FALSE(fs::exists(dir / "missing"));
}

// The lock covers <out>; drape's own working files of <out> are refused as
// outputs, so that no job writes over another's unfinished dataset, lock or
// training state (a merge --out z.h5.partial --force once replaced a
// running generate's partial file).
TEST_CASE("an output named as another output's working file is refused", "[io][lock]") {
  test::TempDir dir;
  CHECK_THROWS_WITH(OutputLock(dir / "z.h5.partial", "drape dataset merge"),
                    Catch::Contains("unfinished file a job writing '" + (dir / "z.h5").string()) &&
                        Catch::Contains("another name"));
  CHECK_THROWS_WITH(OutputLock(dir / "z.h5.lock", "drape dataset merge"), Catch::Contains("the lock of a job"));
  CHECK_THROWS_WITH(OutputLock(dir / "m.h5.state", "drape dataset merge"), Catch::Contains("training state of the model"));
  CHECK_FALSE(fs::exists(dir / "z.h5.partial.lock"));
  // Names that only look alike are a user's own.
  CHECK_NOTHROW(OutputLock(dir / "notes.state", "drape x"));
  CHECK_NOTHROW(OutputLock(dir / "partial.h5", "drape x"));
}

TEST_CASE("a stop signal inside a DeferredStop ends the job when the scope closes and not before", "[io][lock]") {
  // A training stopped between writing its model and its state left the
  // model an epoch ahead of the state and the epoch's line unprinted.
  test::TempDir dir;
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    std::signal(SIGTERM, SIG_DFL);  // (Catch's handler, in the test program: the lock's own is what is tested)
    {
      const OutputLock lock(dir / "m.h5", "drape train");
      {
        const DeferredStop together;
        ::kill(::getpid(), SIGTERM);
        std::ofstream(dir / "inside") << "written after the signal came";
      }
      std::ofstream(dir / "after") << "never";
    }
    ::_exit(0);
  }
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  CHECK(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGTERM);
  CHECK(fs::exists(dir / "inside"));
  CHECK_FALSE(fs::exists(dir / "after"));
  CHECK_FALSE(fs::exists(OutputLock::lock_file(dir / "m.h5")));  // the handler's work, done at the scope's end
}
