// Internal to src/vk: the C interface of tessera-vk-glsl.so (glsl_module.cpp), the GLSL compiler
// module src/vk/shader.cpp loads with dlopen when tessera::vk must compile GLSL.
#pragma once

#include <cstddef>
#include <cstdint>

/// Stages of tessera_vk_glsl_compile.
#define TESSERA_VK_GLSL_COMPUTE 0
#define TESSERA_VK_GLSL_VERTEX 1
#define TESSERA_VK_GLSL_FRAGMENT 2
/// Its results: the SPIR-V in *words (*count words), a compile error in *log, or a failure of
/// the compiler itself in *log. Each pointer it sets is freed with tessera_vk_glsl_free.
#define TESSERA_VK_GLSL_OK 0
#define TESSERA_VK_GLSL_ERROR 1
#define TESSERA_VK_GLSL_FAILED 2

extern "C" {
/// Compiles `length` bytes of GLSL for Vulkan 1.0 (shaderc, VULKAN defined, optimised).
typedef int (*TesseraVkGlslCompile)(const char* text, std::size_t length, int stage,
                                    std::uint32_t** words, std::size_t* count, char** log);
typedef void (*TesseraVkGlslFree)(void* p);
}
