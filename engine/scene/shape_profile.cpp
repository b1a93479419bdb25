// Profiles to reports: each field's measured time split over its tape's steps by what each op
// costs on this machine, each step charged to its source line (simplified tapes keep their steps'
// lines while profiling), and the columns of the picture coloured by work and by tape length.
#include "engine/scene/shape_profile.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <set>

#include "backends/vm/vm_points.h"
#include "engine/scene/shape_field.h"
#include "engine/scene/shape_mesh.h"

namespace fscript::scene {
namespace {

// The tape of 4 parameters and then `k` steps of `op` on them (none: the parameters alone).
ir::IntervalTape calibration_tape(ir::Op op, int k) {
  ir::Function fn;
  fn.num_params = 4;
  fn.kernel = true;
  ir::Block* b = fn.add_block();
  auto append = [b](ir::Inst* i) { return i->block = b, b->insts.push_back(i), i; };
  ir::Inst* p[4];
  for (int a = 0; a < 4; ++a) (p[a] = append(fn.make(ir::Op::Param)))->aux = a;
  ir::Inst* last = p[0];
  int arity = std::max(0, ir::op_info(op).arity);
  for (int j = 0; j < k; ++j) {
    ir::Inst* i = fn.make(op);
    i->imm = 0.5f;
    for (int a = 0; a < arity; ++a) i->args.push_back(p[(j + a) % 3]);
    last = append(i);
  }
  ir::Inst* ret = fn.make(ir::Op::Ret);
  ret->args.push_back(last);
  append(ret);
  return ir::IntervalTape(fn);
}

// Nanoseconds per point of the tape on the VM, the best of a few runs over points in (0.1, 0.9).
double tape_ns(const ir::IntervalTape& t) {
  constexpr size_t n = 4 * vm::kPointLanes;
  static std::vector<float> in[4];
  if (in[0].empty())
    for (size_t i = 0; i < n; ++i)
      for (int a = 0; a < 4; ++a) in[a].push_back(0.1f + 0.8f * static_cast<float>((i * (a + 3) * 37) % n) / n);
  std::vector<float> out(vm::kPointLanes);
  double best = 1e30;
  for (int rep = 0; rep < 5; ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    for (size_t i = 0; i < n; i += vm::kPointLanes) {
      const float* at[4] = {in[0].data() + i, in[1].data() + i, in[2].data() + i, in[3].data() + i};
      vm::eval_tape_points(t, at, 4, vm::kPointLanes, out.data());
    }
    best = std::min(best, std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count());
  }
  return best / n;
}

}  // namespace

double op_cost_ns(ir::Op op) {
  static std::mutex lock;
  static std::map<ir::Op, double> known;
  static double base = -1;
  std::lock_guard<std::mutex> hold(lock);
  if (base < 0) base = tape_ns(calibration_tape(ir::Op::Param, 0));
  auto it = known.find(op);
  if (it != known.end()) return it->second;
  constexpr int k = 32;
  double c = (tape_ns(calibration_tape(op, k)) - base) / k;
  return known[op] = std::max(c, 0.01);  // a floor: every step costs something
}

namespace {

// Parameters and constants are where a step's operands come from, not work of a line.
bool operation(ir::Op op) { return op != ir::Op::Param && op != ir::Op::Const; }

using Tapes = std::vector<std::shared_ptr<const ir::IntervalTape>>;

size_t operations(const Tapes& tapes) {
  size_t n = 0;
  for (const auto& t : tapes) n += t->operations();
  return n;
}

struct Lines {
  std::map<uint32_t, LineCost> by_line;
  // op_cost_ns by op, asked once each here (it locks and looks up; a report charges millions of steps).
  std::array<double, ir::kNumOps> costs{};
  double cost(ir::Op op) {
    double& c = costs[static_cast<size_t>(op)];
    return c > 0 ? c : c = op_cost_ns(op);
  }
  // Charges `points` evaluations of `tapes` (each point runs them all) taking `ns` to their
  // steps' lines, the time split by what each step's op costs.
  void charge(const Tapes& tapes, uint64_t points, double ns, std::map<uint32_t, double>& runs) {
    double sum = 0;
    for (const auto& t : tapes)
      for (const auto& step : t->steps()) sum += cost(step.op);
    std::set<uint32_t> seen;
    for (const auto& t : tapes) {
      const auto& steps = t->steps();
      const auto& src = t->sources();
      for (size_t i = 0; i < steps.size(); ++i) {
        if (!operation(steps[i].op)) continue;
        uint32_t line = i < src.size() ? src[i].line : 0;
        LineCost& l = by_line[line];
        l.line = line;
        l.ops += static_cast<double>(points);
        l.ns += sum > 0 ? ns * cost(steps[i].op) / sum : 0;
        if (seen.insert(line).second) runs[line] += static_cast<double>(points);
      }
    }
  }
};

}  // namespace

ShapeProfile profile_report(const vrml::Scene& scene, const vrml::Node& node, const mesh::FieldProfile& p) {
  ShapeProfile r;
  const frontend::SourceFile& file = vrml::file_of(scene, node);
  r.path = file.path();
  r.line = file.position(node.span.begin).line;
  r.kind = node.type;
  Lines lines;
  std::map<uint32_t, double> runs;  // points whose tape runs the line
  double tape_sum = 0, value_ops = 0;
  for (const mesh::FieldRecord& rec : p.records()) {
    uint64_t pts = rec.points, grads = rec.gradients;
    r.points += pts, r.gradients += grads, r.boxes += rec.bounds;
    r.value_ms += rec.point_ns / 1e6, r.gradient_ms += rec.gradient_ns / 1e6, r.bound_ms += rec.bound_ns / 1e6;
    const size_t ops = operations(rec.value);
    if (!rec.has_box) r.whole_points += pts, r.whole_length = ops;
    if (rec.value.empty()) continue;
    r.mapped = true;
    if (rec.has_box && pts > 0) {
      ++r.regions;
      r.tape_min = r.regions == 1 ? ops : std::min(r.tape_min, ops);
      r.tape_max = std::max(r.tape_max, ops);
      tape_sum += static_cast<double>(ops);
    }
    value_ops += static_cast<double>(pts) * static_cast<double>(ops);
    if (pts) lines.charge(rec.value, pts, static_cast<double>(rec.point_ns), runs);
    if (grads && !rec.gradient.empty()) lines.charge(rec.gradient, grads, static_cast<double>(rec.gradient_ns), runs);
  }
  if (r.regions) r.tape_mean = tape_sum / static_cast<double>(r.regions);
  if (r.points) r.ops_per_point = value_ops / static_cast<double>(r.points);
  for (const mesh::OctreeLevel& l : p.prune().levels) r.decided += l.empty + l.full, r.undecided += l.ambiguous;
  double evaluated = static_cast<double>(r.points + r.gradients);
  for (auto& [line, l] : lines.by_line) {
    l.runs_at = evaluated > 0 ? runs[line] / evaluated : 0;
    if (line) l.text = file.line_at(line);
    r.ops += l.ops, r.ns += l.ns;
    r.lines.push_back(l);
  }
  return r;
}

std::string profile_text(const ShapeProfile& r, size_t rows) {
  std::string out;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%s:%u: %s: %llu values in %.1f ms, %llu gradients in %.1f ms, %llu boxes bounded in %.1f ms\n",
                r.path.c_str(), r.line, r.kind.c_str(), static_cast<unsigned long long>(r.points), r.value_ms,
                static_cast<unsigned long long>(r.gradients), r.gradient_ms, static_cast<unsigned long long>(r.boxes),
                r.bound_ms);
  out += buf;
  if (!r.mapped)
    return out + "  its function runs on no tape (a 3D texture, or not straight-line code): no lines to show\n";
  if (r.decided + r.undecided == 0) {
    std::snprintf(buf, sizeof buf, "  no pruning: every value on the whole function (%zu operations)\n",
                  r.whole_length);
  } else {
    std::snprintf(buf, sizeof buf,
                  "  pruning: %llu octree regions decided, %llu open; the whole function (%zu operations) for %llu "
                  "values; %zu regions with a tape of their own",
                  static_cast<unsigned long long>(r.decided), static_cast<unsigned long long>(r.undecided),
                  r.whole_length, static_cast<unsigned long long>(r.whole_points), r.regions);
    out += buf;
    if (r.regions)
      std::snprintf(buf, sizeof buf, ": %zu to %zu operations, mean %.1f; %.1f operations per value\n", r.tape_min,
                    r.tape_max, r.tape_mean, r.ops_per_point);
    else std::snprintf(buf, sizeof buf, "\n");
  }
  out += buf;
  out += "   line   time    ops  runs at  source\n";
  std::vector<LineCost> sorted = r.lines;
  std::stable_sort(sorted.begin(), sorted.end(), [](const LineCost& a, const LineCost& b) { return a.ns > b.ns; });
  if (rows && sorted.size() > rows) sorted.resize(rows);
  for (const LineCost& l : sorted) {
    std::string text = l.line ? l.text : "(inputs and constants)";
    size_t lead = text.find_first_not_of(" \t");
    text = lead == std::string::npos ? "" : text.substr(lead);
    if (text.size() > 72) text = text.substr(0, 69) + "...";
    std::string where = l.line ? std::to_string(l.line) : "-";
    std::snprintf(buf, sizeof buf, "  %5s %5.1f%% %5.1f%%  %6.1f%%  %s\n", where.c_str(),
                  r.ns > 0 ? 100 * l.ns / r.ns : 0.0, r.ops > 0 ? 100 * l.ops / r.ops : 0.0, 100 * l.runs_at,
                  text.c_str());
    out += buf;
  }
  return out;
}

bool profile_scene(const vrml::Scene& scene, const SceneModel& model, int threads, bool prune, SceneProfile& out,
                   backends::RuntimeError& err, const vrml::Node*& where) {
  mesh::MesherOptions mesher;
  mesher.profiler = &out.profiler;
  for (const Shape& s : model.shapes) {
    if (s.group >= 0 || s.kind != ShapeKind::Implicit) continue;
    mesh::Mesh m;
    if (!mesh_shape(s, m, err, true, threads, prune, mesher)) return where = s.fshape, false;
  }
  for (size_t g = 0; g < model.groups.size(); ++g) {
    if (model.groups[g].parent >= 0 || parametric_group(model, static_cast<int>(g))) continue;
    mesh::Mesh m;
    if (!mesh_group(model, static_cast<int>(g), m, err, true, threads, prune, mesher))
      return where = model.groups[g].node, false;
  }
  for (const auto& [key, p] : out.profiler.profiles()) {
    out.shapes.push_back(profile_report(scene, *static_cast<const vrml::Node*>(key), *p));
    out.profiles.push_back(p.get());
  }
  return true;
}

nlohmann::json profile_json(const ShapeProfile& r) {
  nlohmann::json lines = nlohmann::json::array();
  for (const LineCost& c : r.lines)
    lines.push_back({{"line", c.line}, {"ops", c.ops}, {"time", r.ns > 0 ? c.ns / r.ns : 0.0}, {"runs_at", c.runs_at}});
  return {{"path", r.path},
          {"line", r.line},
          {"node", r.kind},
          {"mapped", r.mapped},
          {"values", r.points},
          {"gradients", r.gradients},
          {"boxes", r.boxes},
          {"value_ms", r.value_ms},
          {"gradient_ms", r.gradient_ms},
          {"bound_ms", r.bound_ms},
          {"whole_operations", r.whole_length},
          {"whole_values", r.whole_points},
          {"regions", r.regions},
          {"tape_min", r.tape_min},
          {"tape_mean", r.tape_mean},
          {"tape_max", r.tape_max},
          {"operations_per_value", r.ops_per_point},
          {"decided", r.decided},
          {"undecided", r.undecided},
          {"lines", lines}};
}

namespace {

// The picture's panels are at least this many pixels on their longer side (columns repeated).
constexpr int kPictureSide = 256;

// Black, red, yellow, white along t in [0, 1].
void heat(double t, uint8_t* px) {
  t = std::clamp(t, 0.0, 1.0);
  px[0] = static_cast<uint8_t>(255 * std::min(1.0, 3 * t));
  px[1] = static_cast<uint8_t>(255 * std::clamp(3 * t - 1, 0.0, 1.0));
  px[2] = static_cast<uint8_t>(255 * std::clamp(3 * t - 2, 0.0, 1.0));
}

}  // namespace

std::vector<uint8_t> profile_picture(const mesh::FieldProfile& p, uint32_t& out_width, uint32_t& out_height) {
  const int w = p.width(), h = p.height();
  if (!w) return {};
  const int zoom = std::max(1, kPictureSide / std::max(w, h)), gap = 4, width = 2 * w * zoom + gap;
  const int height = h * zoom;
  std::vector<uint8_t> px(static_cast<size_t>(width) * static_cast<size_t>(height) * 3, 255);
  uint64_t most_work = 0;
  double most_len = 0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      most_work = std::max(most_work, p.column_work(i, j));
      if (uint64_t n = p.column_values(i, j))
        most_len = std::max(most_len, static_cast<double>(p.column_value_ops(i, j)) / static_cast<double>(n));
    }
  const uint8_t none[3] = {16, 24, 64};
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      uint8_t left[3], right[3];
      uint64_t work = p.column_work(i, j), n = p.column_values(i, j);
      if (work) heat(std::sqrt(static_cast<double>(work) / static_cast<double>(most_work)), left);
      else std::copy(none, none + 3, left);
      if (n) heat(static_cast<double>(p.column_value_ops(i, j)) / static_cast<double>(n) / most_len, right);
      else std::copy(none, none + 3, right);
      for (int dj = 0; dj < zoom; ++dj)
        for (int di = 0; di < zoom; ++di) {
          size_t row = static_cast<size_t>(j * zoom + dj) * static_cast<size_t>(width);
          std::copy(left, left + 3, &px[(row + static_cast<size_t>(i * zoom + di)) * 3]);
          std::copy(right, right + 3, &px[(row + static_cast<size_t>(w * zoom + gap + i * zoom + di)) * 3]);
        }
    }
  out_width = static_cast<uint32_t>(width), out_height = static_cast<uint32_t>(height);
  return px;
}

}  // namespace fscript::scene
