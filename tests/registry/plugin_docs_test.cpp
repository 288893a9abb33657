// docs/plugins.md lists every shipped plugin (an outside check found two in
// no document at all): a plugin added without a line there fails here.
#include <catch2/catch.hpp>

#include <drape/registry.hpp>

#include "test_support.hpp"

using namespace drape;

TEST_CASE("docs/plugins.md has a row for every shipped plugin", "[registry][docs]") {
  const std::string docs = test::read_file(test::source_dir() / "docs/plugins.md");
  const auto table = docs.find("## Every shipped plugin");
  REQUIRE(table != std::string::npos);
  const std::string rows = docs.substr(table, docs.find("\n## ", table + 1) - table);
  const Registry& registry = Registry::load_default();
  REQUIRE(registry.all().size() > 40);
  for (const PluginDescriptor* d : registry.all()) {
    INFO(d->name);
    CHECK(rows.find("| `" + d->name + "` | " + d->kind + " |") != std::string::npos);
  }
}
