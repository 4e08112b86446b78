// Counter-based random numbers: every draw is a pure hash of (seed, stream, index), so parallel
// code gets the same numbers on any thread count and in any execution order (no shared RNG state).
// The mixer is SplitMix64's finalizer (Steele, Lea & Flood 2014), applied once per input word.
#pragma once

#include <cmath>
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

// Consecutive draws of one stream (seed, stream) as an object: draw k is counter_hash(seed,
// stream, k), so a sampler can give every sample its own stream (e.g. the sample index).
class CounterRng {
 public:
  CounterRng(std::uint64_t seed, std::uint64_t stream) : seed_(seed), stream_(stream) {}

  std::uint64_t next_u64() { return counter_hash(seed_, stream_, index_++); }

  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }

  // Standard normal (Box-Muller; the second value of the pair is dropped).
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

  // Standard normal conditioned on [-bound, bound] (rejection; bound > 0).
  double truncated_normal(double bound) {
    for (int k = 0; k < 64; ++k) {
      const double z = normal();
      if (std::abs(z) <= bound) return z;
    }
    return 0.0;  // probability < 1e-40 for bound >= 1
  }

 private:
  std::uint64_t seed_, stream_, index_ = 0;
};

}  // namespace mcon
