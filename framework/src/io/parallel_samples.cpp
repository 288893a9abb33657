#include <drape/io/parallel_samples.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>

namespace drape {

void make_samples_in_parallel(DatasetWriter& writer, ProgressBar& bar, const std::vector<std::size_t>& todo,
                              int threads, const std::function<SampleWorker()>& make_worker,
                              const std::function<void()>& poll) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex failure_mutex;
  std::exception_ptr failure;
  const auto fail = [&](std::exception_ptr e) {
    const std::lock_guard<std::mutex> lock(failure_mutex);
    if (!failure) failure = std::move(e);
    stop = true;
  };
  std::mutex done_mutex;
  std::condition_variable done_changed;
  int running = std::max(threads, 1);
  auto run = [&] {
    try {
      const SampleWorker work = make_worker();
      for (std::size_t k = next++; k < todo.size() && !stop; k = next++) work(todo[k]);
    } catch (...) {
      fail(std::current_exception());
    }
    const std::lock_guard<std::mutex> lock(done_mutex);
    --running;
    done_changed.notify_all();
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < std::max(threads, 1); ++t) pool.emplace_back(run);
  if (poll) {
    std::unique_lock<std::mutex> lock(done_mutex);
    while (!done_changed.wait_for(lock, std::chrono::duration<double>(kPollSeconds), [&] { return running == 0; })) {
      if (stop) continue;  // stopping already: wait for the workers
      lock.unlock();
      try {
        poll();
      } catch (...) {
        fail(std::current_exception());  // first: a worker it stops mid-sample fails after it
      }
      lock.lock();
    }
  }
  for (auto& t : pool) t.join();
  bar.finish();
  if (failure) {
    writer.close();
    std::fprintf(stderr, "stopped: the samples done so far are kept; run the same command again to resume\n");
    std::rethrow_exception(failure);
  }
  writer.finish();
}

}  // namespace drape
