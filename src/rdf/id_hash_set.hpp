// A hash set of dense uint32_t ids whose keys live elsewhere (in a term table or
// a quad vector). The caller hashes and compares against its own storage, so the
// set holds no pointers back to its owner and stays valid when the owner moves.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

namespace mospec::rdf::detail {

class IdHashSet {
 public:
  static constexpr uint32_t kNone = UINT32_MAX;

  // The id whose key equals the probe (eq(id) is true), or kNone.
  template <class Eq>
  uint32_t find(uint64_t hash, Eq&& eq) const {
    if (slots_.empty()) return kNone;
    const uint32_t h = fold(hash);
    const size_t mask = slots_.size() - 1;
    for (size_t i = h & mask;; i = (i + 1) & mask) {
      const Slot& s = slots_[i];
      if (s.id == kNone) return kNone;
      if (s.hash == h && eq(s.id)) return s.id;
    }
  }

  // Adds an id the caller has checked is absent.
  void insert(uint64_t hash, uint32_t id) {
    // Linear probing stays short below a 70% load factor.
    if ((count_ + 1) * 10 > slots_.size() * 7) grow();
    place(Slot{id, fold(hash)});
    ++count_;
  }

  // Room for `n` ids without growing.
  void reserve(size_t n) {
    while (n * 10 > slots_.size() * 7) grow();
  }

  size_t size() const { return count_; }
  void clear() {
    slots_.clear();
    count_ = 0;
  }
  size_t memory_bytes() const { return slots_.capacity() * sizeof(Slot); }

 private:
  struct Slot {
    uint32_t id = kNone;
    uint32_t hash = 0;  // kept so that growing never re-reads the keys
  };

  static uint32_t fold(uint64_t h) { return static_cast<uint32_t>(h ^ (h >> 32)); }

  void place(Slot slot) {
    const size_t mask = slots_.size() - 1;
    size_t i = slot.hash & mask;
    while (slots_[i].id != kNone) i = (i + 1) & mask;
    slots_[i] = slot;
  }

  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(old.empty() ? 16 : old.size() * 2, Slot{});
    for (const Slot& s : old)
      if (s.id != kNone) place(s);
  }

  std::vector<Slot> slots_;
  size_t count_ = 0;
};

// 64-bit mixing (splitmix64 finaliser) for combining hashes of small integers.
inline uint64_t mix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

inline uint64_t combine(uint64_t seed, uint64_t value) {
  return mix64(seed ^ mix64(value));
}

// A hash of text for in-memory tables (term tables, JSON-LD term maps): eight
// bytes per step, inlined, about a third of the cost of std::hash on the
// short strings (terms, IRIs) these tables hold. Not randomised, like std::hash.
inline uint64_t hash_text(std::string_view s) {
  const auto* p = reinterpret_cast<const unsigned char*>(s.data());
  size_t n = s.size();
  uint64_t h = 0x9e3779b97f4a7c15ULL ^ (n * 0xff51afd7ed558ccdULL);
  while (n >= 8) {
    uint64_t w;
    std::memcpy(&w, p, 8);
    h = (h ^ w) * 0xbf58476d1ce4e5b9ULL;
    h ^= h >> 31;
    p += 8;
    n -= 8;
  }
  // The last 1-7 bytes in at most two loads rather than a loop per byte: the
  // word ending at the text's end when the text is that long (it overlaps
  // bytes already mixed in, which is fine for a hash), else two overlapping
  // halves.
  uint64_t tail = 0;
  if (n > 0) {
    if (s.size() >= 8) {
      std::memcpy(&tail, s.data() + s.size() - 8, 8);
    } else if (n >= 4) {
      uint32_t lo, hi;
      std::memcpy(&lo, p, 4);
      std::memcpy(&hi, p + n - 4, 4);
      tail = lo | (static_cast<uint64_t>(hi) << 32);
    } else {
      tail =
          p[0] | (static_cast<uint64_t>(p[n / 2]) << 8) | (static_cast<uint64_t>(p[n - 1]) << 16);
    }
  }
  h = (h ^ tail) * 0x94d049bb133111ebULL;
  return h ^ (h >> 29);
}

}  // namespace mospec::rdf::detail
