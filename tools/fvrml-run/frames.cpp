// Frames: numbered mesh files or a contact sheet for `--frames N`, and animated VRML97 / glTF,
// where each animated node's frames go through the frame cache (frames polygonized in parallel).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <mutex>

#include "frontend/source.h"
#include "engine/mesh/field.h"
#include "engine/mesh/frame_cache.h"
#include "engine/mesh/gltf.h"
#include "engine/render/png.h"
#include "engine/scene/shape_mesh.h"
#include "engine/scene/standard_geometry.h"
#include "engine/scene/vrml_export.h"
#include "runtime/support/parallel.h"
#include "runtime/support/progress.h"
#include "runtime/support/files.h"
#include "tools/fvrml-run/memo.h"
#include "tools/fvrml-run/run.h"
#include "tools/fvrml-run/shard.h"

namespace fvrml_run {
namespace {

using fscript::scene::kMaxFrames;  // a file's `frames` over it is an error (scene_model.h)

// Runs fn(i) for i < n on `threads` workers, each taking every threads-th index; false when any
// call failed (the others still finish theirs).
template <class Fn>
bool parallel_for(int n, int threads, Fn fn) {
  int t = std::max(1, std::min(threads, n));
  return fscript::support::run_parts(t, [&](int w) {
    bool ok = true;
    for (int i = w; i < n; i += t) ok = fn(i) && ok;
    return ok;
  });
}

// The scene at fractions i / n, built one after another so diagnostics stay in order (printed
// once, with the first).
bool frame_models(const Options& o, Loaded& l, int n, std::vector<SceneModel>& out, bool print_first) {
  out.resize(n);
  for (int f = 0; f < n; ++f) {
    fscript::scene::ModelOptions mo = o.model;
    mo.fraction = static_cast<double>(f) / n;
    if (!build(l, out[f], mo, print_first && f == 0)) return false;
  }
  return true;
}

bool externally_driven(const vrml::Scene& scene, const vrml::Node& n) {
  if (n.def_name.empty()) return false;
  for (const auto& r : scene.routes)
    if (r.to_node == n.def_name && r.to_field == "set_fraction") return true;
  return false;
}

// Writes text to OUT, or to standard output for "-" or no -o.
bool write_text(const Options& o, const std::string& text) {
  if (o.output.empty() || o.output == "-") {
    std::cout << text;
    return true;
  }
  std::string error;
  if (fscript::support::write_file_atomic(o.output, text, error)) return true;
  std::cerr << "error: " << error << "\n";
  return false;
}

// The glTF animation of a track's cached frames: all of them, or (partial) those made so far, each
// shown until the next one made.
mesh::GltfAnimation gltf_animation(const vrml::Scene& scene, const Track& t, const mesh::FrameCache& cache,
                                   bool partial) {
  mesh::GltfAnimation a;
  a.name = t.node->def_name.empty() ? "line " + std::to_string(node_line(scene, *t.node)) : t.node->def_name;
  a.cycle_interval = fscript::scene::time_fields(*t.node).cycle_interval;
  for (size_t i = 0; i < cache.size(); ++i) {
    mesh::Mesh m;
    if (!cache.peek(i, m)) continue;
    a.frames.push_back(std::move(m));
    if (partial) a.starts.push_back(a.cycle_interval * static_cast<double>(i) / static_cast<double>(cache.size()));
  }
  return a;
}

}  // namespace

// A track's frames differ where some script it runs reads t.
bool moves(const SceneModel& m, const Track& t) {
  auto shape_moves = [](const fscript::scene::Shape& s) {
    bool r = s.geometry.reads_t || (s.texture && s.texture->reads_t) || (s.colour && s.colour->reads_t);
    for (const auto& f : s.material) r = r || f.reads_t;
    return r;
  };
  if (!t.group) return shape_moves(m.shapes[static_cast<size_t>(t.index)]);
  for (size_t g = 0; g < m.groups.size(); ++g) {
    if (!fscript::scene::inside_group(m, static_cast<int>(g), t.index)) continue;
    const auto& grp = m.groups[g];
    if (grp.op_kernel && grp.op_kernel->reads_t) return true;
    for (const auto& [field, parts] : grp.affine)
      for (const auto& f : parts)
        if (f.reads_t) return true;
    for (int s : grp.shapes)
      if (shape_moves(m.shapes[static_cast<size_t>(s)])) return true;
  }
  return false;
}

namespace {

// A shard's part records the hash of the files the scene read; a merge checks it against them now.
bool stamp_scene(const Options& o, const Loaded& l) {
  if (o.shard_part) o.shard_part->scene_hash = scene_files_hash(l.files);
  if (!o.merging || scene_files_hash(l.files) == o.merging->scene_hash) return true;
  std::cerr << o.path << ": error: the scene's files changed since the shards were made; run the shards again\n";
  return false;
}

// --shard K/M: makes the frames i % M == K of a track (a still track's one frame: shard 0) and
// adds them to the part with their keys.
bool shard_frames(const Options& o, const std::vector<std::string>& keys, mesh::FrameCache& cache,
                  fscript::backends::RuntimeError& err) {
  Part& part = *o.shard_part;
  for (size_t i = static_cast<size_t>(part.shard.index); i < keys.size(); i += static_cast<size_t>(part.shard.count)) {
    mesh::Mesh m;
    if (!cache.get(i, m, err)) return false;
    part.frames.push_back({keys[i], *cache.compact(i)});
  }
  return true;
}

// The frame keys of a track in the memo; frames found there go into the cache. Returns the keys of
// the frames still to make (empty strings for those found). A still track has one key, frame 0's.
std::vector<std::string> from_memo(const Options& o, const vrml::Scene& scene, const Track& t,
                                   const std::vector<SceneModel>& ms, bool world, bool still, mesh::FrameCache& cache) {
  std::vector<std::string> keys(still ? 1 : ms.size());
  if (!o.memo) return keys;
  for (size_t i = 0; i < keys.size(); ++i) {
    size_t k = static_cast<size_t>(t.index);
    keys[i] = t.group ? group_key(o, scene, ms[i], k, world) : shape_key(o, scene, ms[i], k, world);
    if (auto hit = o.memo->find_frame(keys[i])) {
      fscript::support::ProgressJob done;
      for (size_t f = i; f < (still ? ms.size() : i + 1); ++f) cache.put(f, *hit);
      keys[i].clear();
    }
  }
  return keys;
}

}  // namespace

int frames(const Options& o, Loaded& l, nlohmann::json& st) {
  auto t2 = Clock::now();
  uint64_t e0 = mesh::evaluation_ns().load();
  std::vector<SceneModel> models;
  if (!frame_models(o, l, o.frames, models, true) || !within_sample_limits(o, l, models[0], o.frames)) return 1;
  report_shapes(o, l, models[0], st);
  if (!stamp_scene(o, l)) return 1;
  std::mutex part_lock;
  int cols = static_cast<int>(std::ceil(std::sqrt(o.frames))), rows = (o.frames + cols - 1) / cols;
  uint32_t tw = std::max<uint32_t>(16, o.width / cols), th = std::max<uint32_t>(16, o.height / rows);
  std::vector<uint8_t> sheet(size_t(tw) * cols * th * rows * 3, 255);
  std::vector<nlohmann::json> per_frame(o.frames);
  int parallel = std::min(o.threads, o.frames), per = std::max(1, o.threads / parallel);
  fscript::support::progress_expect(static_cast<uint64_t>(o.frames) * mesh_jobs(models[0]), "frames");
  std::atomic<bool> failed{false};
  bool ok = parallel_for(o.frames, parallel, [&](int f) {
    if (o.shard_part && f % o.shard_part->shard.count != o.shard_part->shard.index) return true;
    mesh::Mesh all;
    DirectParts direct;  // a contact sheet's implicit shapes, drawn without meshing
    fscript::backends::RuntimeError err;
    size_t bad = 0;
    if (o.whole_frames) {  // fvrml-run merge: the frame as its shard made it
      auto it = o.whole_frames->find(static_cast<uint32_t>(f));
      if (it == o.whole_frames->end()) {
        std::cerr << "error: frame " << f << " is in none of the parts (shard " << f % o.merging->shard.count << " of "
                  << o.merging->shard.count << " should have made it)\n";
        return false;
      }
      all = it->second;
    } else {
      bool sheet_part = o.format == "png" && !o.shard_part;  // a shard's frames travel as meshes
      if (sheet_part && !direct_parts(o, l.scene, models[f], direct)) return false;
      Meshed meshed = mesh_scene(o, l.scene, models[f], true, per, direct.meshed_no_more);
      if (meshed.failed) {
        failed = true;
        if (!o.keep_going) return false;
      }
      all = o.format == "png" ? picture(meshed, l.scene) : merged(meshed);
    }
    per_frame[f] = {{"fraction", static_cast<double>(f) / o.frames},
                    {"vertices", all.positions.size()},
                    {"triangles", all.triangles.size()}};
    if (o.shard_part) {
      std::lock_guard<std::mutex> hold(part_lock);
      o.shard_part->whole_frames.emplace_back(static_cast<uint32_t>(f), std::move(all));
      return true;
    }
    if (o.format != "png") return write_frame(o, numbered(o.output, f, o.frames), all);
    fscript::render::RenderOptions ro = render_options(o, l.scene, tw, th);
    ro.threads = static_cast<unsigned>(per);
    std::vector<uint8_t> px;
    if (direct.shapes.empty()) px = fscript::render::render(all, ro);
    else if (!fscript::render::render(all, direct.shapes, ro, px, err, bad))
      return report(o, l.scene, direct.nodes[bad], err), false;
    int cx = f % cols, cy = f / cols;
    for (uint32_t y = 0; y < th; ++y)
      std::copy_n(px.begin() + size_t(y) * tw * 3, tw * 3,
                  sheet.begin() + ((size_t(cy) * th + y) * tw * cols + size_t(cx) * tw) * 3);
    return true;
  });
  if (!ok) return 1;
  if (o.shard_part) {  // main.cpp writes the part, its frames in order whatever the threads did
    std::sort(o.shard_part->whole_frames.begin(), o.shard_part->whole_frames.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    return 0;
  }
  std::string error;
  if (o.format == "png" && !fscript::render::write_png(o.output, tw * cols, th * rows, 3, sheet, error))
    return std::cerr << "error: " << error << "\n", 1;
  st["frames"] = per_frame;
  st["polygonize_ms"] = ms_since(t2);
  st["evaluation_ms"] = evaluation_ms_since(e0);
  return failed ? 1 : 0;
}

std::vector<Track> tracks(const Options& o, const SceneModel& model) {
  std::vector<Track> out;
  if (o.format != "wrl" && o.format != "glb") return out;
  auto add = [&](Track t, double own) {
    t.frames = o.frames > 0 ? o.frames : std::clamp(static_cast<int>(own), 0, kMaxFrames);
    if (t.frames == 0 && !o.instant && moves(model, t)) t.frames = kDefaultAnimationFrames;
    if (t.frames > 0) out.push_back(t);
  };
  for (size_t i = 0; i < model.shapes.size(); ++i) {
    const auto& s = model.shapes[i];
    if (s.group < 0) add({s.fshape, false, static_cast<int>(i), 0}, s.frames);
  }
  for (size_t g = 0; g < model.groups.size(); ++g) {
    const auto& grp = model.groups[g];
    if (grp.parent < 0)
      add({grp.node, true, static_cast<int>(g), 0}, fscript::scene::field_number(*grp.node, "frames"));
  }
  return out;
}

bool scene_moves(const SceneModel& model) {
  for (size_t i = 0; i < model.shapes.size(); ++i)
    if (model.shapes[i].group < 0 && moves(model, {model.shapes[i].fshape, false, static_cast<int>(i), 0})) return true;
  for (size_t g = 0; g < model.groups.size(); ++g)
    if (model.groups[g].parent < 0 && moves(model, {model.groups[g].node, true, static_cast<int>(g), 0})) return true;
  return false;
}

bool within_sample_limits(const Options& o, Loaded& l, const SceneModel& model, int frames) {
  using fscript::scene::ShapeKind;
  std::vector<uint64_t> per(model.shapes.size(), static_cast<uint64_t>(std::max(frames, 1)));
  for (const auto& t : frames > 0 ? std::vector<Track>{} : tracks(o, model))
    for (size_t i = 0; i < model.shapes.size(); ++i)
      if (t.group ? fscript::scene::inside_group(model, model.shapes[i].group, t.index)
                  : static_cast<int>(i) == t.index)
        per[i] = static_cast<uint64_t>(t.frames);
  // Work: every point of every frame. Memory: one frame of every shape at once, and the finished
  // parametric frames an animation keeps (implicit ones depend on the surface: the limit stops them).
  double samples = 0, bytes = 0, most = 0, most_bytes = 0;
  size_t worst = 0, heaviest = 0;
  for (size_t i = 0; i < model.shapes.size(); ++i) {
    fscript::scene::ShapeCost c = fscript::scene::shape_cost(model.shapes[i]);
    double n = c.samples * static_cast<double>(per[i]), b = c.bytes + c.kept * static_cast<double>(per[i] - 1);
    samples += n, bytes += b;
    if (n > most) most = n, worst = i;
    if (b > most_bytes) most_bytes = b, heaviest = i;
  }
  double memory = fscript::scene::memory_limit_bytes(o.model.max_memory_mib);
  bool over_work = samples > fscript::scene::kMaxShapeSamples;
  if (!over_work && bytes <= memory) return true;
  size_t at_shape = over_work ? worst : heaviest;
  const auto& s = model.shapes[at_shape];
  const vrml::Node& at = s.geometry_node ? *s.geometry_node : *s.fshape;
  const vrml::FieldSlot* res = at.slot("resolution");
  uint64_t f = per[at_shape];
  char text[400];
  if (over_work)
    std::snprintf(
        text, sizeof text,
        "the run asks for %.3g sample points (this shape: %.3g, times %llu frame%s), over the limit of %.3g for "
        "one run; lower the resolutions, the frames or --resolution-scale",
        samples, most / static_cast<double>(f), static_cast<unsigned long long>(f), f == 1 ? "" : "s",
        fscript::scene::kMaxShapeSamples);
  else
    std::snprintf(text, sizeof text,
                  "the run needs about %s of memory (this shape: %s, %llu frame%s), over the %s of --max-memory; lower "
                  "the resolutions, the frames or --resolution-scale",
                  fscript::scene::bytes_text(bytes).c_str(), fscript::scene::bytes_text(most_bytes).c_str(),
                  static_cast<unsigned long long>(f), f == 1 ? "" : "s", fscript::scene::bytes_text(memory).c_str());
  l.diag.error(vrml::file_of(l.scene, at), res ? res->span : at.span, text);
  std::cerr << fscript::frontend::render_all(l.diag);
  return false;
}

int animated(const Options& o, Loaded& l, const SceneModel& model, nlohmann::json& st) {
  auto t2 = Clock::now();
  uint64_t e0 = mesh::evaluation_ns().load();
  bool world = o.format != "wrl", failed = false;
  std::vector<Track> ts = tracks(o, model);
  std::set<const vrml::Node*> skip;
  for (const auto& t : ts) skip.insert(t.node);
  uint64_t jobs = mesh_jobs(model, skip);
  for (const auto& t : ts) jobs += moves(model, t) ? static_cast<uint64_t>(t.frames) : 1;  // a still one is made once
  fscript::support::progress_expect(jobs, "frames");
  if (!stamp_scene(o, l)) return 1;
  // A shard makes only its frames; the static shapes are made by the merge.
  Meshed meshed = o.shard_part ? Meshed{} : mesh_scene(o, l.scene, model, world, o.threads, skip);
  if (meshed.failed && !o.keep_going) return 1;
  failed |= meshed.failed;
  std::map<int, std::vector<SceneModel>> models;  // per frame count
  std::vector<std::unique_ptr<mesh::FrameCache>> caches;
  std::map<const vrml::Node*, fscript::scene::Animation> animations;
  std::vector<mesh::GltfAnimation> gltf;
  nlohmann::json report_json = nlohmann::json::array();
  // The scene's standard geometry, for the live preview's scenes so far: made once, not per scene.
  std::vector<mesh::Mesh> standard;
  if (o.on_partial && world) standard = fscript::scene::standard_meshes(l.scene);
  for (const auto& t : ts) {
    if (!models.count(t.frames) && !frame_models(o, l, t.frames, models[t.frames], false)) return 1;
    const auto& ms = models[t.frames];
    int parallel = std::min(o.threads, t.frames), per = std::max(1, o.threads / parallel);
    caches.push_back(std::make_unique<mesh::FrameCache>(
        t.frames,
        [&o, &ms, t, per, world, prune = o.prune, mesher = o.mesher](size_t i, mesh::Mesh& out,
                                                                     fscript::backends::RuntimeError& err) {
          if (cancelled(o)) return err.message = "cancelled", false;
          return t.group ? fscript::scene::mesh_group(ms[i], t.index, out, err, world, per, prune, mesher)
                         : fscript::scene::mesh_shape(ms[i].shapes[t.index], out, err, world, per, prune, mesher);
        }));
    mesh::FrameCache& cache = *caches.back();
    bool still = !moves(model, t), made = true;
    std::vector<std::string> keys = from_memo(o, l.scene, t, ms, world, still, cache);
    fscript::backends::RuntimeError err;
    if (o.shard_part) {
      if (!shard_frames(o, keys, cache, err)) {
        report(o, l.scene, t.node, err);
        return 1;
      }
      continue;
    }
    if (o.merging)
      for (size_t i = 0; i < keys.size(); ++i)
        if (!keys[i].empty()) {
          std::cerr << o.path << ":" << node_line(l.scene, *t.node) << ": error: frame " << i << " of this node is in "
                    << "none of the parts (shard " << i % static_cast<size_t>(o.merging->shard.count) << " of "
                    << o.merging->shard.count << " should have made it)\n";
          return 1;
        }
    if (still && !cache.has(0)) {  // every frame as the first: made once
      mesh::Mesh first;
      made = cache.get(0, first, err);
      for (size_t i = 1; made && i < cache.size(); ++i) cache.put(i, *cache.compact(0));
    }
    // The live preview sees the scene after 1, 2, 4, ... frames: the static shapes, the animations
    // done and this one's frames so far (made coarse to fine, so they span the cycle).
    auto publish = [&](size_t cached) {
      if (!o.on_partial || !world || cached >= cache.size() || (cached & (cached - 1)) != 0) return;
      mesh::Mesh all = meshed.all();
      for (const auto& part : standard) all.append(part);
      std::vector<mesh::GltfAnimation> now = gltf;
      now.push_back(gltf_animation(l.scene, t, cache, true));
      size_t frames = now.back().frames.size();  // other threads may have added some meanwhile
      o.on_partial(mesh::encode_glb(all, now), frames, cache.size());
    };
    if (!made || !cache.fill(parallel, err, publish)) {
      if (cancelled(o)) return 1;
      report(o, l.scene, t.node, err);
      if (!o.keep_going) return 1;
      failed = true;
      continue;
    }
    for (size_t i = 0; i < keys.size(); ++i)
      if (!keys[i].empty()) o.memo->store_frame(keys[i], *cache.compact(i));
    double fraction = t.group ? model.groups[t.index].fraction : model.shapes[t.index].fraction;
    int initial = std::clamp(static_cast<int>(std::floor(fraction * t.frames)), 0, t.frames - 1);
    report_json.push_back({{"line", node_line(l.scene, *t.node)},
                           {"frames", t.frames},
                           {"triangles", cache.triangles()},
                           {"cache_bytes", cache.bytes()},
                           {"bytes_per_triangle", cache.triangles() ? double(cache.bytes()) / cache.triangles() : 0.0},
                           {"constant", cache.all_same()}});
    if (cache.all_same()) {  // nothing moves: one frame, shown as a static shape
      mesh::Mesh m;
      cache.peek(0, m);
      meshed.put(t.node, std::move(m));
      continue;
    }
    if (!world) {
      animations[t.node] = {&cache, fscript::scene::time_fields(*t.node), externally_driven(l.scene, *t.node), initial};
      continue;
    }
    gltf.push_back(gltf_animation(l.scene, t, cache, false));
  }
  st["polygonize_ms"] = ms_since(t2);
  st["evaluation_ms"] = evaluation_ms_since(e0);
  st["animations"] = report_json;
  if (o.shard_part) return 0;  // main.cpp writes the part
  auto t3 = Clock::now();
  bool written = false;
  if (world) {
    std::string error;
    written = fscript::support::write_file_atomic(o.output, mesh::encode_glb(picture(meshed, l.scene), gltf), error);
    if (!written) std::cerr << "error: " << error << "\n";
  } else {
    written = write_text(o, fscript::scene::export_vrml(l.scene, meshed.by_node, animations, o.output));
  }
  st["write_ms"] = ms_since(t3);
  return !written || failed ? 1 : 0;
}

}  // namespace fvrml_run
