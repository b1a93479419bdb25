#pragma once
// Meshes kept from one run of the live preview to the next, so a save that changes one shape does
// not polygonize the others again. A mesh is found by a key that holds everything it is made from:
// the node as the VRML97 writer writes it (with the scene's PROTOs), the model's resolved numbers
// (domain, resolution, time, transform) and the options.
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "engine/mesh/frame_cache.h"
#include "tools/fvrml-run/run.h"

namespace fvrml_run {

// The key of model.shapes[i] or of the top-level FTransform model.groups[i].
std::string shape_key(const Options& o, const vrml::Scene& scene, const SceneModel& model, size_t i, bool world);
std::string group_key(const Options& o, const vrml::Scene& scene, const SceneModel& model, size_t i, bool world);

class MeshMemo {
 public:
  std::optional<mesh::Mesh> find(const std::string& key);
  void store(const std::string& key, const mesh::Mesh& m);
  // Frames of animations, as the frame cache holds them.
  std::optional<mesh::CompactMesh> find_frame(const std::string& key);
  void store_frame(const std::string& key, const mesh::CompactMesh& m);

  // A run ended well: what it did not use is dropped (a failed run keeps everything).
  void sweep();
  struct Counts {
    size_t reused = 0, made = 0;  // meshes and frames of the last run
  };
  Counts counts();
  void reset_counts();

 private:
  template <class T>
  struct Entry {
    T mesh;
    bool used = true;
  };
  template <class T>
  std::optional<T> take(std::map<std::string, Entry<T>>& entries, const std::string& key);
  template <class T>
  void keep(std::map<std::string, Entry<T>>& entries, const std::string& key, const T& m);

  std::mutex lock_;
  std::map<std::string, Entry<mesh::Mesh>> meshes_;
  std::map<std::string, Entry<mesh::CompactMesh>> frames_;
  Counts counts_;
};

}  // namespace fvrml_run
