// fscript render3d: a picture of a script's implicit shape (f >= 0 inside a box) without meshing,
// by the direct renderer (engine/render/direct.h): shaded, or its depth or normals.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "engine/mesh/local_field.h"
#include "engine/render/direct.h"
#include "engine/render/png.h"
#include "engine/render/shading.h"
#include "ir/interval_eval.h"
#include "runtime/support/files.h"
#include "runtime/support/progress.h"
#include "tools/fscript/commands.h"

namespace fscript::cli {
namespace {

using Clock = std::chrono::steady_clock;

// The script's field: its kernel, bounded and simplified per region where intervals can bound it.
struct ScriptField {
  std::unique_ptr<ir::IntervalTape> tape;
  std::unique_ptr<mesh::Field> field;
};

void make_field(const Compiled& c, ScriptField& s) {
  const ir::Function& fn = c.module->kernel_function();
  if (!ir::interval_evaluable(fn)) {
    s.field = std::make_unique<mesh::KernelField>(*c.kernel, 0.0f);
    return;
  }
  s.tape = std::make_unique<ir::IntervalTape>(fn);
  s.field = std::make_unique<mesh::LocalKernelField>(*c.kernel, 0.0f, *s.tape, nullptr, mesh::GradientTape{});
}

std::vector<uint8_t> image(const render::Hits& h, const render::RayGrid& g, const std::string& kind) {
  const size_t n = size_t(g.w) * g.h;
  std::vector<uint8_t> px(3 * n, kind == "shaded" ? 255 : 0);
  render::Shading light;
  auto unit = [](std::array<double, 3> v) {
    double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return std::array<double, 3>{v[0] / l, v[1] / l, v[2] / l};
  };
  light.right = unit(g.origin_col), light.up = unit({-g.origin_row[0], -g.origin_row[1], -g.origin_row[2]});
  light.back = unit({-g.dir[0], -g.dir[1], -g.dir[2]});
  const render::FixedViewShading lit(light, light.back);
  auto byte = [](float v) { return static_cast<uint8_t>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); };
  const int mode = kind == "depth" ? 0 : kind == "normal" ? 1 : 2;
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(h.depth[i])) continue;
    const auto& nr = h.normal[i];
    std::array<float, 3> rgb;
    if (mode == 0) {
      float v = static_cast<float>(1 - (h.depth[i] - g.near) / (g.far - g.near));
      rgb = {v, v, v};
    } else if (mode == 1) {
      for (int a = 0; a < 3; ++a) rgb[static_cast<size_t>(a)] = 0.5f + 0.5f * nr[static_cast<size_t>(a)];
    } else {
      rgb = lit.shade({0.8f, 0.8f, 0.8f}, {nr[0], nr[1], nr[2]});
    }
    for (size_t k = 0; k < 3; ++k) px[3 * i + k] = byte(rgb[k]);
  }
  return px;
}

void print_stats(const render::DirectStats& st, const render::RayGrid& g) {
  const double rays = static_cast<double>(g.w) * g.h, dense = rays * g.steps;
  if (!st.pruned) std::printf("pruning: off (dense: every step of every ray until it meets the shape)\n");
  else
    for (const auto& l : st.levels)
      std::printf("level %ux%u x %u steps: %zu empty, %zu full, %zu ambiguous\n", l.tile, l.tile, l.steps, l.empty,
                  l.full, l.ambiguous);
  std::printf("step points evaluated: %zu (%.3f%% of every step of every ray), %.2f per ray\n", st.points,
              100.0 * static_cast<double>(st.points) / dense, static_cast<double>(st.points) / rays);
  std::printf("hits: %zu; refining them: %zu points; normals from the slope: %zu\n", st.hits, st.refines, st.gradients);
  if (st.pruned) std::printf("regions constant along their rays, probed once a ray: %zu\n", st.constant);
}

}  // namespace

int cmd_render3d(const Options& o, const Render3dArgs& a) {
  uint32_t w, h;
  float bd[6], view[2] = {0, 0};
  if (!parse_size(a.size, w, h)) {
    std::cerr << "error: --size wants W or WxH with 1 <= W, H <= 32768, got '" << a.size << "'\n";
    return kExitUsage;
  }
  if (!parse_numbers(a.bounds, 6, bd) || bd[0] >= bd[1] || bd[2] >= bd[3] || bd[4] >= bd[5]) {
    std::cerr << "error: --bounds wants six finite numbers X0,X1,Y0,Y1,Z0,Z1 with X0 < X1, Y0 < Y1, Z0 < Z1, got '"
              << a.bounds << "'\n";
    return kExitUsage;
  }
  if (!a.view.empty() && !parse_numbers(a.view, 2, view)) {
    std::cerr << "error: --view wants AZIMUTH,ELEVATION in degrees, got '" << a.view << "'\n";
    return kExitUsage;
  }
  if (a.image != "shaded" && a.image != "depth" && a.image != "normal") {
    std::cerr << "error: --image wants shaded, depth or normal, got '" << a.image << "'\n";
    return kExitUsage;
  }
  if (!a.out.empty() && a.file != "-" && support::same_file(a.out, a.file)) {
    std::cerr << "error: the output " << a.out << " is the script this command reads: name another output\n";
    return kExitUsage;
  }
  const auto start = Clock::now();
  auto since = [](Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); };
  Compiled c;
  if (int rc = compile_file(a.file, a.entry, o, c); rc != kExitOk) return rc;
  size_t n_in = c.kernel->num_inputs();
  if (n_in < 3 || n_in > 4) {
    std::cerr << "error: render3d needs an entry of x, y, z (and t, taken as 0): this one has " << n_in << " inputs\n";
    return kExitInput;
  }
  ScriptField sf;
  make_field(c, sf);
  const double compile_ms = since(start);
  std::array<double, 6> box{bd[0], bd[1], bd[2], bd[3], bd[4], bd[5]};
  render::RayGrid g = render::orthographic(box, w, h, a.steps ? a.steps : std::max(w, h), view[0], view[1]);
  render::DirectOptions ro;
  ro.threads = std::max(1u, a.threads);
  ro.prune = a.prune;
  ro.points = false;
  render::Hits hits;
  render::DirectStats st;
  backends::RuntimeError err;
  double ms = 0;
  bool ok = true;
  support::progress_expect(std::max(1u, a.repeat), "pictures");
  std::optional<support::ProgressLine> line;
  line.emplace("fscript render3d");
  for (unsigned r = 0; ok && r < std::max(1u, a.repeat); ++r) {  // the best of `repeat`
    auto t0 = Clock::now();
    support::ProgressJob job;
    ro.progress = &job;
    ok = render::trace(*sf.field, g, ro, hits, st, err);
    ro.progress = nullptr;
    double t = since(t0);
    ms = r == 0 ? t : std::min(ms, t);
  }
  line.reset();
  if (!ok) {
    print_runtime_error(*c.script.file, err);
    return kExitInput;
  }
  std::string path = a.out;
  if (path.empty()) {
    std::string stem = a.file == "-" ? "render3d" : std::filesystem::path(a.file).stem().string();
    path = (stem.empty() ? std::string("render3d") : stem) + ".png";
  }
  std::string error;
  auto t1 = Clock::now();
  std::vector<uint8_t> px = image(hits, g, a.image);
  const double image_ms = since(t1);
  t1 = Clock::now();
  if (!render::write_png(path, w, h, 3, px, error)) {
    std::cerr << "error: " << error << "\n";
    return kExitInput;
  }
  const double png_ms = since(t1);
  std::printf("%zu pixels on the shape\n%.3f ms\n", st.hits, ms);
  std::fflush(stdout);
  std::cerr << "wrote " << path << ": " << w << "x" << h << ", " << st.hits << " pixels on the shape\n";
  if (a.stats) {
    print_stats(st, g);
    std::printf("time: compiling %.1f ms, tracing %.1f ms (the best of %u), shading %.1f ms, writing the PNG %.1f ms\n",
                compile_ms, ms, std::max(1u, a.repeat), image_ms, png_ms);
  }
  return kExitOk;
}

}  // namespace fscript::cli
