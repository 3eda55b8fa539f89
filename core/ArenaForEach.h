#pragma once
// body(i) for every i in [0, count): on the threads of `arena` (oneTBB), or in order on the calling
// thread when there is none (nullptr) or a single index. The caller links TBB.
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cstddef>

namespace cdb {

template <class Body>
void forEachIndex(tbb::task_arena* arena, std::size_t count, const Body& body) {
  if (!arena || count < 2) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  arena->execute([&] { tbb::parallel_for(std::size_t{0}, count, body); });
}

}  // namespace cdb
