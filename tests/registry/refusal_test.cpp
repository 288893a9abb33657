// The registry refuses what it cannot trust: a library built for another plugin
// ABI (skipped with a message giving both versions, its factory never called)
// and two plugins of one name (an error naming both files).
#include <catch2/catch.hpp>

#include <fstream>

#include <drape/registry.hpp>

#include <filesystem>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {
const fs::path kFixtures = DRAPE_FIXTURE_DIR;
}

TEST_CASE("a plugin built for another ABI is refused with both versions", "[registry]") {
  const fs::path file = fs::canonical(kFixtures / "wrong_abi" / "libdrape_plugin_future_abi.so");
  Registry registry;
  REQUIRE_NOTHROW(registry.load_path({file.parent_path()}));

  REQUIRE(registry.refused().size() == 1);
  const std::string& why = registry.refused().front();
  CHECK_THAT(why, Catch::Contains(file.string()) && Catch::Contains("ABI") &&
                      Catch::Contains("ABI " + std::to_string(kAbiVersion + 1)) &&
                      Catch::Contains("ABI " + std::to_string(kAbiVersion)));
  // The factory was never called, so its plugin does not exist...
  CHECK(registry.find("future") == nullptr);
  // ...and asking for it explains why.
  CHECK_THROWS_WITH(registry.get("future"), Catch::Contains("refused") && Catch::Contains(file.string()));
}

TEST_CASE("loading the wrong-ABI file directly refuses it too", "[registry]") {
  Registry registry;
  registry.load_file(kFixtures / "wrong_abi" / "libdrape_plugin_future_abi.so");
  CHECK(registry.refused().size() == 1);
  CHECK(registry.all().empty());
}

TEST_CASE("two plugins with one name are an error naming both files", "[registry]") {
  const fs::path dir = kFixtures / "duplicate";
  const fs::path a = fs::canonical(dir / "libdrape_plugin_twin_a.so");
  const fs::path b = fs::canonical(dir / "libdrape_plugin_twin_b.so");
  Registry registry;
  CHECK_THROWS_AS(registry.load_path({dir}), ConfigError);
  Registry again;
  CHECK_THROWS_WITH(again.load_path({dir}), Catch::Contains("'twin'") && Catch::Contains(a.string()) &&
                                                Catch::Contains(b.string()));
}

TEST_CASE("one directory reached twice through the path is loaded once", "[registry]") {
  // Not a duplicate: the same file, e.g. --plugin-path equal to $DRAPE_PLUGIN_PATH.
  const fs::path dir = kFixtures / "duplicate";
  Registry registry;
  REQUIRE_NOTHROW(registry.load_file(dir / "libdrape_plugin_twin_a.so"));
  REQUIRE_NOTHROW(registry.load_file(dir / "." / "libdrape_plugin_twin_a.so"));
  CHECK(registry.names() == std::vector<std::string>{"twin"});
}

TEST_CASE("drape plugins reports a refused library and fails on duplicates", "[registry][cli]") {
  std::string out;
  const std::string drape = "env -u DRAPE_PLUGIN_PATH " + test::drape_program().string() + " plugins --brief";
  REQUIRE(test::run(drape + " --plugin-path " + (kFixtures / "wrong_abi").string(), out) == 0);
  CHECK_THAT(out, Catch::Contains("refused") && Catch::Contains("libdrape_plugin_future_abi.so") &&
                      Catch::Contains("ABI " + std::to_string(kAbiVersion + 1)));
  CHECK(out.find("op future") == std::string::npos);

  CHECK(test::run(drape + " --plugin-path " + (kFixtures / "duplicate").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("libdrape_plugin_twin_a.so") && Catch::Contains("libdrape_plugin_twin_b.so"));
}

TEST_CASE("a plugin path entry that is no folder says whether it is missing or no plugin file", "[registry][cli]") {
  // A single plugin file is an entry too; both were "is not a directory" (an outside check).
  test::TempDir dir;
  std::ofstream(dir / "notes.txt") << "not a plugin";
  std::string out;
  const std::string drape = "env -u DRAPE_PLUGIN_PATH " + test::drape_program().string() + " plugins --brief --plugin-path ";
  REQUIRE(test::run(drape + (dir / "libdrape_plugin_gone.so").string(), out) == 0);
  CHECK_THAT(out, Catch::Contains("libdrape_plugin_gone.so' does not exist"));
  REQUIRE(test::run(drape + (dir / "notes.txt").string(), out) == 0);
  CHECK_THAT(out, Catch::Contains("notes.txt' is neither a folder nor a plugin library (libdrape_plugin_<name>.so)"));
}

TEST_CASE("a library whose factory throws is refused with its path and the reason", "[registry]") {
  const fs::path dir = kFixtures / "failing_factory";
  const fs::path file = fs::canonical(dir / "libdrape_plugin_failing_factory.so");
  Registry registry;
  // The other libraries on the path still load: one bad file does not stop a command that does not use it.
  REQUIRE_NOTHROW(registry.load_path({dir, kFixtures / "duplicate" / "libdrape_plugin_twin_a.so"}));
  CHECK(registry.names() == std::vector<std::string>{"twin"});
  REQUIRE(registry.refused().size() == 1);
  CHECK_THAT(registry.refused().front(), Catch::Contains(file.string()) && Catch::Contains("the parameter table has no row 7"));
  CHECK_THROWS_WITH(registry.get("failing"), Catch::Contains("note: refused " + file.string()));

  std::string out;
  const std::string drape = "env -u DRAPE_PLUGIN_PATH " + test::drape_program().string() + " plugins --brief --plugin-path ";
  REQUIRE(test::run(drape + dir.string(), out) == 0);  // the command that finds the bad file still runs
  CHECK_THAT(out, Catch::Contains("refused " + file.string()) && Catch::Contains("no row 7") && Catch::Contains("energy gravity"));
}

TEST_CASE("a library with a descriptor the framework cannot use is refused and the rest of the path loads", "[registry]") {
  // One bad descriptor stopped every command, drape plugins too (an outside check).
  const std::vector<std::pair<std::string, std::string>> faults = {
      {"no_factory", "must define exactly one of create_node"},
      {"listed_twice", "it lists two plugins named 'faulty'"},
      {"bad_name", "plugin name 'has space' is not a word"},
      {"bad_default", "parameter 'factor' (float): 1 is outside the allowed range"}};
  for (const auto& [fault, why] : faults) {
    INFO(fault);
    const fs::path file = fs::canonical(kFixtures / "faulty" / fault / "libdrape_plugin_faulty.so");
    Registry registry;
    REQUIRE_NOTHROW(registry.load_path({file, kFixtures / "duplicate" / "libdrape_plugin_twin_a.so"}));
    CHECK(registry.names() == std::vector<std::string>{"twin"});
    REQUIRE(registry.refused().size() == 1);
    CHECK_THAT(registry.refused().front(), Catch::Contains(file.string()) && Catch::Contains(why));
    std::string out;
    REQUIRE(test::run("env -u DRAPE_PLUGIN_PATH " + test::drape_program().string() + " plugins --brief --plugin-path " +
                          file.string(), out) == 0);
    CHECK_THAT(out, Catch::Contains("refused " + file.string()) && Catch::Contains("energy gravity"));
  }
}

TEST_CASE("a factory that makes nothing is an error naming the plugin, not a crash", "[registry]") {
  // twin's create_node returns a null pointer: graph check and Python's
  // Model.untrained crashed on it.
  Registry registry;
  registry.load_file(kFixtures / "duplicate" / "libdrape_plugin_twin_a.so");
  CHECK_THROWS_AS(registry.create_node("twin", Params({}, {}, "twin")), ConfigError);
  CHECK_THROWS_WITH(registry.create_node("twin", Params({}, {}, "twin")),
                    Catch::Contains("plugin 'twin'") && Catch::Contains("create_node returned nothing"));
}

TEST_CASE("a library that exports no plugin symbols is refused naming what it lacks", "[registry]") {
  const fs::path file = fs::canonical(kFixtures / "no_exports" / "libdrape_plugin_no_exports.so");
  Registry registry;
  REQUIRE_NOTHROW(registry.load_path({file.parent_path()}));
  REQUIRE(registry.refused().size() == 1);
  CHECK_THAT(registry.refused().front(), Catch::Contains(file.string()) &&
                                             Catch::Contains("exports no drape_plugin_abi_version and drape_plugin_factory"));
}
