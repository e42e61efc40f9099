// Runs independent work on every core (pure CPU references: bands, converged integrals).
#pragma once

#include <algorithm>
#include <thread>
#include <vector>

namespace pbrlab {

// Whether this build can start threads. A page without shared memory (GitHub Pages serves none
// of the headers wasm threads need) has one thread.
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
constexpr bool kThreads = false;
#else
constexpr bool kThreads = true;
#endif

// f(i) for i in [0, n), interleaved over the machine's cores (in order, without threads).
template <typename F>
void parallelFor(size_t n, F f) {
    if constexpr (!kThreads) {
        for (size_t i = 0; i < n; ++i) f(i);
        return;
    }
    const size_t workers = std::max(1u, std::min(8u, std::thread::hardware_concurrency()));
    std::vector<std::thread> threads;
    for (size_t w = 0; w < workers; ++w)
        threads.emplace_back([&, w] {
            for (size_t i = w; i < n; i += workers) f(i);
        });
    for (std::thread& t : threads) t.join();
}

}  // namespace pbrlab
