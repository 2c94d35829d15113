// Private to libcore/voronoi: running independent pieces of work on a few threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <functional>
#include <thread>
#include <vector>

namespace bw::voronoi::detail {

// `requested` threads, or one per hardware thread when it is 0 or less.
inline int thread_count(int requested) {
  return requested > 0 ? requested : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// Runs body(i) for every i in [0, n) on up to `threads` threads (the calling thread
// is one of them), handing out indices in increasing order. `body` must not throw.
inline void parallel_for(std::size_t n, int threads, const std::function<void(std::size_t)>& body) {
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t i = next++; i < n; i = next++) body(i);
  };
  const std::size_t helpers = n == 0 ? 0 : std::min<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), n) - 1;
  std::vector<std::thread> pool;
  pool.reserve(helpers);
  for (std::size_t t = 0; t < helpers; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
}

}  // namespace bw::voronoi::detail
