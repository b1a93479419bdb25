#pragma once
// Sharding across machines (docs/sharding.md): `--shard K/M` makes the frames i with i % M == K of
// every animated node, or in a still scene slab K of every implicit shape, and writes them to a
// part file with the hash of the scene's files and the run's arguments; `fvrml-run merge PART...
// -o OUT` checks that the parts are one job's, complete and without overlap, then writes what the
// run on one machine writes.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/mesh/dc_slabs.h"
#include "engine/mesh/frame_cache.h"

namespace fvrml_run {

namespace mesh = fscript::mesh;

struct Shard {
  int index = 0, count = 0;  // count 0: the whole job
};

// "K/M" with 0 <= K < M <= 10000, or "auto": Slurm's job array (SLURM_ARRAY_TASK_ID from
// SLURM_ARRAY_TASK_MIN, over SLURM_ARRAY_TASK_COUNT; with FVRML_SHARDS=M set, task K of any array
// is shard K of M, for reruns). False with a message.
bool parse_shard(const std::string& text, Shard& out, std::string& error);

struct PartFrame {
  std::string key;  // the frame's memo key (memo.h): the node, its resolved numbers, the options
  mesh::CompactMesh compact;
};

struct Part {
  std::string cwd;                // where the shard ran: the arguments' paths are relative to it
  std::vector<std::string> args;  // the command line without --shard and -o
  uint64_t scene_hash = 0;        // of every file the scene read (scene_files_hash)
  Shard shard;
  std::vector<PartFrame> frames;
  // --frames N with mesh files or a contact sheet: whole frames (every shape in one mesh), exact,
  // since those outputs are written from meshes as made, not from the frame cache.
  std::vector<std::pair<uint32_t, mesh::Mesh>> whole_frames;
  // A still scene: each implicit shape's slab of block layers (dual contouring, dc_slabs.h).
  std::vector<mesh::Slab> slabs;
  bool still = false;  // a still scene's shard (slabs, perhaps none), not an animation's
};

// FNV-1a over the contents of the files, in order (the scene, then its Inlines and EXTERNPROTOs).
uint64_t scene_files_hash(const std::vector<std::string>& files);

bool write_part(const std::string& path, const Part& p, std::string& error);
// Reads a part; false with "what is wrong" (not a part, a newer format, truncated).
bool read_part(const std::string& path, Part& p, std::string& error);

// The command line of a shard as the part records it: argv[1..] without --shard and -o (in any of
// CLI11's spellings).
std::vector<std::string> args_for_part(int argc, char** argv);

// Checks that the parts are one job's shards 0 .. M-1, each once; false with an error naming the
// part or the missing shard.
bool check_parts(const std::vector<std::string>& paths, const std::vector<Part>& parts, std::string& error);

}  // namespace fvrml_run
