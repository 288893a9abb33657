#include <drape/params.hpp>

#include <catch2/catch.hpp>

using namespace drape;

namespace {
const std::vector<ParamSpec> specs = {
    {"width", ParamType::Int, "64", "channels", 1.0, 4096.0},
    {"rate", ParamType::Float, "0.5", "a rate", 0.0, 1.0},
    {"channels", ParamType::IntList, "[32, 64]", "per layer", 1.0, {}},
    {"activation", ParamType::String, "relu", "nonlinearity", {}, {}, {"relu", "leaky_relu", "tanh"}},
    {"flag", ParamType::Bool, "false", "a switch"},
};
ParamValues values(const std::string& yaml) { return param_values_from_yaml(YAML::Load(yaml), "g.yaml"); }
}  // namespace

TEST_CASE("params fill in defaults and read typed values", "[params]") {
  const Params p(specs, values("{ width: 128, channels: [8, 16, 32] }"), "node 'enc' (cnn1d)");
  CHECK(p.get_int("width") == 128);
  CHECK(p.get_float("rate") == Approx(0.5));
  CHECK(p.get_int_list("channels") == std::vector<long>{8, 16, 32});
  CHECK(p.get_string("activation") == "relu");
  CHECK_FALSE(p.get_bool("flag"));
  CHECK(p.get_float("width") == Approx(128.0));  // an int reads as a float too
  CHECK(p.to_yaml()["width"].as<int>() == 128);
}

TEST_CASE("params report unknown keys with close matches and the line", "[params]") {
  try {
    Params(specs, values("{ width: 64,\n  widht: 3 }"), "node 'enc' (cnn1d)");
    FAIL("no error");
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    CHECK_THAT(m, Catch::Contains("g.yaml:2"));
    CHECK_THAT(m, Catch::Contains("unknown parameter 'widht'"));
    CHECK_THAT(m, Catch::Contains("did you mean 'width'"));
  }
}

TEST_CASE("params check types, ranges and choices", "[params]") {
  CHECK_THROWS_WITH(Params(specs, values("{ width: 0 }"), "n"), Catch::Contains("outside the allowed range"));
  CHECK_THROWS_WITH(Params(specs, values("{ width: 2.5 }"), "n"), Catch::Contains("not an integer"));
  CHECK_THROWS_WITH(Params(specs, values("{ rate: fast }"), "n"), Catch::Contains("not a number"));
  CHECK_THROWS_WITH(Params(specs, values("{ channels: [4, 0] }"), "n"), Catch::Contains("outside"));
  CHECK_THROWS_WITH(Params(specs, values("{ activation: relux }"), "n"), Catch::Contains("did you mean 'relu'"));
  CHECK_THROWS_WITH(Params(specs, values("{ flag: maybe }"), "n"), Catch::Contains("true or false"));
  CHECK_THROWS_AS(Params(specs, values("{ rate: .nan }"), "n"), ConfigError);
}

TEST_CASE("a single value is a list of one", "[params]") {
  const Params p(specs, values("{ channels: 7 }"), "n");
  CHECK(p.get_int_list("channels") == std::vector<long>{7});
}
