// KTX 2.0 shared pieces: vkFormat names, the PVRTC1 Data Format Descriptor, Zstandard levels.
#include "texture_file/ktx2_format.h"

#include <zstd.h>

#include <memory>

#include "texture_file/container_bytes.h"

namespace tessera::texture_file::ktx2 {

using container::load_u32;
using container::plural_bytes;

const VkPvrtcFormat* find_vk_format(std::uint32_t vk_format) {
  for (const VkPvrtcFormat& f : kVkFormats) {
    if (f.vk_format == vk_format) return &f;
  }
  return nullptr;
}

const VkPvrtcFormat& vk_format_for(pvrtc::Format format, bool srgb) {
  for (const VkPvrtcFormat& f : kVkFormats) {
    if (f.format == format && f.srgb == srgb) return f;
  }
  return kVkFormats[0];  // unreachable: the table holds every combination
}

std::string vk_format_name(std::uint32_t vk) {
  struct Named {
    std::uint32_t vk;
    const char* name;
  };
  static constexpr Named kNamed[] = {
      {0, "UNDEFINED"},
      {9, "R8_UNORM"},
      {16, "R8G8_UNORM"},
      {23, "R8G8B8_UNORM"},
      {29, "R8G8B8_SRGB"},
      {37, "R8G8B8A8_UNORM"},
      {43, "R8G8B8A8_SRGB"},
      {44, "B8G8R8A8_UNORM"},
      {50, "B8G8R8A8_SRGB"},
      {70, "R16_UNORM"},
      {76, "R16_SFLOAT"},
      {77, "R16G16_UNORM"},
      {83, "R16G16_SFLOAT"},
      {91, "R16G16B16A16_UNORM"},
      {97, "R16G16B16A16_SFLOAT"},
      {100, "R32_SFLOAT"},
      {103, "R32G32_SFLOAT"},
      {106, "R32G32B32_SFLOAT"},
      {109, "R32G32B32A32_SFLOAT"},
      {122, "B10G11R11_UFLOAT_PACK32"},
      {123, "E5B9G9R9_UFLOAT_PACK32"},
      {1000054002, "PVRTC2_2BPP_UNORM_BLOCK_IMG"},
      {1000054003, "PVRTC2_4BPP_UNORM_BLOCK_IMG"},
      {1000054006, "PVRTC2_2BPP_SRGB_BLOCK_IMG"},
      {1000054007, "PVRTC2_4BPP_SRGB_BLOCK_IMG"},
  };
  // 131..156: BC1-7, ETC2, EAC; 157..184: ASTC LDR, UNORM and SRGB of each block size.
  static constexpr const char* kBlock[] = {
      "BC1_RGB_UNORM_BLOCK",       "BC1_RGB_SRGB_BLOCK",
      "BC1_RGBA_UNORM_BLOCK",      "BC1_RGBA_SRGB_BLOCK",
      "BC2_UNORM_BLOCK",           "BC2_SRGB_BLOCK",
      "BC3_UNORM_BLOCK",           "BC3_SRGB_BLOCK",
      "BC4_UNORM_BLOCK",           "BC4_SNORM_BLOCK",
      "BC5_UNORM_BLOCK",           "BC5_SNORM_BLOCK",
      "BC6H_UFLOAT_BLOCK",         "BC6H_SFLOAT_BLOCK",
      "BC7_UNORM_BLOCK",           "BC7_SRGB_BLOCK",
      "ETC2_R8G8B8_UNORM_BLOCK",   "ETC2_R8G8B8_SRGB_BLOCK",
      "ETC2_R8G8B8A1_UNORM_BLOCK", "ETC2_R8G8B8A1_SRGB_BLOCK",
      "ETC2_R8G8B8A8_UNORM_BLOCK", "ETC2_R8G8B8A8_SRGB_BLOCK",
      "EAC_R11_UNORM_BLOCK",       "EAC_R11_SNORM_BLOCK",
      "EAC_R11G11_UNORM_BLOCK",    "EAC_R11G11_SNORM_BLOCK",
  };
  static constexpr const char* kAstc[] = {"4x4", "5x4",  "5x5",  "6x5",  "6x6",   "8x5",   "8x6",
                                          "8x8", "10x5", "10x6", "10x8", "10x10", "12x10", "12x12"};
  if (const VkPvrtcFormat* f = find_vk_format(vk)) return f->name;
  for (const Named& n : kNamed) {
    if (n.vk == vk) return std::string("VK_FORMAT_") + n.name;
  }
  if (vk >= 131 && vk < 131 + std::size(kBlock))
    return std::string("VK_FORMAT_") + kBlock[vk - 131];
  if (vk >= 157 && vk < 157 + 2 * std::size(kAstc)) {
    return std::string("VK_FORMAT_ASTC_") + kAstc[(vk - 157) / 2] +
           ((vk - 157) % 2 ? "_SRGB_BLOCK" : "_UNORM_BLOCK");
  }
  return "";
}

std::vector<std::uint8_t> make_dfd(pvrtc::Format format, bool srgb, bool premultiplied) {
  constexpr std::uint32_t kBlockSize = 24 + 16;  // basic block with one sample
  std::vector<std::uint8_t> d;
  container::store_u32(d, 4 + kBlockSize);  // dfdTotalSize
  container::store_u32(d, 0);               // vendorId 0 (Khronos), descriptorType 0 (basic)
  container::store_u32(d, kDfVersion13 | kBlockSize << 16);
  d.push_back(kDfModelPvrtc);
  d.push_back(kDfPrimariesBt709);
  d.push_back(srgb ? kDfTransferSrgb : kDfTransferLinear);
  d.push_back(premultiplied ? kDfFlagAlphaPremultiplied : 0);
  d.push_back(std::uint8_t(pvrtc::block_width(format) - 1));  // texelBlockDimension0..3
  d.push_back(3);
  d.push_back(0);
  d.push_back(0);
  d.push_back(8);  // bytesPlane0; bytesPlane1..7 are 0
  d.insert(d.end(), 7, 0);
  // The sample: bitOffset 0, bitLength 63 (64 bits), channel KHR_DF_CHANNEL_PVRTC_COLOR (0)
  // with no qualifiers, samplePosition 0, sampleLower 0, sampleUpper 0xFFFFFFFF.
  container::store_u32(d, 63u << 16);
  container::store_u32(d, 0);
  container::store_u32(d, 0);
  container::store_u32(d, 0xFFFFFFFFu);
  return d;
}

Result<DfdInfo> read_dfd(std::span<const std::uint8_t> dfd, const VkPvrtcFormat& vk,
                         const std::string& name) {
  auto corrupt = [&](const std::string& what) { return container::corrupt(name, what); };
  constexpr std::size_t kMinSize = 4 + 24;  // dfdTotalSize and a basic block without samples
  if (dfd.size() < kMinSize) {
    return corrupt("Data Format Descriptor of " + plural_bytes(dfd.size()) +
                   " is too short (a basic descriptor block needs " + std::to_string(kMinSize) +
                   ")");
  }
  const std::uint32_t total = load_u32(dfd, 0);
  if (total != dfd.size()) {
    return corrupt("dfdTotalSize " + std::to_string(total) + " differs from dfdByteLength " +
                   std::to_string(dfd.size()));
  }
  const std::uint32_t type_word = load_u32(dfd, 4);
  const std::uint32_t vendor = type_word & 0x1FFFFu;
  const std::uint32_t type = type_word >> 17;
  if (vendor != 0 || type != 0) {
    return corrupt(
        "the Data Format Descriptor's first block is not a Khronos basic block (vendorId " +
        std::to_string(vendor) + ", descriptorType " + std::to_string(type) + ")");
  }
  const std::uint32_t block_size = load_u32(dfd, 8) >> 16;
  if (block_size < 24 || (block_size - 24) % 16 != 0 || block_size > dfd.size() - 4) {
    return corrupt("Data Format Descriptor block size " + std::to_string(block_size) +
                   " is not 24 + 16 x samples within its " + plural_bytes(dfd.size() - 4));
  }
  const std::uint8_t model = dfd[12];
  const std::uint8_t transfer = dfd[14];
  const std::uint8_t flags = dfd[15];
  if (model != kDfModelPvrtc) {
    return corrupt("Data Format Descriptor colour model " + std::to_string(model) +
                   " does not match " + vk.name + " (KHR_DF_MODEL_PVRTC, " +
                   std::to_string(kDfModelPvrtc) + ")");
  }
  const int bw = pvrtc::block_width(vk.format);
  if (dfd[16] != bw - 1 || dfd[17] != 3 || dfd[18] != 0 || dfd[19] != 0) {
    return corrupt("Data Format Descriptor texel block " + std::to_string(dfd[16] + 1) + "x" +
                   std::to_string(dfd[17] + 1) + "x" + std::to_string(dfd[18] + 1) + "x" +
                   std::to_string(dfd[19] + 1) + " does not match " + vk.name + " (" +
                   std::to_string(bw) + "x4x1x1)");
  }
  if (dfd[20] != 8) {
    return corrupt("Data Format Descriptor bytesPlane0 " + std::to_string(dfd[20]) +
                   " does not match " + vk.name + " (8-byte blocks)");
  }
  if (transfer != kDfTransferLinear && transfer != kDfTransferSrgb) {
    return corrupt("Data Format Descriptor transfer function " + std::to_string(transfer) +
                   " is neither linear (1) nor sRGB (2)");
  }
  if ((transfer == kDfTransferSrgb) != vk.srgb) {
    return corrupt(std::string("Data Format Descriptor transfer function ") +
                   (transfer == kDfTransferSrgb ? "sRGB" : "linear") + " contradicts " + vk.name);
  }
  DfdInfo info;
  info.srgb = vk.srgb;
  info.premultiplied = (flags & kDfFlagAlphaPremultiplied) != 0;
  return info;
}

Result<std::vector<std::uint8_t>> zstd_compress(std::span<const std::uint8_t> raw, int level) {
  std::unique_ptr<ZSTD_CCtx, decltype(&ZSTD_freeCCtx)> cctx(ZSTD_createCCtx(), ZSTD_freeCCtx);
  if (!cctx) return Status::error(ErrorCode::io_error, "zstd: out of memory");
  std::vector<std::uint8_t> out(ZSTD_compressBound(raw.size()));
  const std::size_t n =
      ZSTD_compressCCtx(cctx.get(), out.data(), out.size(), raw.data(), raw.size(), level);
  if (ZSTD_isError(n)) {
    return Status::error(ErrorCode::invalid_argument,
                         std::string("zstd compression failed: ") + ZSTD_getErrorName(n));
  }
  out.resize(n);
  return out;
}

Status zstd_decompress(std::span<const std::uint8_t> frame, std::span<std::uint8_t> out,
                       const std::string& what) {
  auto corrupt = [&](const std::string& why) { return container::corrupt(what, why); };
  const unsigned long long declared = ZSTD_getFrameContentSize(frame.data(), frame.size());
  if (declared == ZSTD_CONTENTSIZE_ERROR) return corrupt("not a Zstandard frame");
  if (declared == ZSTD_CONTENTSIZE_UNKNOWN) {
    return corrupt("the Zstandard frame does not declare its size");
  }
  if (declared != out.size()) {
    return corrupt("the Zstandard frame declares " + plural_bytes(declared) + ", " +
                   plural_bytes(out.size()) + " expected");
  }
  const std::size_t frame_size = ZSTD_findFrameCompressedSize(frame.data(), frame.size());
  if (ZSTD_isError(frame_size)) {
    return corrupt(std::string("bad Zstandard frame (") + ZSTD_getErrorName(frame_size) + ")");
  }
  if (frame_size != frame.size()) {
    return corrupt(plural_bytes(frame.size() - frame_size) + " after the Zstandard frame");
  }
  std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> dctx(ZSTD_createDCtx(), ZSTD_freeDCtx);
  if (!dctx) return Status::error(ErrorCode::io_error, what + ": zstd: out of memory");
  // Single-pass into `out`: zstd stops with an error rather than write past its end.
  const std::size_t n =
      ZSTD_decompressDCtx(dctx.get(), out.data(), out.size(), frame.data(), frame.size());
  if (ZSTD_isError(n)) {
    return corrupt(std::string("bad Zstandard data (") + ZSTD_getErrorName(n) + ")");
  }
  if (n != out.size()) {
    return corrupt("Zstandard data decompressed to " + plural_bytes(n) + ", " +
                   plural_bytes(out.size()) + " expected");
  }
  return Status::success();
}

}  // namespace tessera::texture_file::ktx2
