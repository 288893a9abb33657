// Every graph node the registry finds has its backward checked against finite
// differences, whatever its name: the nodes that take plain tensors are
// checked here on random inputs (add, scale, concat, l2, vertex_distance, linear: no template
// assets needed), every other one in its own test file, which the table below
// names and this test reads (the file must build that node by name and compare
// it with differences). A new node plugin in neither place fails here, naming
// itself, as a new energy is checked by tests/energies/conformance_test.cpp.
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include <fstream>
#include <map>
#include <sstream>

#include "plugin_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

struct Case {
  std::string params;
  std::map<std::string, Tensor> inputs;
};

// Nodes of plain tensors, checked here: one or more parameter sets each.
std::map<std::string, std::vector<Case>> plain_cases() {
  const Tensor a = random_tensor(2, 5, 3, 11), b = random_tensor(2, 5, 3, 12), c = random_tensor(2, 5, 3, 13);
  return {
      {"add", {{"{}", {{"a", a}, {"b", b}}}, {"{}", {{"a", a}, {"b", b}, {"c", c}, {"d", random_tensor(2, 5, 3, 14)}}}}},
      {"scale", {{"{factor: -2.5}", {{"x", a}}}, {"{factor: 0.125}", {{"x", b}}}}},
      {"concat", {{"{}", {{"a", a}, {"b", random_tensor(2, 5, 4, 15)}}}, {"{}", {{"a", a}, {"b", random_tensor(2, 1, 2, 16)}}}}},
      {"l2", {{"{}", {{"pred", a}, {"target", b}}}}},
      {"vertex_distance", {{"{}", {{"pred", a}, {"target", b}}}}},
      {"linear", {{"{width: 4, activation: tanh}", {{"x", a}}}}},
  };
}

// Nodes that need a template's assets or a body: the test file that checks
// their backward against differences.
const std::map<std::string, std::string>& checked_elsewhere() {
  static const std::map<std::string, std::string> files = {
      {"cnn1d", "tests/plugins/cnn1d_test.cpp"},
      {"gcn", "tests/gcn/gcn_test.cpp"},
      {"gcn_learned", "tests/gcn/gcn_learned_test.cpp"},
      {"pointnet", "tests/plugins/pointnet_test.cpp"},
      {"anchor_blend", "tests/gcn/tailornet_parts_test.cpp"},
      {"cnn1d_decoder", "tests/losses/cnn1d_decoder_test.cpp"},
      {"gcn_decoder", "tests/gcn/gcn_test.cpp"},
      {"mlp", "tests/plugins/mlp_test.cpp"},
      {"msgcn", "tests/gcn/msgcn_test.cpp"},
      {"spectral", "tests/gcn/spectral_test.cpp"},
      {"uvcnn", "tests/losses/uvcnn_test.cpp"},
      {"deformation", "tests/losses/deformation_test.cpp"},
      {"direction", "tests/losses/direction_test.cpp"},
      {"edge", "tests/plugins/edge_test.cpp"},
      {"laplacian", "tests/losses/laplacian_test.cpp"},
      {"penetration", "tests/losses/penetration_test.cpp"},
      {"spectral_loss", "tests/losses/spectral_loss_test.cpp"},
      {"v2v", "tests/losses/v2v_test.cpp"},
      {"gather", "tests/plugins/gather_test.cpp"},
      {"push_out", "tests/gcn/tailornet_parts_test.cpp"},
      {"spectral_lowpass", "tests/gcn/tailornet_parts_test.cpp"},
      {"subtract_mean_body", "tests/plugins/template_offset_test.cpp"},
      {"resample_body", "tests/plugins/resample_body_test.cpp"},
      {"add_template", "tests/plugins/template_offset_test.cpp"},
      {"skin", "tests/plugins/skin_test.cpp"},
      {"skin_rotation", "tests/plugins/skin_rotation_test.cpp"},
  };
  return files;
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("every node plugin's backward is checked against finite differences", "[plugins][gradcheck]") {
  const auto plain = plain_cases();
  int nodes = 0;
  for (const PluginDescriptor* d : plugins().all()) {
    if (!d->create_node) continue;  // energies, bodies, garments: their own conformance tests
    ++nodes;
    INFO("node plugin '" << d->name << "' (" << d->file << ")");
    if (const auto it = plain.find(d->name); it != plain.end()) {
      for (const Case& c : it->second) {
        INFO("params " << c.params);
        auto node = make_node(d->name, c.params);
        const GradCheckReport r = check_node_gradients(*node, c.inputs, {"n", 3});
        INFO(r.str());
        CHECK_FALSE(r.entries.empty());
        CHECK(r.ok(1e-2));
      }
      continue;
    }
    const auto file = checked_elsewhere().find(d->name);
    if (file == checked_elsewhere().end()) {
      FAIL_CHECK("no gradient check: add its inputs to plain_cases() here, or name the test file that checks it in "
                 "checked_elsewhere()");
      continue;
    }
    const std::string text = read_text(source_dir() / file->second);
    INFO("its test " << file->second);
    CHECK_THAT(text, Catch::Contains("\"" + d->name + "\""));
    CHECK_THAT(text, Catch::Contains("check_node_gradients") || Catch::Contains("finite differences"));
  }
  CHECK(nodes > 0);
  // Neither table names a node that is no longer registered.
  for (const auto& [name, cases] : plain) {
    INFO(name);
    CHECK(plugins().find(name) != nullptr);
  }
  for (const auto& [name, file] : checked_elsewhere()) {
    INFO(name);
    CHECK(plugins().find(name) != nullptr);
  }
}

TEST_CASE("add and scale compute what they say", "[plugins]") {
  const Tensor a = random_tensor(1, 4, 3, 1), b = random_tensor(1, 4, 3, 2);
  auto add = make_node("add");
  const auto sum = run_forward(*add, {{"a", a}, {"b", b}});
  CHECK(sum.at("out").vec().isApprox(a.vec() + b.vec()));
  CHECK_THROWS_AS(add->setup({{"a", {4, 3}}, {"b", {4, 2}}}, {}), ConfigError);
  auto scale = make_node("scale", "{factor: -3}");
  CHECK(run_forward(*scale, {{"x", a}}).at("out").vec().isApprox(-3.0f * a.vec()));
}
