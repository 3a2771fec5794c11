// KTX 2.0 pieces the reader and the writer share (internal): the identifier, the PVRTC1
// vkFormats, the Data Format Descriptor (Khronos Data Format Specification 1.3, basic block)
// and Zstandard (de)compression of one level.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/pvrtc.h"

namespace tessera::texture_file::ktx2 {

inline constexpr std::array<std::uint8_t, 12> kIdentifier = {0xAB, 'K',  'T',  'X',  ' ',  '2',
                                                             '0',  0xBB, '\r', '\n', 0x1A, '\n'};
/// Identifier, nine u32 fields (vkFormat .. supercompressionScheme), the index (dfd and kvd
/// offset/length as u32, sgd offset/length as u64).
inline constexpr std::size_t kHeaderSize = 80;
/// One level index entry: byteOffset, byteLength, uncompressedByteLength (u64 each).
inline constexpr std::size_t kLevelEntrySize = 24;
/// PVRTC1 blocks are 8 bytes: levels are aligned to lcm(8, 4) when not supercompressed.
inline constexpr std::size_t kLevelAlignment = 8;

inline constexpr std::uint32_t kSchemeNone = 0;
inline constexpr std::uint32_t kSchemeBasisLz = 1;
inline constexpr std::uint32_t kSchemeZstd = 2;
inline constexpr std::uint32_t kSchemeZlib = 3;

/// A vkFormat tessera reads and writes.
struct VkPvrtcFormat {
  std::uint32_t vk_format;
  pvrtc::Format format;
  bool srgb;
  const char* name;
};
inline constexpr VkPvrtcFormat kVkFormats[] = {
    {1000054000u, pvrtc::Format::pvrtc1_2bpp, false, "VK_FORMAT_PVRTC1_2BPP_UNORM_BLOCK_IMG"},
    {1000054001u, pvrtc::Format::pvrtc1_4bpp, false, "VK_FORMAT_PVRTC1_4BPP_UNORM_BLOCK_IMG"},
    {1000054004u, pvrtc::Format::pvrtc1_2bpp, true, "VK_FORMAT_PVRTC1_2BPP_SRGB_BLOCK_IMG"},
    {1000054005u, pvrtc::Format::pvrtc1_4bpp, true, "VK_FORMAT_PVRTC1_4BPP_SRGB_BLOCK_IMG"},
};

/// The entry of `kVkFormats` for `vk_format`, or nullptr.
const VkPvrtcFormat* find_vk_format(std::uint32_t vk_format);
/// The entry for a PVRTC format and colour space (always found).
const VkPvrtcFormat& vk_format_for(pvrtc::Format format, bool srgb);
/// "VK_FORMAT_R8G8B8A8_UNORM" for common formats (uncompressed 8/16/32-bit, BC, ETC2, EAC,
/// ASTC, PVRTC); "" for the rest.
std::string vk_format_name(std::uint32_t vk_format);

// Data Format Descriptor constants (khr_df.h).
inline constexpr std::uint8_t kDfModelPvrtc = 164;
inline constexpr std::uint8_t kDfPrimariesBt709 = 1;
inline constexpr std::uint8_t kDfTransferLinear = 1;
inline constexpr std::uint8_t kDfTransferSrgb = 2;
inline constexpr std::uint8_t kDfFlagAlphaPremultiplied = 1;
inline constexpr std::uint16_t kDfVersion13 = 2;  ///< KHR_DF_VERSIONNUMBER_1_3

/// The whole DFD tessera writes (dfdTotalSize first): one basic descriptor block, model PVRTC,
/// BT.709 primaries, sRGB or linear transfer, ALPHA_PREMULTIPLIED when `premultiplied`,
/// texel block 4x4 (4 bpp) or 8x4 (2 bpp), bytesPlane0 = 8, and one sample of 64 bits
/// (channel KHR_DF_CHANNEL_PVRTC_COLOR, sampleLower 0, sampleUpper 0xFFFFFFFF): 44 bytes,
/// what KTX-Software's vk2dfd gives for the same vkFormat plus the premultiplied flag.
std::vector<std::uint8_t> make_dfd(pvrtc::Format format, bool srgb, bool premultiplied);

/// What the reader takes from a DFD.
struct DfdInfo {
  bool srgb = false;
  bool premultiplied = false;
};
/// Checks the DFD `dfd` (dfdByteLength bytes from dfdByteOffset) against `vk`: a basic
/// descriptor block of a consistent size, model PVRTC, texel block and bytesPlane0 of `vk`'s
/// format, transfer function linear or sRGB as `vk` says. Errors are corrupt_data and start
/// with `name`.
Result<DfdInfo> read_dfd(std::span<const std::uint8_t> dfd, const VkPvrtcFormat& vk,
                         const std::string& name);

/// Zstandard blocks hold at most 128 KiB and each needs a 3-byte header, so a frame of n bytes
/// decompresses to at most n / 3 * 128 KiB: what `zstd_expansion_possible` checks.
inline constexpr std::uint64_t kZstdMaxBlockBytes = std::uint64_t{1} << 17;
inline bool zstd_expansion_possible(std::uint64_t compressed, std::uint64_t uncompressed) {
  return uncompressed <= compressed / 3 * kZstdMaxBlockBytes;
}

/// One Zstandard frame of `raw` at `level` (1..22), with its content size in the frame header.
/// Deterministic for one libzstd version.
Result<std::vector<std::uint8_t>> zstd_compress(std::span<const std::uint8_t> raw, int level);

/// Decompresses `frame` into exactly `out.size()` bytes. Refused (corrupt_data, message
/// `what` + ": ..."), before anything is written, when `frame` is not exactly one Zstandard
/// frame or its header does not declare exactly `out.size()` bytes; zstd itself then never
/// writes past `out`, and a frame that decodes to any other size is an error too.
Status zstd_decompress(std::span<const std::uint8_t> frame, std::span<std::uint8_t> out,
                       const std::string& what);

}  // namespace tessera::texture_file::ktx2
