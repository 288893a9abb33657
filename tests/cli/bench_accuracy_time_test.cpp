// `drape bench accuracy-time`: on a tiny dataset and a briefly trained full
// model, every method gets a row with finite numbers, the table, CSV and chart
// agree, and the Pareto flags follow from the numbers.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

struct Row {
  std::string name;
  double seconds, me, potential, p;
  bool pareto;
};

std::vector<Row> read_csv(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    const auto close = line.find("\",");
    Row r;
    r.name = line.substr(1, close - 1);
    std::stringstream rest(line.substr(close + 2));
    char comma;
    int pareto = 0;
    rest >> r.seconds >> comma >> r.me >> comma >> r.potential >> comma >> r.p >> comma >> pareto;
    r.pareto = pareto == 1;
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

TEST_CASE("bench accuracy-time measures every method against a converged drape", "[bench][accuracy-time]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const std::string drape = test::drape_program().string();
  std::string out;
  REQUIRE(test::run(drape + " generate " + (dir / "tiny.yaml").string() + " --count 10 --bmi 15:40 --seed 3 --out " +
                        (dir / "d.h5").string(),
                    out) == 0);
  REQUIRE(test::run(drape + " train " + (test::source_dir() / "graphs/drape.yaml").string() + " --data " +
                        (dir / "d.h5").string() + " --out " + (dir / "m.h5").string() + " --epochs 1 --k 32 -q",
                    out) == 0);
  REQUIRE(test::run(drape + " bench accuracy-time --data " + (dir / "d.h5").string() + " --model " + (dir / "m.h5").string() +
                        " --bodies 1 --budgets 1:1,2:3 --iterations 2 --spectral-k 4,1000 --reference-settle 10 --csv " +
                        (dir / "t.csv").string() + " --svg " + (dir / "t.svg").string(),
                    out) == 0);
  INFO(out);
  const auto rows = read_csv(dir / "t.csv");
  std::vector<std::string> names;
  for (const auto& r : rows) names.push_back(r.name);
  // Two budgets, the network, its spectral branch at k = 4 (1000 is more than it has: no row), one optimisation.
  CHECK(names == std::vector<std::string>{"simulation 1+1 steps", "simulation 2+3 steps", "network",
                                          "network, spectral branch k = 4", "network + 2 optimisation iterations"});
  for (const auto& r : rows) {
    INFO(r.name);
    CHECK(r.seconds > 0);
    CHECK(std::isfinite(r.me));
    CHECK(r.me >= 0);
    CHECK(std::isfinite(r.potential));
    CHECK((r.p >= 0 && r.p <= 100));
    CHECK_THAT(out, Catch::Contains("| " + r.name + " |"));
    // Pareto: no other row is at least as fast and at least as accurate, and strictly better in one.
    bool dominated = false;
    for (const auto& o : rows)
      if (&o != &r && o.seconds <= r.seconds && o.me <= r.me && (o.seconds < r.seconds || o.me < r.me)) dominated = true;
    CHECK(r.pareto == !dominated);
  }
  const auto fastest = std::min_element(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.seconds < b.seconds; });
  CHECK(fastest->pareto);
  std::ifstream svg(dir / "t.svg");
  std::stringstream chart;
  chart << svg.rdbuf();
  CHECK_THAT(chart.str(), Catch::Contains("network + 2 optimisation iterations"));
  CHECK_THAT(chart.str(), Catch::Contains("Pareto"));
}
