// The experiment table's Markdown and CSV (apps/drape/experiment/experiment_table.cpp,
// compiled into this test: it is the program's, not the library's).
#include "../../apps/drape/experiment/experiment_table.cpp"

#include <catch2/catch.hpp>

#include <cmath>

TEST_CASE("an experiment table shows a value measured on no body as none and explains every column marked *", "[experiment]") {
  drape::cli::ExperimentTable t;
  t.title = "t";
  t.columns = {"ME", "L_p"};
  // An optimize row whose drapes are all "not results": its L_p is NaN (it printed "nan").
  t.rows = {{"Sim", {{"L_p", 1.82}}, "s", ""}, {"opt (1 of 1 not results)", {{"ME", 0.3}, {"L_p", std::nan("")}}, "s", ""}};
  t.seed = {{}, {}};
  const std::string md = drape::cli::table_markdown(t), csv = drape::cli::table_csv(t);
  CHECK_THAT(md, !Catch::Contains("nan") && Catch::Contains("| opt (1 of 1 not results) | 0.3 / — | — |"));
  CHECK_THAT(csv, !Catch::Contains(",nan") && Catch::Contains("opt (1 of 1 not results),0.3,,,,"));
  // L_p is marked *, and with no seed number in the rows the reason was promised "below the table" and never given.
  CHECK_THAT(md, Catch::Contains("| L_p (J) * |") && Catch::Contains("* L_p holds ours alone: the seed's L_p is another quantity: "));
}
