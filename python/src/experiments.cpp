// tessera.run_seams / tessera.run_aa: the library's experiments and their result format
// (experiments::to_json / to_markdown), the same text `tessera seams` / `tessera aa` write.
#include "experiments.h"

#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "tessera/experiments.h"

namespace tessera::python {

namespace {

using namespace pybind11::literals;

/// The JSON text as a dict (Python's json module), or the Markdown as it is.
py::object report(const std::string& json, const std::string& markdown, bool as_markdown) {
  if (as_markdown) return py::str(markdown);
  return py::module_::import("json").attr("loads")(json);
}

py::object run_seams_py(std::vector<int> msaa, int frames, int quality_frames, int width,
                        int height, int reference_factor, int near_seam_pixels, int threads,
                        bool markdown) {
  experiments::SeamsConfig c;
  c.msaa = std::move(msaa);
  c.frames = frames;
  c.quality_frames = quality_frames;
  c.width = width;
  c.height = height;
  c.reference_factor = reference_factor;
  c.near_seam_pixels = near_seam_pixels;
  c.threads = threads;
  c.keep_images = false;
  std::string json, md;
  {
    py::gil_scoped_release release;
    experiments::SeamsResult r = unwrap(experiments::run_seams(c));
    json = experiments::to_json(c, r, {.images = false});
    md = experiments::to_markdown(c, r, {.images = false});
  }
  return report(json, md, markdown);
}

py::object run_aa_py(std::vector<int> ssaa, int width, int height, int frames, int lights,
                     bool heavy, int threads, bool markdown) {
  experiments::AaConfig c;
  c.ssaa = std::move(ssaa);
  c.width = width;
  c.height = height;
  c.frames = frames;
  c.lights = lights;
  c.heavy = heavy;
  c.threads = threads;
  std::string json, md;
  {
    py::gil_scoped_release release;
    const experiments::AaResult r = unwrap(experiments::run_aa(c));
    json = unwrap(experiments::to_json(c, r));
    md = unwrap(experiments::to_markdown(c, r));
  }
  return report(json, md, markdown);
}

}  // namespace

void register_experiments(py::module_& m) {
  m.def("run_seams", &run_seams_py,
        "Toth 2013's seam experiment on the built-in Figure-1 scene on the CPU "
        "(experiments::run_seams): returns the dict of `tessera seams --json` with the same "
        "options (without `zoom_window`: no images are written), or with markdown=True the text "
        "of seams.md.",
        py::kw_only(), "msaa"_a = std::vector<int>{1, 2, 4, 8}, "frames"_a = 8,
        "quality_frames"_a = 0, "width"_a = 480, "height"_a = 540, "reference_factor"_a = 8,
        "near_seam_pixels"_a = 2, "threads"_a = 0, "markdown"_a = false);
  m.def("run_aa", &run_aa_py,
        "Hollander et al. 2013's adaptive-supersampling experiment on the built-in scene on the "
        "CPU (experiments::run_aa): returns the dict of `tessera aa --json` with the same "
        "options, or with markdown=True the text of aa.md.",
        py::kw_only(), "ssaa"_a = std::vector<int>{2, 3, 4}, "width"_a = 1024, "height"_a = 768,
        "frames"_a = 3, "lights"_a = 8, "heavy"_a = false, "threads"_a = 0, "markdown"_a = false);
}

}  // namespace tessera::python
