// The profiling wrapper of a field: forwards every ask to the field it wraps, timing evaluations
// and bounds, and wraps the regions' fields it hands out in turn.
#include "engine/mesh/field_profile.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "engine/mesh/marching_tetrahedra.h"

namespace fscript::mesh {
namespace {

uint64_t ns_since(std::chrono::steady_clock::time_point t0) {
  return static_cast<uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count());
}

// The operations of every tape `f` runs for a value (or a gradient): what one point costs it.
uint32_t operations(const Field& f, bool gradient) {
  std::vector<const ir::IntervalTape*> tapes;
  f.part_tapes(gradient, tapes);
  size_t n = 0;
  for (const ir::IntervalTape* t : tapes) n += t->operations();
  return static_cast<uint32_t>(n);
}

// What one field does while its job runs (counted from many threads at once).
struct LiveRecord {
  std::shared_ptr<const Field> field;
  bool has_box = false;
  Box3 box{};
  uint32_t value_length = 0;                 // operations of its value tape (0: it runs no tape)
  std::atomic<uint32_t> gradient_length{0};  // of its gradient tape, once one ran
  std::atomic<uint64_t> points{0}, point_ns{0}, gradients{0}, gradient_ns{0}, bounds{0}, bound_ns{0};
};

// The fields of one job: made as the mesher asks for them, copied into the profile at its end.
class JobRecords {
 public:
  explicit JobRecords(FieldProfile& p) : profile(p) {}
  std::shared_ptr<const Field> wrap(std::shared_ptr<const Field> f, const Box3* box);
  // The records with their tapes copied (shared where fields share one), the fields let go.
  std::deque<FieldRecord> finish();
  FieldProfile& profile;

 private:
  std::mutex lock_;
  std::deque<LiveRecord> live_;  // a deque: records stay where they are while more are added
};

class ProfiledField : public Field {
 public:
  ProfiledField(std::shared_ptr<const Field> inner, LiveRecord& rec, JobRecords& job)
      : inner_(std::move(inner)), rec_(rec), job_(job) {}

  bool eval(const float* x, const float* y, const float* z, size_t n, float* out,
            backends::RuntimeError& err) const override {
    auto t0 = std::chrono::steady_clock::now();
    bool ok = inner_->eval(x, y, z, n, out, err);
    count(rec_.points, rec_.point_ns, n, t0);
    job_.profile.add_points(x, y, n, rec_.value_length, true);
    return ok;
  }
  bool eval_rows(const float* x, size_t count_, const float* y, const float* z, size_t rows, float* out,
                 backends::RuntimeError& err) const override {
    auto t0 = std::chrono::steady_clock::now();
    bool ok = inner_->eval_rows(x, count_, y, z, rows, out, err);
    count(rec_.points, rec_.point_ns, count_ * rows, t0);
    for (size_t r = 0; r < rows; ++r) job_.profile.add_points(x, y + r, count_, rec_.value_length, true, count_);
    return ok;
  }
  math::Interval bound(const Box3& b) const override {
    auto t0 = std::chrono::steady_clock::now();
    math::Interval v = inner_->bound(b);
    count(rec_.bounds, rec_.bound_ns, 1, t0);
    return v;
  }
  void bounds(const Box3* boxes, size_t n, math::Interval* out) const override {
    auto t0 = std::chrono::steady_clock::now();
    inner_->bounds(boxes, n, out);
    count(rec_.bounds, rec_.bound_ns, n, t0);
  }
  bool can_bound() const override { return inner_->can_bound(); }
  bool has_gradient() const override { return inner_->has_gradient(); }
  bool eval_gradient(const float* x, const float* y, const float* z, size_t n, float* const out[4],
                     backends::RuntimeError& err) const override {
    auto t0 = std::chrono::steady_clock::now();
    bool ok = inner_->eval_gradient(x, y, z, n, out, err);
    count(rec_.gradients, rec_.gradient_ns, n, t0);
    uint32_t len = rec_.gradient_length.load(std::memory_order_relaxed);
    if (!len) {  // the gradient's tapes are made by its first evaluation
      len = operations(*inner_, true);
      rec_.gradient_length.store(len, std::memory_order_relaxed);
    }
    job_.profile.add_points(x, y, n, len, false);
    return ok;
  }
  std::shared_ptr<const Field> local(const Box3& b) const override {
    std::shared_ptr<const Field> l = inner_->local(b);
    return l ? job_.wrap(std::move(l), &b) : nullptr;
  }
  void bounds_and_locals(const Box3* boxes, size_t n, math::Interval* out, const WantsLocal& wants,
                         std::shared_ptr<const Field>* locals) const override {
    auto t0 = std::chrono::steady_clock::now();
    inner_->bounds_and_locals(boxes, n, out, wants, locals);
    count(rec_.bounds, rec_.bound_ns, n, t0);
    for (size_t i = 0; i < n; ++i)
      if (locals[i]) locals[i] = job_.wrap(std::move(locals[i]), &boxes[i]);
  }
  void expect_points(uint64_t points) const override { inner_->expect_points(points); }
  const ir::IntervalTape* value_tape() const override { return inner_->value_tape(); }
  const ir::IntervalTape* gradient_tape() const override { return inner_->gradient_tape(); }
  void part_tapes(bool gradient, std::vector<const ir::IntervalTape*>& out) const override {
    inner_->part_tapes(gradient, out);
  }

 private:
  static void count(std::atomic<uint64_t>& what, std::atomic<uint64_t>& ns, size_t n,
                    std::chrono::steady_clock::time_point t0) {
    what.fetch_add(n, std::memory_order_relaxed);
    ns.fetch_add(ns_since(t0), std::memory_order_relaxed);
  }
  std::shared_ptr<const Field> inner_;
  LiveRecord& rec_;
  JobRecords& job_;
};

std::shared_ptr<const Field> JobRecords::wrap(std::shared_ptr<const Field> f, const Box3* box) {
  LiveRecord* rec;
  {
    std::lock_guard<std::mutex> hold(lock_);
    rec = &live_.emplace_back();
  }
  if (box) rec->has_box = true, rec->box = *box;
  rec->value_length = operations(*f, false);
  rec->field = f;
  return std::make_shared<ProfiledField>(std::move(f), *rec, *this);
}

std::deque<FieldRecord> JobRecords::finish() {
  std::map<const ir::IntervalTape*, std::shared_ptr<const ir::IntervalTape>> copies;
  auto copy = [&](const ir::IntervalTape* t) -> std::shared_ptr<const ir::IntervalTape> {
    if (!t) return nullptr;
    auto& c = copies[t];
    if (!c) c = std::make_shared<const ir::IntervalTape>(*t);
    return c;
  };
  std::deque<FieldRecord> out;
  for (LiveRecord& l : live_) {
    FieldRecord& r = out.emplace_back();
    r.has_box = l.has_box, r.box = l.box;
    r.points = l.points.load(), r.point_ns = l.point_ns.load();
    r.gradients = l.gradients.load(), r.gradient_ns = l.gradient_ns.load();
    r.bounds = l.bounds.load(), r.bound_ns = l.bound_ns.load();
    std::vector<const ir::IntervalTape*> tapes;
    l.field->part_tapes(false, tapes);
    for (const ir::IntervalTape* t : tapes) r.value.push_back(copy(t));
    tapes.clear();
    if (r.gradients) l.field->part_tapes(true, tapes);
    for (const ir::IntervalTape* t : tapes) r.gradient.push_back(copy(t));
    l.field.reset();
  }
  return out;
}

}  // namespace

void FieldProfile::begin(const std::array<double, 6>& box, const std::array<int, 3>& cells) {
  std::call_once(begun_, [&] {
    width_ = std::max(1, cells[0]), height_ = std::max(1, cells[1]);
    for (int a = 0; a < 2; ++a)
      lo_[a] = box[2 * a], scale_[a] = (a ? height_ : width_) / std::max(box[2 * a + 1] - box[2 * a], 1e-30);
    size_t n = static_cast<size_t>(width_) * static_cast<size_t>(height_);
    work_ = std::make_unique<std::atomic<uint64_t>[]>(n);
    value_ops_ = std::make_unique<std::atomic<uint64_t>[]>(n);
    values_ = std::make_unique<std::atomic<uint64_t>[]>(n);
  });
}

int FieldProfile::column(float v, int axis) const {
  double c = (static_cast<double>(v) - lo_[axis]) * scale_[axis];
  int most = axis == 0 ? width_ - 1 : height_ - 1;
  return std::isnan(c) ? 0 : static_cast<int>(std::clamp(c, 0.0, static_cast<double>(most)));
}

void FieldProfile::add_points(const float* x, const float* y, size_t n, uint32_t ops, bool value, size_t row) {
  if (!width_) return;
  for (size_t i = 0; i < n; ++i) {
    size_t k = at(column(x[i], 0), height_ - 1 - column(y[i / row], 1));
    work_[k].fetch_add(ops, std::memory_order_relaxed);
    if (!value) continue;
    value_ops_[k].fetch_add(ops, std::memory_order_relaxed);
    values_[k].fetch_add(1, std::memory_order_relaxed);
  }
}

void FieldProfile::add_prune(const PruneStats& s) {
  std::lock_guard<std::mutex> hold(lock_);
  prune_.add(s);
}

void FieldProfile::add_records(std::deque<FieldRecord>&& done) {
  std::lock_guard<std::mutex> hold(lock_);
  for (FieldRecord& r : done) records_.push_back(std::move(r));
}

bool polygonize_profiled(const ImplicitJob& job, Mesh& out, backends::RuntimeError& err) {
  FieldProfile& p = *job.profile;
  p.begin(job.box, job.cells);
  ir::KeepSources sources;
  // The gradient's kernel and tape are made (and compiled) before the clocks start: compiling is
  // not evaluation, and would be charged to the first region that asks.
  if (job.mesher.kind == Mesher::DualContouring && job.field->has_gradient()) job.field->gradient_tape();
  ImplicitJob inner = job;
  JobRecords records(p);
  PruneStats st;
  bool ok;
  {
    std::shared_ptr<const Field> whole =
        records.wrap(std::shared_ptr<const Field>(job.field, [](const Field*) {}), nullptr);
    inner.field = whole.get();
    inner.profile = nullptr;
    inner.stats = &st;
    ok = polygonize(inner, out, err);
  }
  p.add_records(records.finish());
  p.add_prune(st);
  if (job.stats) *job.stats = st;
  return ok;
}

FieldProfile& Profiler::of(const void* key) {
  std::lock_guard<std::mutex> hold(lock_);
  for (auto& [k, p] : profiles_)
    if (k == key) return *p;
  profiles_.emplace_back(key, std::make_unique<FieldProfile>());
  return *profiles_.back().second;
}

}  // namespace fscript::mesh
