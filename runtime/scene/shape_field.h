#pragma once
// Implicit fields of the scene: a shape's FRep with its 3D texture (displacement: f + d), and an
// FTransform combining its children (set operations, blends, analytical operations).
#include <memory>
#include <vector>

#include "runtime/mesh/field.h"
#include "runtime/scene/scene_model.h"

namespace fscript::scene {

class ShapeField : public mesh::Field {
 public:
  explicit ShapeField(const Shape& s) : s_(s) {}
  bool eval(const float* x, const float* y, const float* z, size_t n, float* out,
            backend::RuntimeError& err) const override;

 private:
  const Shape& s_;
};

class GroupField : public mesh::Field {
 public:
  GroupField(const SceneModel& m, int group);
  bool eval(const float* x, const float* y, const float* z, size_t n, float* out,
            backend::RuntimeError& err) const override;
  // False (with a message) when a child cannot be part of an implicit field (a parametric shape).
  bool valid(std::string& why) const;
  std::array<double, 6> box() const;     // the union of the children's boxes
  std::array<int, 3> cells() const;      // the finest child resolution
  const Shape* first_shape() const;      // for the colour of the result

 private:
  const SceneModel& m_;
  const Group& g_;
  std::vector<std::unique_ptr<mesh::Field>> kids_;
  std::vector<const Shape*> shapes_;     // every shape below, for box and resolution
  std::string invalid_;
};

}  // namespace fscript::scene
