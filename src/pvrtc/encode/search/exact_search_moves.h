// exact_search_moves.h — pieces shared by the exact endpoint searches of both bit rates
// (exact_search.cpp for 4 bpp, exact_search_2bpp.cpp for 2 bpp): the moves on a block's endpoint
// codes and the table of pairs one block visit has already scored.
#pragma once

#include <cstdint>
#include <cstring>

#include "pvrtc/format/pvrtc_kernel.h"

namespace tessera::pvrtc::detail {

// Candidate moves on the codes of one endpoint pair. Returns false when the move is invalid.
inline bool apply_move(int move, EndpointCodes& a, EndpointCodes& b) {
  int ba[4], bb[4];
  channel_bits(false, a.opaque, ba);
  channel_bits(true, b.opaque, bb);
  std::uint32_t* ca[4] = {&a.r, &a.g, &a.b, &a.a};
  std::uint32_t* cb[4] = {&b.r, &b.g, &b.b, &b.a};
  auto step = [](std::uint32_t* c, int bits, int d) {
    if (bits == 0) return false;
    const int v = int(*c) + d;
    if (v < 0 || v >= (1 << bits)) return false;
    *c = std::uint32_t(v);
    return true;
  };
  if (move < 16) {  // single channel: endpoint (move / 8), channel ((move / 2) % 4), sign
    const bool on_b = move >= 8;
    const int ch = (move / 2) % 4;
    const int d = (move & 1) ? 1 : -1;
    return on_b ? step(cb[ch], bb[ch], d) : step(ca[ch], ba[ch], d);
  }
  if (move >= 24) {  // one channel of A and B together: same / opposite sign
    const int k = move - 24, ch = (k / 4) % 3, d = (k & 1) ? 1 : -1;
    const int db = (k & 2) ? -d : d;
    return step(ca[ch], ba[ch], d) && step(cb[ch], bb[ch], db);
  }
  // Joint colour moves: 16/17 A, 18/19 B, 20/21 both, 22 spread, 23 contract.
  const int m = move - 16;
  bool ok = true;
  for (int ch = 0; ch < 3 && ok; ++ch) {
    if (m < 2) {
      ok = step(ca[ch], ba[ch], m ? 1 : -1);
    } else if (m < 4) {
      ok = step(cb[ch], bb[ch], m == 3 ? 1 : -1);
    } else if (m < 6) {
      ok = step(ca[ch], ba[ch], m == 5 ? 1 : -1) && step(cb[ch], bb[ch], m == 5 ? 1 : -1);
    } else {
      ok = step(ca[ch], ba[ch], m == 6 ? -1 : 1) && step(cb[ch], bb[ch], m == 6 ? 1 : -1);
    }
  }
  return ok;
}

// Moves 0-23 as above; 24-35 step one channel of A and B together (the pair's midpoint moves
// while its spread stays).
constexpr int kMoves = 36;

// The endpoint pairs one block visit has met (candidates scored and pairs that were current):
// each one's window error is at least the current best (a rejected candidate scored at least
// the best of its time, a pair left by a kept move scored more than its successor), so meeting
// one again it need not be scored (exact). Open addressing on the packed (A, B) fields.
class SeenPairs {
 public:
  SeenPairs() { std::memset(slot_, 0xff, sizeof(slot_)); }
  /// True when `key` was inserted before; inserts it otherwise.
  bool check_insert(std::uint32_t key) {
    if (key == kEmpty) return false;  // not representable: always scored
    std::uint32_t h = (key * 0x9e3779b1u) >> (32 - kBits);
    for (;;) {
      if (slot_[h] == key) return true;
      if (slot_[h] == kEmpty) {
        if (count_ == kMaxCount) return false;  // full: score it (exact either way)
        slot_[h] = key;
        ++count_;
        return false;
      }
      h = (h + 1) & (kSize - 1);
    }
  }

 private:
  static constexpr int kBits = 9, kSize = 1 << kBits, kMaxCount = kSize / 2;
  static constexpr std::uint32_t kEmpty = ~0u;
  std::uint32_t slot_[kSize];
  int count_ = 0;
};

}  // namespace tessera::pvrtc::detail
