#pragma once
// The one parallel loop of the project: indices handed out in order to a fixed number of
// workers, each knowing its number (to use its own hemicube or scratch buffers). Which worker
// takes which index varies from run to run, so a body's result must not depend on it.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace rad {

/// `requested` workers, or one per hardware thread when `requested` <= 0.
inline int workerCount(int requested = 0) {
  return requested > 0 ? requested : std::max(1, int(std::thread::hardware_concurrency()));
}

/// Calls body(index, worker) for every index in [0, count) on min(workers, count) threads
/// (the caller's among them), handing out `chunk` indices at a time. The first exception a
/// body throws is rethrown here once every worker has stopped; the other workers stop taking
/// indices.
template <class Body>
void parallelFor(size_t count, int workers, Body&& body, size_t chunk = 1) {
  workers = int(std::min<size_t>(size_t(std::max(1, workers)), std::max<size_t>(count, 1)));
  chunk = std::max<size_t>(chunk, 1);
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex errorLock;
  auto work = [&](int worker) {
    try {
      for (size_t i; !failed && (i = next.fetch_add(chunk)) < count;)
        for (size_t k = i; k < std::min(count, i + chunk); ++k) body(k, worker);
    } catch (...) {
      std::lock_guard<std::mutex> lock(errorLock);
      if (!error) error = std::current_exception();
      failed = true;
    }
  };
  std::vector<std::thread> threads;
  for (int w = 1; w < workers; ++w) threads.emplace_back(work, w);
  work(0);
  for (auto& t : threads) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace rad
