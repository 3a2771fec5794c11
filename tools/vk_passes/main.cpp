// vk_passes OUTPUT_DIR — a build step of tessera::vk: writes the GLSL of vk::AdaptiveSupersampler's
// passes that read neither the engine's hook nor its G-buffer layout (the budget's HISTOGRAM,
// SELECT and APPLY, the frame list's ARGS: they read only the parameter block and the work
// buffer) as OUTPUT_DIR/PASS.comp, expanded as `create` expands them (src/adaptive/: the
// preamble, the shipped adaptive_component.glsl) for canonical options. The build compiles them
// with glslangValidator to SPIR-V and embeds them (src/CMakeLists.txt); `create` then compiles
// only the passes that shade or read the G-buffer, and patches the embedded modules' descriptor
// set to the component's (src/vk/embedded_passes.cpp).
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
  for (const char* pass : vk::kEmbeddedPasses) {
    Result<glsl::Expanded> e = glsl::expand_includes(adaptive::pass_source(o, pass),
                                                     adaptive::pass_expand_options(o, d, b, pass));
    if (!e) {
      std::fprintf(stderr, "vk_passes: %s\n", e.status().message.c_str());
      return 1;
    }
    const std::string path = std::string(argv[1]) + "/" + pass + ".comp";
    std::ofstream out(path, std::ios::binary);
    out << e->text;  // glslangValidator -V defines VULKAN, as shaderc does at create
    if (!out) {
      std::fprintf(stderr, "vk_passes: cannot write %s\n", path.c_str());
      return 1;
    }
  }
  return 0;
}
