// tessera/procedural.h — deterministic procedural test content.
//
// Built-in demos and most tests use these images instead of files. Every generator is a pure
// function of its arguments (integer hashing, no global random state), so the same call gives
// the same bytes on every machine and thread count.
// Tests: tests/unit/core_test.cpp (the procedural images are fixed bytes).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tessera/core.h"

namespace tessera {

/// Kinds of procedural image.
enum class Procedural {
  gradient,  ///< Smooth colour gradients and soft rings: low-frequency content.
  bricks,    ///< Mortar lines between coloured bricks: hard edges, high contrast.
  noise,     ///< Multi-octave value noise with colour variation: photo-like texture detail.
  foliage,   ///< Leaf-like RGBA texture with cut-out and soft alpha (has_alpha = true).
  text,      ///< Thin dark strokes on a light background: the hardest case for block codecs.
};

/// All kinds, in a fixed order.
const std::vector<Procedural>& all_procedurals();
/// Lower-case name ("gradient", ...).
const char* procedural_name(Procedural kind);

/// Generates a `width` x `height` sRGB image of `kind` (sizes must pass `check_image_size`).
/// `seed` varies the content; the result depends on nothing else.
ImageRGBA8 make_procedural(Procedural kind, int width, int height, std::uint32_t seed = 1);

}  // namespace tessera
