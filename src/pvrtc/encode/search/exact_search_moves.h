// exact_search_moves.h — pieces shared by the exact endpoint searches of both bit rates
// (exact_search.cpp for 4 bpp, exact_search_2bpp.cpp for 2 bpp): the moves on a block's endpoint
// codes and the table of pairs one block visit has already scored.
#pragma once

#include <cstdint>
#include <cstring>

#include "pvrtc/format/pvrtc_kernel.h"

namespace tessera::pvrtc::detail {

// Candidate moves on the codes of one endpoint pair, as steps of -1, 0 or +1 on its eight codes
// (A r g b a, B r g b a): 0-15 one channel of one endpoint (endpoint move / 8, channel
// (move / 2) % 4, sign move & 1 ? +1 : -1); 16/17 all colour channels of A -1/+1, 18/19 of B,
// 20/21 of both, 22 spread (A -1, B +1), 23 contract (A +1, B -1); 24-35 one colour channel
// ((move - 24) / 4) of A and B together (A's sign as above, B's the same where bit 1 of
// move - 24 is clear, else opposite: the pair's midpoint moves while its spread stays).
constexpr int kMoves = 36;

struct MoveTable {
  std::int8_t step[kMoves][8];
  /// The colour channel (0-2) the move changes where it changes exactly one, else -1.
  std::int8_t planar[kMoves];
  constexpr MoveTable() : step{}, planar{} {
    for (int mv = 0; mv < kMoves; ++mv) {
      planar[mv] = -1;
      if (mv < 16) {
        const int ch = (mv / 2) % 4;
        step[mv][(mv >= 8 ? 4 : 0) + ch] = std::int8_t(mv & 1 ? 1 : -1);
        if (ch < 3) planar[mv] = std::int8_t(ch);
      } else if (mv < 24) {
        const int m = mv - 16;
        // Steps of A and B: 16/17 A, 18/19 B, 20/21 both, 22 spread, 23 contract.
        constexpr int kA[8] = {-1, 1, 0, 0, -1, 1, -1, 1};
        constexpr int kB[8] = {0, 0, -1, 1, -1, 1, 1, -1};
        const int da = kA[m], db = kB[m];
        for (int ch = 0; ch < 3; ++ch) {
          step[mv][ch] = std::int8_t(da);
          step[mv][4 + ch] = std::int8_t(db);
        }
      } else {
        const int k = mv - 24, ch = k / 4, d = (k & 1) ? 1 : -1;
        step[mv][ch] = std::int8_t(d);
        step[mv][4 + ch] = std::int8_t((k & 2) ? -d : d);
        planar[mv] = std::int8_t(ch);
      }
    }
  }
};
inline constexpr MoveTable kMoveTable;

/// One endpoint pair's codes unpacked once for all its moves: the eight codes and their limits
/// (1 << bits; 0 for a channel the mode lacks, so that any step on it is invalid).
struct PairCodes {
  bool opaque[2];
  std::int32_t v[8], lim[8];
  PairCodes(std::uint16_t a, std::uint16_t b) {
    const EndpointCodes e[2] = {unpack_endpoint(false, a), unpack_endpoint(true, b)};
    for (int k = 0; k < 2; ++k) {
      opaque[k] = e[k].opaque;
      int bits[4];
      channel_bits(k == 1, e[k].opaque, bits);
      const std::uint32_t c[4] = {e[k].r, e[k].g, e[k].b, e[k].a};
      for (int ch = 0; ch < 4; ++ch) {
        v[4 * k + ch] = std::int32_t(c[ch]);
        lim[4 * k + ch] = bits[ch] == 0 ? 0 : 1 << bits[ch];
      }
    }
  }
  /// The packed pair after `move`; false when it steps a code out of its range.
  bool moved(int move, std::uint16_t& na, std::uint16_t& nb) const {
    const std::int8_t* st = kMoveTable.step[move];
    std::int32_t n[8];
    for (int i = 0; i < 8; ++i) {
      n[i] = v[i] + st[i];
      if (st[i] != 0 && std::uint32_t(n[i]) >= std::uint32_t(lim[i])) return false;
    }
    na = std::uint16_t(pack_endpoint(false, {opaque[0], std::uint32_t(n[0]), std::uint32_t(n[1]),
                                             std::uint32_t(n[2]), std::uint32_t(n[3])}));
    nb = std::uint16_t(pack_endpoint(true, {opaque[1], std::uint32_t(n[4]), std::uint32_t(n[5]),
                                            std::uint32_t(n[6]), std::uint32_t(n[7])}));
    return true;
  }
};

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
