#pragma once
/// A long parallel loop in parts, with its progress: the solvers' linking, opening and
/// refinement run over tens of thousands of patches for minutes, and a user is to see them
/// move.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <functional>

namespace rad {

/// Runs body(i) for every i in [0, count), in parallel, in parts of about a hundredth (at least
/// `smallest` indices, so that cheap bodies are not cut too fine), and calls
/// done(from + (to - from) x the fraction done) before each part. Each index is independent of
/// the others, so the parts compute what one loop would, for any thread count.
template <class Body>
void for_in_parts(size_t count, double from, double to, const std::function<void(double)>& done,
                  const Body& body, size_t smallest = 256) {
  const size_t part = std::max<size_t>(smallest, count / 100);
  for (size_t begin = 0; begin < count; begin += part) {
    if (done) done(from + (to - from) * static_cast<double>(begin) / static_cast<double>(count));
    tbb::parallel_for(begin, std::min(count, begin + part), body);
  }
}

}  // namespace rad
