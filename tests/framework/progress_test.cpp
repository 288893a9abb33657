// ProgressBar on a plain stream (what CI logs see) with a fake clock: counts,
// ETA from this run's rate, resumed offsets, throttling and threads.
#include <drape/progress.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <sstream>
#include <thread>
#include <vector>

using namespace drape;

namespace {

struct FakeClock {
  double now = 100.0;  // any origin: only differences matter
  std::function<double()> fn() {
    return [this] { return now; };
  }
};

ProgressBar::Options plain(FakeClock& clock, std::size_t start = 0) {
  ProgressBar::Options o;
  o.clock = clock.fn();
  o.start = start;
  o.terminal = false;
  o.width = 10;
  return o;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

}  // namespace

TEST_CASE("progress: the line shows counts, percent, elapsed time and the ETA from the rate", "[progress]") {
  FakeClock clock;
  std::ostringstream out;
  ProgressBar bar("simulate", 100, out, plain(clock));
  CHECK_THAT(bar.line(), Catch::Contains("0/100 0%") && Catch::Contains("ETA --"));
  clock.now += 10;
  bar.advance(25);  // 2.5 items/s, 75 left
  bar.set_status("loss 0.012");
  CHECK(bar.line() == "simulate [##........] 25/100 25% 10.0 s elapsed, ETA 30.0 s  loss 0.012");
  clock.now += 2;
  bar.advance(12);  // 37 in 12 s, 63 left: 63 * 12 / 37 = 20.4 s
  CHECK(bar.line() == "simulate [###.......] 37/100 37% 12.0 s elapsed, ETA 20.4 s  loss 0.012");
}

TEST_CASE("progress: a resumed job counts earlier items in the bar, not in the rate", "[progress]") {
  FakeClock clock;
  std::ostringstream out;
  ProgressBar bar("generate", 100, out, plain(clock, 40));
  CHECK_THAT(bar.line(), Catch::StartsWith("generate [####......] 40/100 40%") && Catch::Contains("ETA --"));
  clock.now += 10;
  bar.advance(20);  // 2 items/s in this run (not 6/s), 40 left
  CHECK_THAT(bar.line(), Catch::Contains("60/100 60% 10.0 s elapsed, ETA 20.0 s"));
  bar.advance(40);
  bar.finish();
  const auto lines = lines_of(out.str());
  REQUIRE(!lines.empty());
  CHECK(lines.back() == "generate [##########] 100/100 100% 10.0 s elapsed");
}

TEST_CASE("progress: off a terminal, one line per 10% and a final 100% line", "[progress]") {
  FakeClock clock;
  std::ostringstream out;
  {
    ProgressBar bar("train", 100, out, plain(clock));
    for (int i = 0; i < 100; ++i) {
      clock.now += 0.5;
      bar.advance();
    }
    bar.finish();
    bar.finish();  // idempotent
  }  // the destructor adds nothing after finish()
  const auto lines = lines_of(out.str());
  REQUIRE(lines.size() == 10);  // 10%, 20%, ..., 90%, then the final line
  CHECK(out.str().find('\r') == std::string::npos);
  CHECK_THAT(lines[0], Catch::StartsWith("train [#.........] 10/100 10% 5.0 s elapsed, ETA 45.0 s"));
  CHECK_THAT(lines[8], Catch::StartsWith("train [#########.] 90/100 90%"));
  CHECK(lines.back() == "train [##########] 100/100 100% 50.0 s elapsed");
}

TEST_CASE("progress: off a terminal, a slow step still logs every 30 s", "[progress]") {
  FakeClock clock;
  std::ostringstream out;
  ProgressBar bar("slow", 1000, out, plain(clock));
  for (int i = 0; i < 9; ++i) {  // 9 items, 0.9%: no 10% step crossed
    clock.now += 10;
    bar.advance();
  }
  // Lines at 30, 60 and 90 s; at 30 s, 997 items left at 10 s each = 9970 s.
  const auto lines = lines_of(out.str());
  REQUIRE(lines.size() == 3);
  CHECK_THAT(lines[0], Catch::Contains("3/1000 0% 30.0 s elapsed, ETA 2 h 46 min"));
  CHECK_THAT(lines[2], Catch::Contains("9/1000 0% 1 min 30 s elapsed"));
}

TEST_CASE("progress: on a terminal the line is redrawn in place at most ~10 times a second", "[progress]") {
  FakeClock clock;
  std::ostringstream out;
  auto options = plain(clock);
  options.terminal = true;
  ProgressBar bar("bench", 1000, out, options);
  for (int i = 0; i < 1000; ++i) {
    clock.now += 0.001;  // 1 s in all
    bar.advance();
    if (i == 500) bar.set_status("a long status that the next lines are shorter than");
    if (i == 700) bar.set_status("short");
  }
  bar.finish();
  const std::string text = out.str();
  const auto draws = std::count(text.begin(), text.end(), '\r');
  CHECK(draws >= 10);
  CHECK(draws <= 12);  // the start, ~10 in the second, the final line
  CHECK(std::count(text.begin(), text.end(), '\n') == 1);
  CHECK(text.back() == '\n');
  const std::string last = text.substr(text.rfind('\r') + 1);
  CHECK_THAT(last, Catch::StartsWith("bench [##########] 1000/1000 100% 1.0 s elapsed  short"));
}

TEST_CASE("progress: advance is thread-safe and clamps at the total", "[progress]") {
  FakeClock clock;  // read under the bar's lock only
  std::ostringstream out;
  ProgressBar bar("threads", 4000, out, plain(clock));
  std::vector<std::thread> workers;
  for (int t = 0; t < 4; ++t)
    workers.emplace_back([&] {
      for (int i = 0; i < 1000; ++i) bar.advance();
    });
  for (auto& w : workers) w.join();
  CHECK(bar.done() == 4000);
  bar.advance(5);
  CHECK(bar.done() == 4000);
  bar.finish();
  CHECK_THAT(lines_of(out.str()).back(), Catch::StartsWith("threads [##########] 4000/4000 100%"));
}

TEST_CASE("progress: durations and an empty job", "[progress]") {
  CHECK(ProgressBar::format_duration(12.34) == "12.3 s");
  CHECK(ProgressBar::format_duration(245) == "4 min 05 s");
  CHECK(ProgressBar::format_duration(7380) == "2 h 03 min");
  FakeClock clock;
  std::ostringstream out;
  ProgressBar bar("nothing", 0, out, plain(clock));
  bar.finish();
  CHECK(out.str() == "nothing [##########] 0/0 100% 0.0 s elapsed\n");
}

// An item that takes minutes (a morph step the contact cuts into partial
// moves) shows what it is doing in a log too: a status set 30 s after the
// last line is written, one set sooner waits.
TEST_CASE("progress: off a terminal, a status is written when 30 s have passed since the last line", "[progress]") {
  FakeClock clock;
  std::ostringstream out;
  ProgressBar bar("simulate", 4, out, plain(clock));
  clock.now += 5;
  bar.set_status("morph step 1: 3 partial moves");
  CHECK(out.str().empty());
  clock.now += 26;  // 31 s since the start
  bar.set_status("morph step 1: 40 partial moves");
  const auto lines = lines_of(out.str());
  REQUIRE(lines.size() == 1);
  CHECK_THAT(lines[0], Catch::StartsWith("simulate [..........] 0/4 0%") && Catch::EndsWith("morph step 1: 40 partial moves"));
  clock.now += 10;
  bar.set_status("morph step 1: 50 partial moves");
  CHECK(lines_of(out.str()).size() == 1);
}
