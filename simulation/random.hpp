#pragma once

/// @file
/// A small, portable random number generator for reproducible experiments: SplitMix64
/// (Steele, Lea, Flood 2014) with uniform and Gaussian draws. The same seed gives the same
/// numbers on every platform and standard library (unlike std::normal_distribution).

#include <cmath>
#include <cstdint>

namespace graspsynth {

/// SplitMix64: 64-bit state, one multiply-xorshift output per draw.
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}

  /// The stream of trial `index` of an experiment with seed `seed`: independent of how trials
  /// are spread over threads.
  static SplitMix64 ForStream(uint64_t seed, uint64_t index) {
    SplitMix64 mix(seed);
    const uint64_t a = mix.Next();
    SplitMix64 stream(a ^ (0x9E3779B97F4A7C15ull * (index + 1)));
    stream.Next();
    return stream;
  }

  uint64_t Next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  /// Uniform in [0, 1) with 53 random bits.
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  /// Standard normal (Box-Muller; one draw per call, two uniforms consumed).
  double Normal() {
    const double u1 = 1.0 - Uniform();  // in (0, 1]
    const double u2 = Uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

 private:
  uint64_t state_;
};

}  // namespace graspsynth
