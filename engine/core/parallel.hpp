#pragma once
// parallelFor over [begin, end) on TBB's pool. Work items must not depend on the order or the
// thread they run on: every bake derives its random seed from the item index, so results are
// deterministic whatever the thread count.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstddef>

namespace bounce {

template <class F>
void parallelFor(std::size_t begin, std::size_t end, F&& fn, std::size_t grain = 1) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, grain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) fn(i);
  });
}

}  // namespace bounce
