// Shape diagnostics (shape_diagnostics.h) from surveys (shape_survey.h): the shape's own grid
// (or a coarser one past 128 samples a side), three times its box around it for its extent, and
// sample blocks of its own grid checked for parts that pass between the samples.
#include "engine/scene/shape_diagnostics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/scene/shape_field.h"
#include "engine/scene/shape_survey.h"
#include "ir/interval_eval.h"

namespace fscript::scene {
namespace {

constexpr int kSurveyCells = 128;  // a grid finer than this is surveyed at one of at most kCoarseCells a side
constexpr int kCoarseCells = 48;
constexpr int kUnboundedCells = 16;
constexpr int kAroundCells = 48;   // the survey of three times the box, for the shape's extent
constexpr double kAround = 3;
constexpr size_t kFinerBlocks = 64;   // blocks of 8^3 samples of the own grid checked for thin parts
constexpr size_t kMissedChecked = 32;  // missed cells tried at finer resolutions
// Intervals look for parts between agreeing samples down to cells split kProofDepth times, over
// at most kProofBoxes boxes a shape (bounded in batches on the blocks' tapes: a few milliseconds,
// 6 ms for the gyroid in a ball, whose sines cost most in intervals).
constexpr int kProofDepth = 3;
constexpr uint64_t kProofBoxes = 20'000;
constexpr uint64_t kSliverShare = 1000;  // parts found by intervals alone in under 1 / this of the cells: slivers
constexpr int kFrames = 24;  // an animation is checked at these fractions of its cycle (fvrml-run's default frames)

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", std::abs(v) < 1e-12 ? 0.0 : v);
  return b;
}

std::string vec(const float* p) { return "(" + num(p[0]) + ", " + num(p[1]) + ", " + num(p[2]) + ")"; }

SurveyGrid own_grid(const Shape& s) { return {s.domain, s.resolution}; }

// The grid surveyed: the own one up to kSurveyCells a side; past it, or for a function intervals
// cannot bound (every brick is sampled: loops, calls), a coarser one.
SurveyGrid coarse(const SurveyGrid& g, bool bounded) {
  int most = std::max({g.n[0], g.n[1], g.n[2]}), cells = bounded ? kCoarseCells : kUnboundedCells;
  if (most <= (bounded ? kSurveyCells : kUnboundedCells)) return g;
  int k = (most + cells - 1) / cells;
  SurveyGrid c = g;
  for (int a = 0; a < 3; ++a) c.n[a] = std::max(1, (g.n[a] + k - 1) / k);
  return c;
}

SurveyGrid around(const SurveyGrid& g) {
  SurveyGrid r;
  for (int a = 0; a < 3; ++a) {
    double c = (g.box[2 * a] + g.box[2 * a + 1]) / 2, h = (g.box[2 * a + 1] - g.box[2 * a]) / 2 * kAround;
    r.box[2 * a] = c - h, r.box[2 * a + 1] = c + h, r.n[a] = kAroundCells;
  }
  return r;
}

// A diagnostic at `field` of node n as written (else at the node, whose field is its default).
frontend::Diagnostic at_field(const vrml::Scene& scene, const vrml::Node& n, const std::string& field,
                              frontend::Severity sev, const std::string& message) {
  const frontend::SourceFile& file = vrml::file_of(scene, n);
  const vrml::FieldSlot* slot = n.slot(field);
  // A script at its first character; other fields at their names.
  uint32_t at = !slot                 ? n.span.begin
      : slot->value.str_spans.empty() ? slot->span.begin
                                      : slot->value.str_spans[0].begin;
  frontend::LineCol pos = file.position(at);
  return frontend::located(sev, file.path(), pos, file.line_at(pos.line), message);
}

// Rounded outward to a tenth of the order of the box's largest side.
void suggest_box(const double e[6], double cell, ShapeFinding& f) {
  double most = std::max({e[1] - e[0], e[3] - e[2], e[5] - e[4]}) + 2 * cell;
  double unit = std::pow(10.0, std::floor(std::log10(most))) / 10;
  for (int a = 0; a < 3; ++a) {
    double lo = std::floor((e[2 * a] - cell) / unit) * unit, hi = std::ceil((e[2 * a + 1] + cell) / unit) * unit;
    f.center[a] = (lo + hi) / 2, f.size[a] = hi - lo;
  }
  f.has_box = true;
}

std::string box_text(const ShapeFinding& f) {
  return "bboxCenter " + field_numbers(f.center) + " bboxSize " + field_numbers(f.size);
}

// What makes NaN out of numbers, by the op that first gives it.
std::string nan_cause(ir::Op op) {
  switch (op) {
    case ir::Op::Sqrt: return "`sqrt` of a negative number";
    case ir::Op::Log: return "`log` of a negative number";
    case ir::Op::Log10: return "`log10` of a negative number";
    case ir::Op::Asin: return "`asin` of a number outside [-1, 1]";
    case ir::Op::Acos: return "`acos` of a number outside [-1, 1]";
    case ir::Op::Div: return "0 / 0 (or infinity / infinity)";
    case ir::Op::Mul: return "0 * infinity";
    case ir::Op::Add:
    case ir::Op::Sub: return "infinity - infinity";
    case ir::Op::Pow: return "`pow` of a negative number to a fractional power";
    case ir::Op::Mod: return "`%` by 0 (or of infinity)";
    default: return std::string("`") + ir::mnemonic(op) + "`";
  }
}

class Diagnoser {
 public:
  Diagnoser(const vrml::Scene& scene, const Shape& s) : scene_(scene), s_(s), field_(s), own_(own_grid(s)) {}

  std::vector<ShapeFinding> run(bool top) {
    SurveyGrid g = coarse(own_, field_.can_bound());
    if (!survey(field_, g, {}, sv_, err_) || !sv_.complete) return {};
    bool empty = sv_.inside == 0, full = sv_.inside == sv_.points;
    if ((empty || full) && g.n != own_.n && !field_.can_bound()) {
      empty = full = false;  // a coarse grid may step over what the own grid sees: no claim
    } else if ((empty || full) && g.n != own_.n) {  // ... so the own grid says
      Survey fine;
      SurveyOptions o;
      o.stop_at_inside = empty;
      if (!survey(field_, own_, o, fine, err_) || !fine.complete) return {};
      empty = fine.inside == 0, full = fine.inside == fine.points;
    }
    frames(top, empty, full);
    if (empty) this->empty();
    if (full && top) this->full();
    if (!empty && !full && top) cut();
    if (sv_.nan > 0) not_a_number();
    finer();
    return std::move(out_);
  }

 private:
  const vrml::Node& geo() const { return *s_.geometry_node; }
  frontend::Diagnostic at(const std::string& field, frontend::Severity sev, const std::string& m) const {
    return at_field(scene_, geo(), field, sev, m);
  }
  std::string samples() const {
    return std::to_string(own_.n[0]) + " x " + std::to_string(own_.n[1]) + " x " + std::to_string(own_.n[2]);
  }

  // Three times the box, surveyed once: where the shape is around its box.
  const Survey* around_box() {
    if (!around_done_) {
      around_done_ = true;
      if (!survey(field_, around(own_), {}, around_, err_) || !around_.complete) around_ok_ = false;
    }
    return around_ok_ ? &around_ : nullptr;
  }
  // The shape ends within three times its box: no sample of that box's outer layer is inside.
  bool bounded_around(ShapeFinding& f) {
    const Survey* a = around_box();
    if (!a || a->inside == 0) return false;
    for (int q = 0; q < 6; ++q)
      if (a->face_inside[q] > 0) return false;
    suggest_box(a->extent, around(own_).step(0), f);
    return true;
  }

  // Whether the shape changes along its animation: its FRep or 3D texture reads t over a timeSpan.
  bool animated() const {
    auto moves = [](const CompiledField& c) { return c.reads_t && c.span0 != c.span1; };
    return moves(s_.geometry) || (s_.texture && moves(*s_.texture));
  }

  // Empty and full across the animation: the shape at kFrames fractions of its cycle, each on the
  // grid the drawn time is surveyed on (and the own grid where that one says empty or full).
  void frames(bool top, bool drawn_empty, bool drawn_full) {
    if (!animated() || !field_.can_bound()) return;
    for (int i = 0; i < kFrames; ++i) {
      ShapeField f(s_, double(i) / kFrames);
      SurveyGrid g = coarse(own_, true);
      Survey sv;
      SurveyOptions mixed;
      mixed.stop_when_mixed = true;
      if (!survey(f, g, mixed, sv, err_) || !sv.complete) return;
      bool empty = sv.inside == 0, full = sv.inside == sv.points;
      if ((empty || full) && g.n != own_.n) {
        Survey fine;
        SurveyOptions o;
        o.stop_at_inside = empty;
        if (!survey(f, own_, o, fine, err_) || !fine.complete) return;
        empty = fine.inside == 0, full = fine.inside == fine.points;
      }
      if (empty) empty_frames_.push_back(i);
      if (full && top) full_frames_.push_back(i);
    }
    frames_checked_ = true;
    if (!drawn_empty && !empty_frames_.empty())
      some_frames(ShapeIssue::Empty, empty_frames_, "empty", "nothing is drawn then");
    if (!drawn_full && !full_frames_.empty())
      some_frames(ShapeIssue::Full, full_frames_, "full", "a solid block the size of the box is drawn then");
  }
  // "in 6 of 24 frames of its animation (fractions 0.25 to 0.458)", or "in every frame of ...".
  static std::string frames_text(const std::vector<int>& at) {
    if (at.size() == size_t(kFrames)) return "in every frame of its animation";
    std::string ranges;
    for (size_t i = 0; i < at.size();) {
      size_t j = i;
      while (j + 1 < at.size() && at[j + 1] == at[j] + 1) ++j;
      ranges += (ranges.empty() ? "" : ", ") + num(double(at[i]) / kFrames) +
          (j > i ? " to " + num(double(at[j]) / kFrames) : "");
      i = j + 1;
    }
    return "in " + std::to_string(at.size()) + " of " + std::to_string(kFrames) + " frames of its animation (" +
        (at.size() == 1 ? "fraction " : "fractions ") + ranges + ")";
  }
  void some_frames(ShapeIssue issue, const std::vector<int>& at, const char* what, const char* then) {
    ShapeFinding f;
    f.issue = issue;
    f.fraction = double(at.size()) / kFrames;
    f.diag = at_field(scene_, geo(), s_.geometry.field, frontend::Severity::Warning,
                      std::string(what) + " shape " + frames_text(at) + ": " + then);
    out_.push_back(std::move(f));
  }
  // What the drawn frame's empty or full diagnostic adds about the animation.
  std::string across(const std::vector<int>& at) const {
    return frames_checked_ ? "; the same " + frames_text(at) : "";
  }

  void empty() {
    ShapeFinding f;
    f.issue = ShapeIssue::Empty;
    std::string m = sv_.open.empty() && sv_.nan == 0
        ? "empty shape: f <= 0 everywhere in its box, so nothing is drawn"
        : "empty shape: f > 0 at none of the " + samples() + " samples of its box, so nothing is drawn";
    m += across(empty_frames_);
    if (bounded_around(f)) m += "; the shape lies outside its box: " + box_text(f) + " holds it";
    f.diag = at(s_.geometry.field, frontend::Severity::Warning, m);
    out_.push_back(std::move(f));
  }

  void full() {
    ShapeFinding f;
    f.issue = ShapeIssue::Full;
    std::string m =
        "full shape: f > 0 at every sample of its box, so it is drawn as a solid block the size of the box" +
        across(full_frames_);
    if (bounded_around(f)) m += "; the shape ends just outside the box: " + box_text(f) + " holds it";
    else m += " (f > 0 goes on past three times the box: is the sign of f the right way round? FVRML draws f >= 0)";
    f.diag = at(s_.geometry.field, frontend::Severity::Warning, m);
    out_.push_back(std::move(f));
  }

  void cut() {
    static const char* kFace[6] = {"-x", "+x", "-y", "+y", "-z", "+z"};
    std::string faces;
    int whole = 0;
    for (int q = 0; q < 6; ++q) {
      if (sv_.face_inside[q] == 0) continue;
      double share = double(sv_.face_inside[q]) / double(std::max<uint64_t>(1, sv_.face_points[q]));
      whole += sv_.face_inside[q] == sv_.face_points[q];
      faces += std::string(faces.empty() ? "" : ", ") + kFace[q] + " (" + num(100 * share) + "%)";
    }
    if (faces.empty()) return;
    ShapeFinding f;
    f.issue = whole == 6 ? ShapeIssue::InsideOut : ShapeIssue::Cut;
    if (whole == 6) {
      f.diag = at(s_.geometry.field, frontend::Severity::Warning,
                  "inside-out shape: f > 0 on all six faces of its box and <= 0 within, so the box is drawn with a "
                  "hollow; FVRML draws where f >= 0: negate f to draw the solid");
    } else if (bounded_around(f)) {
      f.diag = at("bboxSize", frontend::Severity::Warning,
                  "the box cuts the shape on its faces " + faces + "; the shape ends just outside: " + box_text(f) +
                      " holds it whole");
    } else {
      f.diag = at("bboxSize", frontend::Severity::Note,
                  "the box cuts the shape on its faces " + faces + " (the shape goes on past three times the box)");
    }
    out_.push_back(std::move(f));
  }

  void not_a_number() {
    ShapeFinding f;
    f.issue = ShapeIssue::NotANumber;
    f.fraction = double(sv_.nan) / double(sv_.points);
    std::string share = f.fraction >= 0.999 ? "all of the box"
        : f.fraction >= 0.01                ? "about " + num(100 * f.fraction) + "% of the box"
                             : std::to_string(sv_.nan) + " of the " + std::to_string(sv_.points) + " samples";
    std::string m = "f is not a number in " + share + " (the mesh has a hole there)";
    const float* p = sv_.nan_point;
    float geometry[4] = {p[0], p[1], p[2], static_cast<float>(s_.geometry.t)};
    if (origin(s_.geometry, geometry, m, f)) return out_.push_back(std::move(f));
    if (s_.texture) {
      float texture[7] = {p[0], p[1], p[2], p[0], p[1], p[2], static_cast<float>(s_.texture->t)};
      if (origin(*s_.texture, texture, m, f)) return out_.push_back(std::move(f));
    }
    f.diag = at(s_.geometry.field, frontend::Severity::Warning, m + ", e.g. at " + vec(p));
    out_.push_back(std::move(f));
  }
  // The first operation of `c` that makes NaN at `params`, as the diagnostic's place.
  bool origin(const CompiledField& c, const float* params, const std::string& m, ShapeFinding& f) {
    if (!c.intervals || c.intervals->sources().empty()) return false;
    size_t step = ir::first_nan_step(*c.intervals, params);
    if (step >= c.intervals->length() || c.intervals->sources()[step].line == 0) return false;
    const auto& where = c.intervals->sources()[step];
    const frontend::SourceFile& file = vrml::file_of(scene_, geo());
    frontend::LineCol pos{where.line, where.col};
    f.diag = frontend::located(
        frontend::Severity::Warning, file.path(), pos, file.line_at(pos.line),
        m + ": " + nan_cause(c.intervals->steps()[step].op) + " gives it here first, e.g. at " + vec(params));
    return true;
  }

  void finer();
  bool finer_block(const int lo[3], std::vector<std::array<int, 3>>& missed, uint64_t& checked);
  struct Agreeing {  // a cell whose samples (corners and centre) are all on one side
    std::array<int, 3> cell;
    bool inside;
  };
  void prove_parts(const mesh::Field& f, const std::vector<Agreeing>& cells, std::vector<std::array<int, 3>>& missed);
  uint64_t proof_boxes_ = 0;  // boxes bounded by prove_parts, for all blocks
  size_t proven_ = 0;         // cells prove_parts found a part in
  int resolving_factor(const std::vector<std::array<int, 3>>& missed);

  const vrml::Scene& scene_;
  const Shape& s_;
  ShapeField field_;
  SurveyGrid own_;
  Survey sv_, around_;
  bool around_done_ = false, around_ok_ = true;
  backends::RuntimeError err_;
  std::vector<ShapeFinding> out_;
  std::vector<int> empty_frames_, full_frames_;  // the animation's frames (of kFrames) found so
  bool frames_checked_ = false;                  // set when every frame was checked
};

// Blocks of 8^3 samples of the own grid at (up to kFinerBlocks of) the open bricks: a cell whose
// eight corners are on one side while its centre is on the other holds a part of the shape the
// samples step over (a sheet thinner than a cell, a small ball between samples).
void Diagnoser::finer() {
  if (sv_.open.empty() || !field_.can_bound()) return;  // without bounds every brick is open
  SurveyGrid g = coarse(own_, true);
  std::vector<std::array<int, 3>> missed;
  uint64_t checked = 0;
  size_t stride = std::max<size_t>(1, sv_.open.size() / kFinerBlocks);
  for (size_t b = 0; b < sv_.open.size(); b += stride) {
    int lo[3];
    for (int a = 0; a < 3; ++a) {
      double centre = g.at(a, std::min(sv_.open[b][a] + 4, g.n[a] - 1));
      int i = static_cast<int>(std::floor((centre - own_.box[2 * a]) / own_.step(a)));
      lo[a] = std::clamp(i - 4, 0, std::max(0, own_.n[a] - 8));
    }
    if (!finer_block(lo, missed, checked)) return;
  }
  // Parts only intervals find are told when they are more than slivers: where CSG parts meet at a
  // grazing angle, a few cells in ten thousand hold a thin wedge at any resolution.
  if (missed.size() == proven_ && proven_ * kSliverShare < checked) return;
  if (missed.empty()) return;
  ShapeFinding f;
  f.issue = ShapeIssue::FinerThanGrid;
  f.fraction = double(missed.size()) / double(checked);
  int k = resolving_factor(missed);
  int most = std::max({own_.n[0], own_.n[1], own_.n[2]});
  f.resolution = k > 0 ? k * most : 0;
  std::string m = "parts of the shape finer than its grid: in " + std::to_string(missed.size()) + " of the " +
      std::to_string(checked) + " cells checked, the samples at the corners miss a part of the shape that passes " +
      "through the cell";
  m += k > 0 ? "; resolution [" + std::to_string(f.resolution) + "] shows them"
             : "; even 8 times the resolution does not show them all";
  f.diag = at("resolution", frontend::Severity::Warning, m);
  out_.push_back(std::move(f));
}

bool Diagnoser::finer_block(const int lo[3], std::vector<std::array<int, 3>>& missed, uint64_t& checked) {
  int hi[3];
  for (int a = 0; a < 3; ++a) hi[a] = std::min(lo[a] + 8, own_.n[a]);
  std::vector<float> x, y, z, v;
  for (int k = lo[2]; k < hi[2]; ++k)
    for (int j = lo[1]; j < hi[1]; ++j)
      for (int i = lo[0]; i < hi[0]; ++i)
        x.push_back(own_.at(0, i)), y.push_back(own_.at(1, j)), z.push_back(own_.at(2, k));
  const size_t corners = x.size();
  std::vector<Agreeing> agree;
  auto mid = [&](int a, int i) { return static_cast<float>(own_.box[2 * a] + (i + 1.0) * own_.step(a)); };
  for (int k = lo[2]; k + 1 < hi[2]; ++k)
    for (int j = lo[1]; j + 1 < hi[1]; ++j)
      for (int i = lo[0]; i + 1 < hi[0]; ++i) x.push_back(mid(0, i)), y.push_back(mid(1, j)), z.push_back(mid(2, k));
  v.resize(x.size());
  mesh::Box3 box;  // the block's samples (its cells' centres lie within): its simplified tape holds there
  for (int a = 0; a < 3; ++a) box.lo[a] = own_.at(a, lo[a]), box.hi[a] = own_.at(a, hi[a] - 1);
  std::shared_ptr<const mesh::Field> local = field_.local(box);
  const mesh::Field& f = local ? *local : field_;
  if (!f.eval(x.data(), y.data(), z.data(), x.size(), v.data(), err_)) return false;
  const int d[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
  auto value = [&](int i, int j, int k) { return v[(size_t(k) * d[1] + size_t(j)) * d[0] + size_t(i)]; };
  size_t c = corners;
  for (int k = 0; k + 1 < d[2]; ++k)
    for (int j = 0; j + 1 < d[1]; ++j)
      for (int i = 0; i + 1 < d[0]; ++i, ++c) {
        int in = 0, nan = 0;
        for (int q = 0; q < 8; ++q) {
          float w = value(i + (q & 1), j + (q >> 1 & 1), k + (q >> 2 & 1));
          nan += std::isnan(w), in += w > 0;
        }
        if (nan) continue;
        ++checked;
        if ((in == 0 && v[c] > 0) || (in == 8 && v[c] <= 0)) missed.push_back({lo[0] + i, lo[1] + j, lo[2] + k});
        else if ((in == 0 || in == 8) && !std::isnan(v[c]))
          agree.push_back({{lo[0] + i, lo[1] + j, lo[2] + k}, in == 8});
      }
  // Only on a tape, whose bounds come in batches (a 3D texture's field bounds box by box).
  if (f.value_tape()) prove_parts(f, agree, missed);
  return true;
}

// Cells whose samples agree, where intervals prove the other side is there all the same: each
// cell's bound, then its eighths' where the bound leaves the other side possible, down to an
// eighth of a cell; a box wholly on the other side is a part between the samples (a thin sheet
// the centre missed, a second sheet). Sound bounds (rounding included) make it a proof.
void Diagnoser::prove_parts(const mesh::Field& f, const std::vector<Agreeing>& cells,
                            std::vector<std::array<int, 3>>& missed) {
  struct Piece {
    mesh::Box3 box;
    size_t cell;
  };
  std::vector<Piece> level;
  for (size_t c = 0; c < cells.size(); ++c) {
    mesh::Box3 b;
    for (int a = 0; a < 3; ++a) b.lo[a] = own_.at(a, cells[c].cell[a]), b.hi[a] = own_.at(a, cells[c].cell[a] + 1);
    level.push_back({b, c});
  }
  std::vector<uint8_t> proven(cells.size(), 0);
  std::vector<math::Interval> bounds;
  std::vector<mesh::Box3> boxes;
  for (int depth = 0; depth <= kProofDepth && !level.empty() && proof_boxes_ < kProofBoxes; ++depth) {
    boxes.clear();
    for (const Piece& p : level) boxes.push_back(p.box);
    bounds.resize(boxes.size());
    f.bounds(boxes.data(), boxes.size(), bounds.data());
    proof_boxes_ += boxes.size();
    std::vector<Piece> next;
    for (size_t q = 0; q < level.size(); ++q) {
      const Piece& p = level[q];
      const math::Interval& b = bounds[q];
      if (proven[p.cell] || b.nan) continue;
      const bool inside = cells[p.cell].inside;
      if (inside ? b.hi <= 0 : b.lo > 0) {
        proven[p.cell] = 1;
        ++proven_;
        missed.push_back(cells[p.cell].cell);
        continue;
      }
      if (inside ? b.lo > 0 : b.hi <= 0) continue;  // nothing of the other side here
      if (depth == kProofDepth) continue;
      for (int o = 0; o < 8; ++o) {
        Piece c = p;
        for (int a = 0; a < 3; ++a) {
          float m = 0.5f * (p.box.lo[a] + p.box.hi[a]);
          (o >> a & 1 ? c.box.lo[a] : c.box.hi[a]) = m;
        }
        next.push_back(c);
      }
    }
    level = std::move(next);
  }
}

// The smallest of 2, 4 and 8 times the resolution whose samples, within the missed cells, take
// both sides in nine of ten of them (0: none does).
int Diagnoser::resolving_factor(const std::vector<std::array<int, 3>>& missed) {
  const size_t n = std::min(missed.size(), kMissedChecked);
  for (int k = 2; k <= 8; k *= 2) {
    size_t resolved = 0;
    for (size_t m = 0; m < n; ++m) {
      std::vector<float> x, y, z, v;
      // The k-times grid's k^3 samples between own samples i and i + 1: j from (2i + 1) k / 2.
      for (int c = 0; c < k; ++c)
        for (int b = 0; b < k; ++b)
          for (int a = 0; a < k; ++a) {
            const int q[3] = {a, b, c};
            float p[3];
            for (int ax = 0; ax < 3; ++ax) {
              double h = own_.step(ax) / k;
              int j = (2 * missed[m][ax] + 1) * k / 2 + q[ax];
              p[ax] = static_cast<float>(own_.box[2 * ax] + (j + 0.5) * h);
            }
            x.push_back(p[0]), y.push_back(p[1]), z.push_back(p[2]);
          }
      v.resize(x.size());
      if (!field_.eval(x.data(), y.data(), z.data(), x.size(), v.data(), err_)) return 0;
      bool in = false, out = false;
      for (float w : v) in |= w > 0, out |= w <= 0;
      resolved += in && out;
    }
    if (10 * resolved >= 9 * n) return k;
  }
  return 0;
}

}  // namespace

std::string field_numbers(const std::array<double, 3>& v) { return num(v[0]) + " " + num(v[1]) + " " + num(v[2]); }

const char* issue_name(ShapeIssue i) {
  switch (i) {
    case ShapeIssue::Empty: return "empty";
    case ShapeIssue::Full: return "full";
    case ShapeIssue::InsideOut: return "inside-out";
    case ShapeIssue::Cut: return "cut";
    case ShapeIssue::NotANumber: return "nan";
    case ShapeIssue::FinerThanGrid: return "finer";
  }
  return "";
}

std::vector<ShapeFinding> diagnose_shape(const vrml::Scene& scene, const Shape& s, bool top) {
  if (s.kind != ShapeKind::Implicit || !s.geometry.kernel || !s.geometry_node) return {};
  return Diagnoser(scene, s).run(top);
}

std::vector<ShapeFinding> diagnose_scene(const vrml::Scene& scene, const SceneModel& model) {
  std::vector<ShapeFinding> all;
  for (const Shape& s : model.shapes)
    for (ShapeFinding& f : diagnose_shape(scene, s, s.group < 0)) f.node = s.geometry_node, all.push_back(std::move(f));
  return all;
}

frontend::Diagnostic runtime_diagnostic(const vrml::Scene& scene, const vrml::Node& n,
                                        const backends::RuntimeError& err, frontend::Severity sev,
                                        const std::string& prefix, const std::string& path) {
  const frontend::SourceFile& file = vrml::file_of(scene, n);
  frontend::LineCol at = err.line ? frontend::LineCol{err.line, std::max(err.col, 1u)} : file.position(n.span.begin);
  return frontend::located(sev, path.empty() ? file.path() : path, at, file.line_at(at.line), prefix + err.message);
}

}  // namespace fscript::scene
