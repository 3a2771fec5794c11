// vk_passes OUTPUT_DIR — a build step of tessera::vk: writes the GLSL of vk::AdaptiveSupersampler's
// passes that do not shade as OUTPUT_DIR/NAME.comp, expanded as `create` expands them
// (src/adaptive/: the preamble, the shipped adaptive_component.glsl):
//   * HISTOGRAM, SELECT, APPLY (the budget) and ARGS (the frame list's group counts) read only
//     the parameter block and the work buffer: expanded for canonical options;
//   * METRICS and LIST read the G-buffer: expanded with m, the UVs and the layout as
//     specialization constants (adaptive_specialized.cpp), in their variants METRICS_NO_FP64
//     (devices without shaderFloat64) and LIST_COUNTS (with the sample-count image).
// The build compiles them with glslangValidator to SPIR-V and embeds them (src/CMakeLists.txt);
// `create` compiles only the passes with the hook, patches the embedded modules' descriptor set
// (and the samplers' bindings) to the component's and specializes them
// (src/vk/embedded_passes.cpp).
#include <cstdio>
#include <fstream>
#include <string>

#include "adaptive/adaptive_host.h"
#include "tessera/glsl.h"
#include "vk/adaptive_bindings.h"
#include "vk/embedded_passes.h"

using namespace tessera;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: vk_passes OUTPUT_DIR\n");
    return 2;
  }
  // Canonical options: every value these passes do not read.
  AdaptiveCommonOptions o;
  o.width = o.height = 8;
  o.m = 2;
  o.layout.depth = {0, "r"};
  o.layout.normal = {0, "gba"};
  o.layout.id = {1, "r"};
  o.hook.name = "embedded pass";
  o.hook.source = "vec4 tessera_shade_sample(ivec2 g, float f) { return vec4(0.0); }";
  adaptive::Derived d;
  if (Status s = adaptive::check_options(o, "vk_passes", d); !s.ok()) {
    std::fprintf(stderr, "vk_passes: %s\n", s.message.c_str());
    return 1;
  }
  d.list_capacity = 1;
  d.float64 = false;  // no Float64 capability in the modules
  adaptive::GlslBindings b;
  b.set = 0;  // patched at create
  b.gbuffer = int(vk::kBindGBuffer);
  b.params = int(vk::kBindParams);
  b.work = int(vk::kBindWork);
  b.image = int(vk::kBindColour);
  auto write = [&](const std::string& name, const glsl::Source& src,
                   const glsl::ExpandOptions& eo) {
    Result<glsl::Expanded> e = glsl::expand_includes(src, eo);
    if (!e) {
      std::fprintf(stderr, "vk_passes: %s\n", e.status().message.c_str());
      return false;
    }
    const std::string path = std::string(argv[1]) + "/" + name + ".comp";
    std::ofstream out(path, std::ios::binary);
    out << e->text;  // glslangValidator -V defines VULKAN, as shaderc does at create
    if (!out) {
      std::fprintf(stderr, "vk_passes: cannot write %s\n", path.c_str());
      return false;
    }
    return true;
  };
  for (const char* pass : vk::kEmbeddedPasses) {
    if (!write(pass, adaptive::pass_source(o, pass),
               adaptive::pass_expand_options(o, d, b, pass))) {
      return 1;
    }
  }
  // METRICS and LIST: the layout, m and UVs as specialization constants.
  for (const std::string& variant : adaptive::specialized_variants()) {
    const std::string pass = variant.substr(0, variant.find('_'));
    if (!write(variant, adaptive::pass_source(o, pass),
               adaptive::specialized_expand_options(variant, b))) {
      return 1;
    }
  }
  return 0;
}
