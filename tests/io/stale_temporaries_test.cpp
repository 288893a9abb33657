// A job killed while writing leaves its temporary beside the target (the
// rename never came). The next write of that target removes the temporaries
// of processes of this machine that are gone, and keeps those of a live
// process, of another machine sharing the folder, and of other targets.
#include <drape/fnv1a.hpp>
#include <drape/io/atomic_file.hpp>
#include <drape/io/output_lock.hpp>

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <climits>
#include <fstream>
#include <string>

#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

// The pid of a process that has exited and been reaped: dead for certain
// (until the system hands the number out again, which a test cannot wait for).
pid_t dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

// The machine's tag in the temporaries' names: eight hex digits of its name's FNV-1a hash.
std::string this_host() {
  char name[HOST_NAME_MAX + 1] = {};
  ::gethostname(name, sizeof name - 1);
  return drape::Fnv1a().text(name).hex().substr(0, 8);
}

void touch(const fs::path& file) { std::ofstream(file) << "left by a killed job"; }

}  // namespace

TEST_CASE("a write removes the temporaries killed jobs left of its target, and only those", "[io][atomic]") {
  test::TempDir dir;
  const std::string host = this_host();
  REQUIRE(host.size() == 8);
  REQUIRE(host.find('/') == std::string::npos);
  REQUIRE(host.find('@') == std::string::npos);
  const std::string dead = std::to_string(dead_pid()), alive = std::to_string(::getppid());
  const fs::path killed = dir / (".set.tmp" + dead + "-0@" + host + ".h5");
  const fs::path killed_state = dir / (".model.h5.tmp" + dead + "-3@" + host + ".state");
  const fs::path running = dir / (".set.tmp" + alive + "-0@" + host + ".h5");
  const fs::path elsewhere = dir / (".set.tmp" + dead + "-0@another-machine.h5");
  const fs::path other_target = dir / (".other.tmp" + dead + "-0@" + host + ".h5");
  const fs::path older_name = dir / (".set.tmp" + dead + "-0.h5");  // before the host was in the name: left alone
  for (const fs::path& f : {killed, killed_state, running, elsewhere, other_target, older_name}) touch(f);

  drape::write_text_atomically(dir / "set.h5", "done");
  CHECK_FALSE(fs::exists(killed));
  CHECK(fs::exists(running));
  CHECK(fs::exists(elsewhere));
  CHECK(fs::exists(other_target));
  CHECK(fs::exists(older_name));
  CHECK(fs::exists(killed_state));  // another target's (model.h5.state)
  drape::write_text_atomically(dir / "model.h5.state", "state");
  CHECK_FALSE(fs::exists(killed_state));
  // Nothing of the writes themselves is left behind.
  int hidden = 0;
  for (const auto& e : fs::directory_iterator(dir.path()))
    hidden += e.path().filename().string().rfind(".set.tmp", 0) == 0 || e.path().filename().string().rfind(".model", 0) == 0;
  CHECK(hidden == 3);  // running, elsewhere, older_name
  std::ifstream in(dir / "set.h5");
  std::string text;
  in >> text;
  CHECK(text == "done");
}

TEST_CASE("a job's lock removes its output's dead temporaries before it checks for room", "[io][atomic]") {
  // A training killed by a full disk left its 4.8 MB state temporary filling it, and the next run (--force
  // too) was refused "no space left" by the check made before any write could remove it.
  test::TempDir dir;
  const std::string host = this_host(), dead = std::to_string(dead_pid());
  const fs::path state = dir / (".m.h5.tmp" + dead + "-1@" + host + ".state");
  const fs::path model = dir / (".m.tmp" + dead + "-0@" + host + ".h5");
  const fs::path partial = dir / (".m.h5.tmp" + dead + "-2@" + host + ".partial");
  const fs::path other = dir / (".n.h5.tmp" + dead + "-1@" + host + ".state");
  for (const fs::path& f : {state, model, partial, other}) touch(f);
  {
    const drape::OutputLock lock(dir / "m.h5", "drape train");
    CHECK_FALSE(fs::exists(state));
    CHECK_FALSE(fs::exists(model));
    CHECK_FALSE(fs::exists(partial));
    CHECK(fs::exists(other));  // another output's
  }
}
