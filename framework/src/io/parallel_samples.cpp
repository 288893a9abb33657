#include <drape/io/parallel_samples.hpp>

#include <atomic>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>

namespace drape {

void make_samples_in_parallel(DatasetWriter& writer, ProgressBar& bar, const std::vector<std::size_t>& todo,
                              int threads, const std::function<SampleWorker()>& make_worker) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex failure_mutex;
  std::exception_ptr failure;
  auto run = [&] {
    try {
      const SampleWorker work = make_worker();
      for (std::size_t k = next++; k < todo.size() && !stop; k = next++) work(todo[k]);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      stop = true;
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < std::max(threads, 1); ++t) pool.emplace_back(run);
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
