#pragma once
/// Counter-based random streams for the solver's visibility jitter: every (shot, element, kind,
/// index) tuple hashes to its own SplitMix64 stream, so a result does not depend on which
/// thread computed it, nor on the order of the work.
#include <cstdint>

namespace rad {

/// SplitMix64's finaliser (Steele, Lea, Flood 2014): a bijection of 64-bit words that mixes
/// every input bit into every output bit.
inline uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// A uniform double in [0, 1) from the stream, advancing it.
inline double next_uniform(uint64_t& state) {
  state = splitmix64(state);
  return static_cast<double>(state >> 11) * 0x1.0p-53;
}

/// What a stream samples visibility for.
enum class StreamKind : uint32_t {
  centre = 0,    ///< an element's centre receiving a shot
  corner = 1,    ///< corner `index` of an element, for the refinement test
  regather = 2,  ///< a new element re-gathering from patch `index`
  back = 3,      ///< the back of a filter's element receiving a shot (or re-gathering)
  near = 4,      ///< an element receiving from piece `index` of a patch it is near
  link = 5,      ///< the hierarchical solver's link from a receiver to source `index`
};

/// The key of the stream of one tuple: the fields hashed one after another (each one mixed
/// into all bits before the next is added), so distinct tuples get unrelated streams whatever
/// the size of each field.
inline uint64_t stream_key(int shot, int element, StreamKind kind, int index) {
  uint64_t h = splitmix64(static_cast<uint32_t>(shot));
  h = splitmix64(h ^ static_cast<uint32_t>(element));
  h = splitmix64(h ^ static_cast<uint32_t>(kind));
  return splitmix64(h ^ static_cast<uint32_t>(index));
}

}  // namespace rad
