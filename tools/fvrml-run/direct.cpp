// Pictures with implicit shapes drawn without meshing: which shapes go that way, their fields,
// colours, materials and world boxes, and the frame's picture from them and the meshes.
#include <iostream>

#include "engine/render/direct.h"
#include "engine/scene/shape_field.h"
#include "engine/scene/shape_mesh.h"
#include "tools/fvrml-run/run.h"

namespace fvrml_run {
namespace {

using fscript::render::DirectShape;
using fscript::scene::Mat4;

// A shape whose intervals leave more than this share of its box's cells open is meshed: its direct
// picture would probe most steps of most rays.
constexpr double kMostOpen = 0.2;

// The world box of `box` (the shape's coordinates) moved by `m`.
std::array<double, 6> world_box(const Mat4& m, const std::array<double, 6>& box) {
  std::array<double, 6> out{HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL};
  for (int k = 0; k < 8; ++k) {
    double p[3] = {box[k & 1], box[2 + ((k >> 1) & 1)], box[4 + ((k >> 2) & 1)]};
    for (int r = 0; r < 3; ++r) {
      double v = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
      out[2 * r] = std::min(out[2 * r], v), out[2 * r + 1] = std::max(out[2 * r + 1], v);
    }
  }
  return out;
}

// Adds a shape drawn by `field` over `box`, coloured and lit as `look` (the shape, or an
// FTransform's first shape), moved to the world by `to_world`; false on a runtime error (printed).
bool add(const Options& o, const vrml::Scene& scene, const vrml::Node* node, std::unique_ptr<mesh::Field> field,
         const std::array<double, 6>& box, const fscript::scene::Shape* look, const Mat4& to_world, DirectParts& out) {
  fscript::render::Occupancy where;
  fscript::backends::RuntimeError err;
  if (!fscript::render::occupied(*field, box, where, err)) return report(o, scene, node, err), false;
  if (where.open > kMostOpen) return true;  // the intervals say too little: meshed
  out.meshed_no_more.insert(node);
  if (!where.extent) return true;  // nothing of it can show
  const std::array<double, 6>& extent = *where.extent;
  DirectShape d;
  d.field = field.get();
  d.box = box;
  d.to_world = to_world;
  d.extent = world_box(to_world, extent);
  for (const auto& p : where.outline) {
    mesh::Vec3 q;
    for (int r = 0; r < 3; ++r)
      q[r] =
          static_cast<float>(to_world[r] * p[0] + to_world[4 + r] * p[1] + to_world[8 + r] * p[2] + to_world[12 + r]);
    d.outline.push_back(q);
  }
  if (look) {
    if (!fscript::scene::shape_material(*look, d.material, err)) return report(o, scene, node, err), false;
    if (look->colour)
      d.colour = [look](const std::vector<std::array<float, 3>>& points, std::vector<std::array<float, 3>>& rgb,
                        fscript::backends::RuntimeError& err) {
        return fscript::scene::colour_points(*look, points, nullptr, rgb, err);
      };
  }
  out.fields.push_back(std::move(field));
  out.shapes.push_back(std::move(d));
  out.nodes.push_back(node);
  return true;
}

}  // namespace

bool direct_parts(const Options& o, const vrml::Scene& scene, const SceneModel& model, DirectParts& out,
                  const std::set<const vrml::Node*>& skip) {
  if (!o.direct_pictures) return true;
  for (const auto& s : model.shapes) {
    if (s.group >= 0 || skip.count(s.fshape) || s.kind != fscript::scene::ShapeKind::Implicit || !s.geometry.kernel)
      continue;
    auto field = std::make_unique<fscript::scene::ShapeField>(s);
    if (!field->can_bound()) continue;  // every step of every ray would be evaluated: meshed instead
    if (!add(o, scene, s.fshape, std::move(field), s.domain, &s, s.transform, out)) return false;
  }
  for (size_t g = 0; g < model.groups.size(); ++g) {
    const auto& group = model.groups[g];
    if (group.parent >= 0 || skip.count(group.node) || fscript::scene::parametric_group(model, static_cast<int>(g)))
      continue;
    auto field = std::make_unique<fscript::scene::GroupField>(model, static_cast<int>(g));
    std::string why;
    if (!field->valid(why) || !field->can_bound()) continue;  // meshed, which reports what is wrong
    const fscript::scene::Shape* first = field->first_shape();
    std::array<double, 6> box = field->box();
    if (!add(o, scene, group.node, std::move(field), box, first, first ? first->transform : fscript::scene::identity(),
             out))
      return false;
  }
  return true;
}

bool draw(const Options& o, const vrml::Scene& scene, Meshed& meshed, const DirectParts& direct,
          const fscript::render::RenderOptions& ro, std::vector<uint8_t>& px) {
  fscript::backends::RuntimeError err;
  size_t failed = 0;
  if (fscript::render::render(picture(meshed, scene), direct.shapes, ro, px, err, failed)) return true;
  report(o, scene, direct.nodes[failed], err);
  return false;
}

}  // namespace fvrml_run
