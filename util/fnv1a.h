// FNV-1a 64, incrementally: a fast, non-cryptographic fingerprint of bytes (file integrity checks,
// exact comparison of pixel sets across runs). Not a defence against deliberate tampering.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace ra::util {

struct Fnv1a64 {
  static constexpr uint64_t kOffsetBasis = 0xcbf29ce484222325ull;
  static constexpr uint64_t kPrime = 0x100000001b3ull;
  uint64_t value = kOffsetBasis;

  void add(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) value = (value ^ p[i]) * kPrime;
  }
  void add(std::string_view s) { add(s.data(), s.size()); }
};

// A 64-bit hash as the project writes it in files and folder names: 16 lower-case hex digits,
// zero-padded ("00c0ffee00c0ffee").
inline std::string hex64(uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace ra::util
