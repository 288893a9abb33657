// SizeTable (drape/scene/size_table.hpp): the tailor's rule on numbers, the
// grade of a size, and the one-line text a dataset and a model keep.
#include <catch2/catch.hpp>

#include <drape/errors.hpp>
#include <drape/scene/size_table.hpp>

using namespace drape;

namespace {

// Three sizes around a 1.00 m design girth with 10 % design ease.
SizeTable three_sizes() {
  SizeTable t;
  t.girth = {{"small", 0.9}, {"regular", 1.0}, {"large", 1.2}};
  t.design = "regular";
  t.design_ease = 0.1;
  return t;
}

}  // namespace

TEST_CASE("size table: the size nearest the design ease among those not smaller than the body", "[sizes]") {
  const SizeTable t = three_sizes();
  // Body 0.85 m: eases small 5.9 %, regular 17.6 %, large 41.2 % -> small (|5.9 - 10| < |17.6 - 10|).
  CHECK(t.choose(0.85).size == "small");
  // Body 0.95 m: small -5.3 % (too small), regular 5.3 %, large 26.3 % -> regular.
  CHECK(t.choose(0.95).size == "regular");
  // Body 1.05 m: regular -4.8 %, large 14.3 % -> large, though regular's |ease - 10 %| is the same order.
  CHECK(t.choose(1.05).size == "large");
  // Body 1.25 m: every size is smaller than the body -> none, and the summary says so.
  const SizeChoice none = t.choose(1.25);
  CHECK(none.size.empty());
  CHECK_THAT(none.summary(), Catch::Contains("does not fit"));
  CHECK(t.choose(1.05).ease("large") == Approx(1.2 / 1.05 - 1));
}

TEST_CASE("size table: a size's grade is its girth over the design size's", "[sizes]") {
  const SizeTable t = three_sizes();
  CHECK(t.grade("regular") == 1.0);
  CHECK(t.grade("large") == Approx(1.2));
  CHECK(t.grade("small") == Approx(0.9));
  CHECK_THROWS_WITH(t.grade("huge"), Catch::Contains("small, regular, large"));
  CHECK_THROWS_WITH(t.grade("LARGE"), Catch::Contains("did you mean 'large'"));  // (sizes are lower case)
}

TEST_CASE("size table: its text reads back exactly, and other text is refused by name", "[sizes]") {
  SizeTable t = three_sizes();
  t.girth[1].second = 1.0 / 3.0;  // a girth that needs 17 digits
  const SizeTable back = SizeTable::parse(t.to_text(), "x");
  CHECK(back.design == t.design);
  CHECK(back.design_ease == t.design_ease);
  REQUIRE(back.girth.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) {
    CHECK(back.girth[i].first == t.girth[i].first);
    CHECK(back.girth[i].second == t.girth[i].second);
  }
  CHECK(SizeTable::parse("design=m; design_ease=0.1; s=0.9, m=1.0", "x").grade("s") == Approx(0.9));
  CHECK_THROWS_WITH(SizeTable::parse("", "model.h5's size_chart"), Catch::Contains("model.h5's size_chart"));
  CHECK_THROWS_WITH(SizeTable::parse("design=m; design_ease=0.1; s=0.9", "x"), Catch::Contains("'m'"));
  CHECK_THROWS_WITH(SizeTable::parse("design=m; design_ease=abc; m=1", "x"), Catch::Contains("'abc' is not a number"));
  CHECK_THROWS_WITH(SizeTable::parse("design=m; design_ease=0.1; m=-1", "x"), Catch::Contains("positive"));
  CHECK_THROWS_WITH(SizeTable::parse("design=m; design_ease=0.1; m", "x"), Catch::Contains("NAME=GIRTH"));
  CHECK_THROWS_AS(SizeTable::parse("design=m; design_ease=nan; m=1", "x"), ConfigError);
}

TEST_CASE("size table: one garment's charts made before and after a size was added join into one", "[sizes]") {
  const SizeTable before = three_sizes();
  SizeTable after = three_sizes();
  after.girth.insert(after.girth.begin(), {"xsmall", 0.8});  // a size below the old smallest
  const SizeTable joined = SizeTable::join(before, after);
  REQUIRE(joined.girth.size() == 4);
  CHECK(joined.names() == "xsmall, small, regular, large");  // smallest first, whichever chart had it
  CHECK(SizeTable::join(after, before).names() == "xsmall, small, regular, large");
  CHECK(joined.grade("xsmall") == Approx(0.8));
  CHECK(joined.design == "regular");
  // A body of 0.75 m: the old chart gives small (+20 %), the joined one xsmall (+6.7 %, nearer the design's 10 %).
  CHECK(before.choose(0.75).size == "small");
  CHECK(joined.choose(0.75).size == "xsmall");

  SizeTable other = after;
  REQUIRE(other.girth[1].first == "small");
  other.girth[1].second = 0.91;  // small measured otherwise: another garment
  CHECK_THROWS_WITH(SizeTable::join(before, other), Catch::Contains("size small") && Catch::Contains("0.910000"));
  other = after;
  other.design_ease = 0.2;
  CHECK_THROWS_WITH(SizeTable::join(before, other), Catch::Contains("design size"));
}
