// fvrml-meshdiff A [B]: the topology of a mesh (components, inside-out ones, watertight, ...), and
// with B the distances between the two, as one JSON object.
#include <CLI/CLI.hpp>
#include <iostream>
#include <nlohmann/json.hpp>

#include "engine/mesh/distance.h"
#include "engine/mesh/mesh_read.h"
#include "runtime/support/version.h"

namespace {

nlohmann::json describe(const fscript::mesh::Mesh& m) {
  auto t = fscript::mesh::topology(m);
  return {{"vertices", m.positions.size()}, {"triangles", m.triangles.size()},
          {"watertight", t.watertight},     {"manifold", t.manifold},
          {"oriented", t.oriented},         {"euler", t.euler},
          {"components", t.components},     {"inverted_components", t.inverted_components},
          {"normals", !m.normals.empty()}};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "fvrml-meshdiff: the topology of a mesh, and Hausdorff and Chamfer distances to a second (PLY, OBJ, STL)"};
  app.set_version_flag("--version", fscript::support::version_line("fvrml-meshdiff"));
  std::string a_path, b_path;
  app.add_option("A", a_path, "the first mesh (distances relative to its bounding-box diagonal)")->required();
  app.add_option("B", b_path, "the second mesh (without it: the topology of A alone)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  fscript::mesh::Mesh a, b;
  std::string error;
  if (!fscript::mesh::read_mesh(a_path, a, error)) {
    std::cerr << a_path << ": error: " << error << "\n";
    return 1;
  }
  if (b_path.empty()) {
    std::cout << nlohmann::json{{"a", describe(a)}}.dump(2) << "\n";
    return 0;
  }
  if (!fscript::mesh::read_mesh(b_path, b, error)) {
    std::cerr << b_path << ": error: " << error << "\n";
    return 1;
  }
  auto d = fscript::mesh::mesh_distances(a, b);
  double diag = fscript::mesh::bbox_diagonal(a);
  auto rel = [&](double v) { return diag > 0 ? v / diag : 0.0; };
  nlohmann::json j = {{"hausdorff", d.hausdorff}, {"hausdorff_relative", rel(d.hausdorff)},
                      {"chamfer", d.chamfer},     {"chamfer_relative", rel(d.chamfer)},
                      {"bbox_diagonal_a", diag},  {"a", describe(a)},
                      {"b", describe(b)}};
  std::cout << j.dump(2) << "\n";
  return 0;
}
