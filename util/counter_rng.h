// Counter-based random numbers: every value is a pure function of (seed, stream, index, draw), so
// primitive i of kind k under seed s is the same bytes whatever the shard count, shard order,
// thread count or machine. The mixing function is SplitMix64 (Steele, Lea & Flood, "Fast splittable
// pseudorandom number generators", OOPSLA 2014): 64-bit integer arithmetic only, hence portable.
#pragma once

#include <cstdint>

namespace ra::util {

// SplitMix64 finaliser: a bijection on 64-bit integers with good avalanche.
constexpr uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Stream tags keep the draws of different purposes independent.
enum class RngStream : uint64_t { kPoint = 1, kLine = 2, kTriangle = 3, kOrientation = 4 };

// The draws of one item (one primitive, one orientation): a counter over a fixed key.
class CounterRng {
 public:
  CounterRng(uint64_t seed, RngStream stream, uint64_t index)
      : CounterRng(seed, static_cast<uint64_t>(stream), index) {}
  // Any 64-bit stream tag (other parts of the project keep their own enums of tags).
  CounterRng(uint64_t seed, uint64_t stream, uint64_t index)
      : key_(splitmix64(splitmix64(splitmix64(seed) ^ stream) ^ index)) {}

  uint64_t next_u64() { return splitmix64(key_ + 0x632BE59BD9B4E019ull * ++counter_); }
  // Uniform on [0, 1) with 53 random bits.
  double uniform01() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }
  // Uniform on [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  // Uniform integer on [lo, hi] (inclusive; hi >= lo). The modulo bias is below 2^-32 for ranges
  // of fewer than 2^32 values.
  int64_t integer(int64_t lo, int64_t hi) {
    const uint64_t span = static_cast<uint64_t>(hi - lo) + 1;
    return lo + static_cast<int64_t>(next_u64() % span);
  }

 private:
  uint64_t key_;
  uint64_t counter_ = 0;
};

}  // namespace ra::util
