// evaluate_drapes (drape eval --drapes): garments stored in a dataset of their
// own (drape optimize --data output) measured against the simulated drapes
// their source_index names; values worked out by hand for translated copies.
#include <catch2/catch.hpp>

#include <drape/training/evaluation.hpp>

#include "train_test_util.hpp"

using namespace drape;
namespace fs = std::filesystem;

TEST_CASE("stored drapes are measured against the simulations their source_index names", "[train][metrics]") {
  test::TempDir dir;
  test::write_tiny_dataset(dir / "truth.h5", 8, 4, 2);
  const DatasetReader truth(dir / "truth.h5");
  // Out of order, one sample twice: the source decides, not the position.
  const std::vector<std::size_t> sources = {5, 1, 5, 6};
  const std::vector<double> shift = {0.01, 0.0, 0.03, 0.002};
  test::write_shifted_drapes(dir / "drapes.h5", truth, sources, shift);
  const DatasetReader drapes(dir / "drapes.h5");
  const std::vector<std::size_t> rows = {0, 1, 2, 3};
  CHECK(drape_sources(truth, drapes, rows) == sources);
  const SplitEvaluation e = evaluate_drapes(*test::tiny_assets(), truth, drapes, rows);
  REQUIRE(e.samples.size() == 4);
  for (std::size_t i = 0; i < 4; ++i) {
    // Every vertex moved by the same shift: ME is the shift in cm (float storage).
    CHECK(e.samples[i].me_cm == Approx(100.0 * shift[i]).margin(1e-4));
    CHECK(e.samples[i].edge_percent == Approx(0.0).margin(1e-3));
  }

  // A drape on another body than its source's, and a source outside the dataset.
  test::write_shifted_drapes(dir / "other_body.h5", truth, sources, shift, 2);
  CHECK_THROWS_WITH(evaluate_drapes(*test::tiny_assets(), truth, DatasetReader(dir / "other_body.h5"), rows),
                    Catch::Contains("other_body.h5: drape sample 2") && Catch::Contains("not the body of sample 5 of") &&
                        Catch::Contains("truth.h5"));
  test::write_tiny_dataset(dir / "small.h5", 4, 2, 1);
  CHECK_THROWS_WITH(evaluate_drapes(*test::tiny_assets(), DatasetReader(dir / "small.h5"), drapes, rows),
                    Catch::Contains("drapes.h5: drape sample 0: source_index 5 is not a sample of") &&
                        Catch::Contains("small.h5 (4 samples)"));
  // A dataset without source_index is no optimiser output.
  CHECK_THROWS_WITH(evaluate_drapes(*test::tiny_assets(), truth, truth, rows), Catch::Contains("no statistic source_index"));
}
