#pragma once
// Fields of the scene: a shape's FRep with its 3D texture (displacement: f + d); an FTransform
// combining implicit children (set operations, blends, analytical operations) or parametric
// children (its analytical operation on each coordinate); both moved by the FTransform's affine
// fields (translation, rotation, scale, scaleOrientation, center) at its t.
#include <memory>
#include <mutex>
#include <vector>

#include "engine/mesh/field.h"
#include "engine/mesh/local_field.h"
#include "engine/mesh/parametric.h"
#include "engine/scene/scene_model.h"

namespace fscript::scene {

// The FTransform's affine fields as a matrix (VRML97 Transform order): each field is FScript
// components of t, numbers (a file that declares them SFVec3f / SFRotation), or the default.
bool group_matrix(const Group& g, Mat4& out, backends::RuntimeError& err);
// Inverse of an affine matrix; false when it is singular (a zero scale).
bool invert_affine(const Mat4& m, Mat4& out);

class ShapeField : public mesh::Field {
 public:
  explicit ShapeField(const Shape& s) : s_(s), geometry_t_(s.geometry.t), texture_t_(s.texture ? s.texture->t : 0) {}
  // The shape at `fraction` of its animation's cycle (its nodes' t over their timeSpan), not at the
  // model's time: what the diagnostics check an animation's frames with.
  ShapeField(const Shape& s, double fraction);
  bool eval(const float* x, const float* y, const float* z, size_t n, float* out,
            backends::RuntimeError& err) const override;
  bool eval_rows(const float* x, size_t count, const float* y, const float* z, size_t rows, float* out,
                 backends::RuntimeError& err) const override;
  math::Interval bound(const mesh::Box3& b) const override;
  void bounds(const mesh::Box3* boxes, size_t n, math::Interval* out) const override;
  bool can_bound() const override;
  bool has_gradient() const override;  // the FRep's, when it has one and no 3D texture displaces it
  bool eval_gradient(const float* x, const float* y, const float* z, size_t n, float* const out[4],
                     backends::RuntimeError& err) const override;
  // The FRep's tape simplified for the box (not under a 3D texture, which takes points whole).
  std::shared_ptr<const mesh::Field> local(const mesh::Box3& b) const override;
  void bounds_and_locals(const mesh::Box3* boxes, size_t n, math::Interval* out, const mesh::WantsLocal& wants,
                         std::shared_ptr<const mesh::Field>* locals) const override;
  void expect_points(uint64_t points) const override;
  const ir::IntervalTape* value_tape() const override;  // the FRep's (not a 3D texture's)
  const ir::IntervalTape* gradient_tape() const override;
  ~ShapeField() override;

 private:
  const mesh::LocalTapes* tapes() const;  // nullptr: a 3D texture, or no intervals
  const Shape& s_;
  double geometry_t_, texture_t_;  // the t the FRep and the 3D texture are taken at
  mutable std::once_flag local_once_;
  mutable std::unique_ptr<mesh::LocalTapes> local_;  // made at the first local()
};

class GroupField : public mesh::Field {
 public:
  GroupField(const SceneModel& m, int group);
  bool eval(const float* x, const float* y, const float* z, size_t n, float* out,
            backends::RuntimeError& err) const override;
  bool eval_rows(const float* x, size_t count, const float* y, const float* z, size_t rows, float* out,
                 backends::RuntimeError& err) const override;
  math::Interval bound(const mesh::Box3& b) const override;
  bool can_bound() const override;
  // Set operations and blends by the chain rule over the children's gradients (not an analytical
  // operation: its script's gradient in f, g, ... is not built).
  bool has_gradient() const override;
  bool eval_gradient(const float* x, const float* y, const float* z, size_t n, float* const out[4],
                     backends::RuntimeError& err) const override;
  void part_tapes(bool gradient, std::vector<const ir::IntervalTape*>& out) const override;
  // False (with a message) when a child cannot be part of an implicit field (a parametric shape).
  bool valid(std::string& why) const;
  std::array<double, 6> box() const;     // the union of the children's boxes
  std::array<int, 3> cells() const;      // the finest child resolution
  const Shape* first_shape() const;      // for the colour of the result
  const std::vector<const Shape*>& shapes() const { return shapes_; }  // every shape below

 private:
  // An analytical operation (the FTransform's operation as a script) over the children's values.
  bool eval_operator(const float* x, const float* y, const float* z, size_t n, float* out,
                     backends::RuntimeError& err) const;
  // Points into the FTransform's own frame, where its children live (kept in `room`, 3n floats;
  // nothing to do when it does not move them).
  void to_local(const float*& x, const float*& y, const float*& z, size_t n, float* room) const;
  // The set operation and its blend parameters (a0, a1, a2; sign +1 for blend_union), read once.
  struct SetOp {
    enum Kind { Union, Intersection, Subtraction, Blend } kind = Union;
    double sign = -1, a0 = 0, a1 = 1, a2 = 1;
  };
  SetOp set_op() const;
  // The set operation folded over the children's values: the first in out, the others in rest.
  void fold(float* out, const float* rest, size_t n) const;
  // One step of that fold with gradients: out (f, df/dx, df/dy, df/dz) combined with g.
  void fold_gradient(float* const out[4], const float* const g[4], size_t n) const;
  const SceneModel& m_;
  const Group& g_;
  std::vector<std::unique_ptr<mesh::Field>> kids_;
  std::vector<const Shape*> shapes_;     // every shape below, for box and resolution
  std::string invalid_;
  Mat4 matrix_ = identity(), inverse_ = identity();
  bool moved_ = false;                   // matrix_ is not the identity
};

// An FTransform over parametric children: x = op(x1, x2, ...) with the same for y and z, every
// child sampled at the same (u, v, w) (they share the FTransform's `parameters`), then moved by
// the affine fields.
class GroupParametric : public mesh::ParametricField {
 public:
  GroupParametric(const SceneModel& m, int group);
  bool eval(const float* u, const float* v, const float* w, size_t n, float* x, float* y, float* z,
            backends::RuntimeError& err) const override;
  bool valid(std::string& why) const;
  const Shape* first_shape() const { return shapes_.empty() ? nullptr : shapes_.front(); }
  const std::vector<const Shape*>& shapes() const { return shapes_; }  // every shape below
  ShapeKind kind() const;                // the children's highest dimension
  std::array<double, 6> domain() const;  // the first child's (u, v, w) domain
  std::array<int, 3> intervals() const;  // the finest child resolution

 private:
  const Group& g_;
  std::vector<std::unique_ptr<mesh::ParametricField>> kids_;
  std::vector<const Shape*> shapes_;
  std::string invalid_;
  Mat4 matrix_ = identity();
};

// True when every shape below the group is parametric (false: all implicit, or mixed).
bool parametric_group(const SceneModel& m, int group);

}  // namespace fscript::scene
