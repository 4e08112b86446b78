// Counter-based random numbers: every draw is a pure hash of (seed, stream, index), so parallel
// code gets the same numbers on any thread count and in any execution order (no shared RNG state).
// The mixer is SplitMix64's finalizer (Steele, Lea & Flood 2014), applied once per input word.
#pragma once

#include <cstdint>

namespace mcon {

inline std::uint64_t splitmix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// 64 random bits for draw `index` of stream `stream` under `seed`.
inline std::uint64_t counter_hash(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return splitmix64(splitmix64(splitmix64(seed) ^ stream) ^ index);
}

// Uniform in [0, 1) with 53 random bits.
inline double counter_uniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return static_cast<double>(counter_hash(seed, stream, index) >> 11) * 0x1.0p-53;
}

}  // namespace mcon
