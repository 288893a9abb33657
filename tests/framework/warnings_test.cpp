// drape::warn (warnings.hpp): one channel, stderr by default, a handler in
// its place (what the Python module installs), callable from many threads;
// and UsageError inside the Error tree.
#include <drape/errors.hpp>
#include <drape/warnings.hpp>

#include <catch2/catch.hpp>

#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

using namespace drape;

TEST_CASE("warnings go to stderr by default and to a handler when one is set", "[errors][warnings]") {
  {
    std::ostringstream captured;
    std::streambuf* const old = std::cerr.rdbuf(captured.rdbuf());
    warn("bending: skipped 3 of 12 hinges");
    std::cerr.rdbuf(old);
    CHECK(captured.str() == "drape: warning: bending: skipped 3 of 12 hinges\n");
  }
  std::mutex m;
  std::vector<std::string> seen;
  const WarningHandler previous = set_warning_handler([&](const std::string& text) {
    const std::lock_guard<std::mutex> lock(m);
    seen.push_back(text);
  });
  CHECK_FALSE(previous);  // the default was in place
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([t] {
      for (int k = 0; k < 25; ++k) warn("thread " + std::to_string(t));
    });
  for (auto& t : threads) t.join();
  CHECK(seen.size() == 100);
  // A handler may warn through the channel itself without a deadlock (it is called outside the lock).
  set_warning_handler([&](const std::string& text) {
    if (text == "outer") warn("inner");
    const std::lock_guard<std::mutex> lock(m);
    seen.push_back(text);
  });
  warn("outer");
  CHECK(seen.back() == "outer");
  CHECK(seen[seen.size() - 2] == "inner");
  CHECK(set_warning_handler(nullptr));  // back to stderr
}

TEST_CASE("a usage error is a configuration error: exit 2, Python's ValueError", "[errors]") {
  try {
    throw UsageError("--count N is required");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()) == "--count N is required");
  }
  CHECK_THROWS_AS(throw UsageError("x"), Error);
}
