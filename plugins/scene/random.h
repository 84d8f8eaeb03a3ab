// A small deterministic random generator for procedural scenes. std:: distributions are not
// used because their output may differ between standard library versions; this generator and
// the conversions below give the same numbers on every machine for the same seed.
#pragma once

#include <cstdint>

namespace scene {

// SplitMix64 (Steele, Lea & Flood 2014): one 64-bit state, full period, good enough mixing for
// placing rocks and bending seaweed.
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull) {}

  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1), from the top 53 bits (exact in a double).
  double unit() { return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); }
  double range(double lo, double hi) { return lo + (hi - lo) * unit(); }
  // Uniform integer in [lo, hi].
  int integer(int lo, int hi) {
    return lo + static_cast<int>(next() % static_cast<uint64_t>(hi - lo + 1));
  }
  // An independent stream for a sub-object, so adding an object does not reshuffle the others.
  Random fork(uint64_t salt) { return Random(next() ^ (salt * 0xD1B54A32D192ED03ull)); }

 private:
  uint64_t state_;
};

}  // namespace scene
