// Part files of sharded animations (shard.h): a magic line, a JSON header (where and how the shard
// ran, the scene's hash, which shard), then each frame's key and compact mesh, then an end mark.
#include "tools/fvrml-run/shard.h"

#include <cstdlib>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "runtime/support/bytes.h"
#include "runtime/support/files.h"

namespace fvrml_run {
namespace {

constexpr char kMagic[] = "FVRML-PART 2\n";
constexpr char kEnd[] = "END\n";
constexpr int kMaxShards = 10000;

// The part's scalars and arrays, and its three-float vectors.
struct Writer : fscript::support::ByteWriter {
  void put_vec3(const mesh::Vec3& v) {
    for (float f : v) put(f);
  }
};

struct Reader : fscript::support::ByteReader {
  mesh::Vec3 get_vec3() { return {get<float>(), get<float>(), get<float>()}; }
};

void put_material(Writer& w, const std::optional<mesh::Material>& mat) {
  w.put<uint8_t>(mat.has_value());
  if (!mat) return;
  for (const mesh::Vec3& v : {mat->diffuse, mat->emissive, mat->specular}) w.put_vec3(v);
  for (float f : {mat->ambient_intensity, mat->shininess, mat->transparency}) w.put(f);
}

std::optional<mesh::Material> get_material(Reader& r) {
  if (!r.get<uint8_t>()) return std::nullopt;
  mesh::Material mat;
  mat.diffuse = r.get_vec3(), mat.emissive = r.get_vec3(), mat.specular = r.get_vec3();
  mat.ambient_intensity = r.get<float>(), mat.shininess = r.get<float>(), mat.transparency = r.get<float>();
  return mat;
}

void put_mesh(Writer& w, const mesh::CompactMesh& m) {
  w.put_vec3(m.origin);
  w.put_vec3(m.step);
  w.put(m.triangles);
  w.put(m.vertices);
  w.put_vector(m.positions);
  w.put_vector(m.normals);
  w.put_vector(m.colours);
  w.put_vector(m.indices);
  w.put_vector(m.polyline_sizes);
  put_material(w, m.material);
}

mesh::CompactMesh get_mesh(Reader& r) {
  mesh::CompactMesh m;
  m.origin = r.get_vec3();
  m.step = r.get_vec3();
  m.triangles = r.get<uint32_t>();
  m.vertices = r.get<uint32_t>();
  m.positions = r.get_vector<uint16_t>();
  m.normals = r.get_vector<uint16_t>();
  m.colours = r.get_vector<uint8_t>();
  m.indices = r.get_vector<uint8_t>();
  m.polyline_sizes = r.get_vector<uint32_t>();
  m.material = get_material(r);
  return m;
}

void put_whole(Writer& w, const mesh::Mesh& m) {
  w.put_vector(m.positions);
  w.put_vector(m.normals);
  w.put_vector(m.colours);
  w.put_vector(m.params);
  w.put_vector(m.triangles);
  w.put<uint64_t>(m.polylines.size());
  for (const auto& line : m.polylines) w.put_vector(line);
  put_material(w, m.material);
}

mesh::Mesh get_whole(Reader& r) {
  mesh::Mesh m;
  m.positions = r.get_vector<mesh::Vec3>();
  m.normals = r.get_vector<mesh::Vec3>();
  m.colours = r.get_vector<mesh::Vec3>();
  m.params = r.get_vector<mesh::Vec3>();
  m.triangles = r.get_vector<std::array<uint32_t, 3>>();
  uint64_t lines = r.get<uint64_t>();
  for (uint64_t i = 0; i < lines && r.ok; ++i) m.polylines.push_back(r.get_vector<uint32_t>());
  m.material = get_material(r);
  return m;
}

bool shard_numbers(long k, long m, Shard& out, std::string& error) {
  if (m < 1 || m > kMaxShards || k < 0 || k >= m) {
    error = "--shard wants K/M with 0 <= K < M <= " + std::to_string(kMaxShards) + ", got " + std::to_string(k) + "/" +
        std::to_string(m);
    return false;
  }
  out = {static_cast<int>(k), static_cast<int>(m)};
  return true;
}

bool whole_number(const char* s, long& v) {
  if (!s || !*s) return false;
  char* end = nullptr;
  v = std::strtol(s, &end, 10);
  return *end == '\0';
}

}  // namespace

bool parse_shard(const std::string& text, Shard& out, std::string& error) {
  long k = 0, m = 0, first = 0;
  if (text == "auto") {
    const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
    const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
    if (!whole_number(id, k) || !whole_number(count, m)) {
      error =
          "--shard auto reads SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT, which are not set (run it in an "
          "sbatch --array job, or give --shard K/M)";
      return false;
    }
    // FVRML_SHARDS=M: the job's shard count, for a rerun of some of its tasks (sbatch --array=2
    // runs one task, whose SLURM_ARRAY_TASK_COUNT is 1); task K is then shard K.
    if (long shards = 0; whole_number(std::getenv("FVRML_SHARDS"), shards)) return shard_numbers(k, shards, out, error);
    if (const char* min = std::getenv("SLURM_ARRAY_TASK_MIN"); min && !whole_number(min, first)) first = 0;
    return shard_numbers(k - first, m, out, error);
  }
  size_t slash = text.find('/');
  if (slash == std::string::npos || !whole_number(text.substr(0, slash).c_str(), k) ||
      !whole_number(text.substr(slash + 1).c_str(), m)) {
    error = "--shard wants K/M (shard K of M, from 0) or auto, got '" + text + "'";
    return false;
  }
  return shard_numbers(k, m, out, error);
}

uint64_t scene_files_hash(const std::vector<std::string>& files) {
  uint64_t h = 1469598103934665603ull;
  for (const std::string& f : files) {
    std::string text, error;
    if (!fscript::support::read_file(f, text, error)) text = "unreadable " + f;
    text += '\0';
    for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  }
  return h;
}

bool write_part(const std::string& path, const Part& p, std::string& error) {
  nlohmann::json header = {{"cwd", p.cwd},
                           {"args", p.args},
                           {"scene_hash", p.scene_hash},
                           {"shard", p.shard.index},
                           {"of", p.shard.count},
                           {"frames", p.frames.size()},
                           {"whole_frames", p.whole_frames.size()},
                           {"slabs", p.slabs.size()}};
  Writer w;
  w.out = kMagic;
  w.put_string(header.dump());
  for (const PartFrame& f : p.frames) {
    w.put_string(f.key);
    put_mesh(w, f.compact);
  }
  for (const auto& [index, m] : p.whole_frames) {
    w.put(index);
    put_whole(w, m);
  }
  // The slabs' bytes go to the file as they are: a big mesh's are hundreds of megabytes.
  std::vector<Writer> heads(p.slabs.size());
  std::vector<std::string_view> pieces{w.out};
  for (size_t i = 0; i < p.slabs.size(); ++i) {
    const mesh::Slab& s = p.slabs[i];
    heads[i].put(s.job), heads[i].put(s.first), heads[i].put(s.end), heads[i].put<uint64_t>(s.bytes.size());
    pieces.push_back(heads[i].out), pieces.push_back(s.bytes);
  }
  pieces.push_back(kEnd);
  return fscript::support::write_file_atomic(path, pieces, error);
}

bool read_part(const std::string& path, Part& p, std::string& error) {
  auto raw = std::make_shared<std::string>();  // kept by the slabs, which point into it
  const std::string& bytes = *raw;
  if (!fscript::support::read_file(path, *raw, error)) return error = "cannot read the part: " + error, false;
  if (bytes.compare(0, std::strlen(kMagic), kMagic) != 0)
    return error = "not a part file of fvrml-run --shard (or of another version)", false;
  Reader r{{bytes, std::strlen(kMagic)}};
  nlohmann::json header = nlohmann::json::parse(r.get_string(), nullptr, false);
  if (!r.ok || !header.is_object() || !header.contains("args") || !header["args"].is_array())
    return error = "the part's header is damaged", false;
  try {
    p.cwd = header.at("cwd").get<std::string>();
    p.args = header.at("args").get<std::vector<std::string>>();
    p.scene_hash = header.at("scene_hash").get<uint64_t>();
    p.shard = {header.at("shard").get<int>(), header.at("of").get<int>()};
    size_t n = header.at("frames").get<size_t>();
    for (size_t i = 0; i < n && r.ok; ++i) {
      PartFrame f;
      f.key = r.get_string();
      f.compact = get_mesh(r);
      p.frames.push_back(std::move(f));
    }
    size_t whole = header.value("whole_frames", size_t{0});
    for (size_t i = 0; i < whole && r.ok; ++i) {
      uint32_t index = r.get<uint32_t>();
      p.whole_frames.emplace_back(index, get_whole(r));
    }
    size_t slabs = header.value("slabs", size_t{0});
    for (size_t i = 0; i < slabs && r.ok; ++i) {
      mesh::Slab s;
      s.job = r.get<uint32_t>(), s.first = r.get<int>(), s.end = r.get<int>();
      uint64_t n = r.get<uint64_t>();
      if (!r.ok || n > r.in.size() - r.at) {
        r.ok = false;
        break;
      }
      s.data = raw, s.bytes = r.in.substr(r.at, n), r.at += n;
      p.slabs.push_back(std::move(s));
    }
  } catch (const nlohmann::json::exception&) {
    return error = "the part's header is damaged", false;
  }
  if (!r.ok || bytes.compare(r.at, std::string::npos, kEnd) != 0)
    return error = "the part is truncated or damaged (was its shard still running?)", false;
  return true;
}

std::vector<std::string> args_for_part(int argc, char** argv) {
  std::vector<std::string> out;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--shard" || a == "-o" || a == "--output") {
      ++i;  // and its value
      continue;
    }
    if (a.rfind("--shard=", 0) == 0 || a.rfind("--output=", 0) == 0 || (a.size() > 2 && a.rfind("-o", 0) == 0))
      continue;
    out.push_back(a);
  }
  return out;
}

bool check_parts(const std::vector<std::string>& paths, const std::vector<Part>& parts, std::string& error) {
  const Part& first = parts.front();
  std::map<int, std::string> seen;
  for (size_t i = 0; i < parts.size(); ++i) {
    const Part& p = parts[i];
    if (p.args != first.args || p.cwd != first.cwd || p.shard.count != first.shard.count)
      return error = paths[i] + ": a shard of another job than " + paths[0] + " (its arguments or shard count differ)",
             false;
    if (p.scene_hash != first.scene_hash)
      return error = paths[i] + ": made from other scene files than " + paths[0] + " (a file changed between shards)",
             false;
    if (!seen.emplace(p.shard.index, paths[i]).second)
      return error = paths[i] + " and " + seen[p.shard.index] + " are both shard " + std::to_string(p.shard.index) +
                 " of " + std::to_string(p.shard.count),
             false;
  }
  std::vector<int> missing;
  for (int k = 0; k < first.shard.count; ++k)
    if (!seen.count(k)) missing.push_back(k);
  if (missing.empty()) return true;
  std::string list, of = std::to_string(first.shard.count);
  for (int k : missing) list += (list.empty() ? "" : ", ") + std::to_string(k);
  error = (missing.size() == 1 ? "shard " : "shards ") + list + " of " + of + " missing (run " +
      (missing.size() == 1 ? "it with --shard " + std::to_string(missing[0]) + "/" + of : "each with --shard K/" + of) +
      ")";
  return false;
}

}  // namespace fvrml_run
