#pragma once
// Dual contouring block by block: kBlock^3 dual cells with their (kBlock + 1)^3 samples, so each step
// works on small dense arrays that stay in cache, only the blocks the surface may cross are kept,
// and blocks run on any thread (dual_contour.cpp joins them in a fixed order: the same bytes).
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "backends/backend.h"
#include "engine/mesh/dc_cells.h"
#include "engine/mesh/field.h"
#include "engine/mesh/sample_pruning.h"
#include "engine/mesh/qef.h"

namespace fscript::mesh {

constexpr int kBlockLevels = 4;                 // octree levels inside a block
constexpr int kBlock = 1 << kBlockLevels;       // dual cells per block side
constexpr int kBlockSamples = kBlock + 1;       // samples per block side (faces shared with neighbours)
constexpr uint32_t kNone = ~uint32_t{0};
constexpr int kNextAxis[3] = {1, 2, 0};

// A sign-change edge between two samples of a block.
struct Crossing {
  uint8_t l[3];  // the edge's lower sample, in the block
  uint8_t axis;
  bool lower_inside;
};

// The four cells (in the block; -1 where they are in the blocks below) around a crossing's edge, in
// the order that winds its polygon around +axis.
void cells_of(const Crossing& c, int out[4][3]);

// A cell's side of a cut segment (dc_cells.h, "Tube faces"; dc_tubes.h): both cells on the face
// record one, whichever of them cuts it.
struct TubeCut {
  int32_t face[3] = {0, 0, 0};  // the face's lowest lattice sample
  uint8_t axis = 0;             // the axis the face is across
  uint8_t segment = 0;          // its two crossing edges: bits face_edge(e, axis)
  uint8_t high = 0;             // this cell lies on the face's +axis side
  uint8_t forward = 0;          // the first crossing's polygon runs from the low cell's vertex to the high cell's
  // This cell's pieces at the segment's first and second crossing (by face_edge): sheets of the
  // block, then its vertices, then the output's.
  uint32_t first = 0, second = 0;
  bool same_segment(const TubeCut& o) const {
    return face[0] == o.face[0] && face[1] == o.face[1] && face[2] == o.face[2] && axis == o.axis &&
        segment == o.segment;
  }
};

// A cut segment's side in another block, to be recorded once every block is worked
// (dc_tubes.h): the cut without its pieces, and the lattice cell whose pieces they are.
struct TubeRequest {
  TubeCut cut;
  int32_t cell[3];
};

// One sheet of surface in a dual cell (manifold dual contouring). Its planes (a Qef) live only while
// the block is merged (cell_sheets to merge_block), so the blocks stay small.
// In 16 bits: a block holds 4,096 cells and at most four sheets in each (6 bytes a sheet, not 12:
// a finished block keeps them to the end).
struct Sheet {
  Sheet() = default;
  Sheet(uint32_t in_cell, uint32_t next_sheet, int sheet_key)
      : cell(static_cast<uint16_t>(in_cell)), link(next_sheet == kNone ? kEnd : static_cast<uint16_t>(next_sheet)),
        key(static_cast<uint16_t>(sheet_key)) {}
  uint32_t next() const { return link == kEnd ? kNone : link; }  // the cell's next sheet, or kNone
  static constexpr uint16_t kEnd = 0xffff;
  uint16_t cell = 0;     // in the block
  uint16_t link = kEnd;  // next(), or kEnd
  uint16_t key = 0;      // which sheet of the cell: sheet_key, plus 64 times its piece (tube faces)
};

struct Block {
  int b[3];   // the block's position among blocks
  int s0[3];  // the lattice sample (from -1) of its sample 0, the lowest corner of its cell 0
  int m[3];   // its cells per axis: kBlock, fewer at the lattice's end
  std::vector<float> f;           // samples, x fastest (while sampling, in a buffer of the thread)
  std::vector<uint8_t> decided;   // 1: sign from the brick map, value not evaluated (the same)
  uint32_t rows[kBlockSamples][kBlockSamples];  // [k][j]: bit i where sample (i, j, k) is inside
  std::vector<Crossing> xs;       // on every edge between the block's samples
  std::vector<std::array<float, 2>> ends;  // f at their lower and upper samples (until the Hermite data is done)
  // Per cell with surface: its inside corners, its tube faces (kTubes: bits 2 * axis + side; its
  // faces are decided by kuhn_flips) and kOneSheet where the whole cell is one sheet (its sheets
  // need no key then), and its first sheet.
  struct CellInfo {
    uint8_t mask = 0, flips = 0;
    uint32_t first = kNone;
  };
  static constexpr uint8_t kOneSheet = 0x80, kTubes = 0x3f;
  std::vector<CellInfo> cells;  // every cell, while the block is worked (a buffer of the thread)
  // Then only its cells with sheets on its upper faces, which the next blocks' polygons reach: a
  // tenth of a face's cells or fewer, and the block's largest part once the whole face was kept.
  struct RimCell {
    uint16_t at;  // rim_index
    uint8_t mask, flips;
    uint32_t first;
  };
  std::vector<RimCell> rim;  // by `at`
  std::vector<Sheet> sheets;
  // Per crossing: its cells' sheets here (kNoSheet: another block's). 16 bits: a block has at most
  // four sheets in each of its 4,096 cells, and these are most of a finished block's bytes.
  static constexpr uint16_t kNoSheet = 0xffff;
  std::vector<std::array<uint16_t, 4>> ids;
  uint32_t id(size_t e, size_t q) const { return ids[e][q] == kNoSheet ? kNone : ids[e][q]; }
  // Vertices (dc_cell_merge.h): each sheet's vertex among the block's (then, once numbered, in the
  // output mesh), their positions (as the mesh stores them) and their largest plane distance.
  std::vector<uint32_t> vertex;
  std::vector<std::array<float, 3>> positions;
  std::vector<TubeCut> cuts;  // its cells' sides of cut segments (their pieces, as `vertex`)
  std::vector<std::array<uint32_t, 3>> fans;  // the middles of loops of three or more pieces (the same)
  std::vector<TubeRequest> requests;          // sides of its cells' cuts in other blocks
  double max_rms = 0;
  size_t merged = 0;        // of those, merged cells
  bool root = false;        // one merged cell holds every sheet: it may merge with other blocks
  Qef root_qef;
  size_t evaluated = 0;
  uint32_t gradient_normals = 0, difference_normals = 0;  // of its crossings' normals (the box's aside)
  bool sound = true;  // no evaluated sample contradicted its brick's bound
  // The field's tape simplified for the block (BrickMap::local_at), while it is sampled and worked:
  // every point either evaluates lies in its box. Null: the field itself.
  std::shared_ptr<const Field> local;
  const Field& field(const Field& f) const { return local ? *local : f; }

  static size_t sample(int i, int j, int k) {
    return (static_cast<size_t>(k) * kBlockSamples + static_cast<size_t>(j)) * kBlockSamples + static_cast<size_t>(i);
  }
  static size_t cell(int i, int j, int k) {
    return (static_cast<size_t>(k) * kBlock + static_cast<size_t>(j)) * kBlock + static_cast<size_t>(i);
  }
  bool inside(int i, int j, int k) const { return rows[k][j] >> i & 1; }
  // The sheet of a cell that holds the crossing between its corners in and out, or kNone; and the
  // key that names it in the cell.
  uint32_t sheet(const CellInfo& c, int in, int out) const;
  static int key(const CellInfo& c, int in, int out);
  // Where a cell with a coordinate kBlock - 1 is on the rim; that cell's signs and sheets (none
  // where the rim keeps none).
  static size_t rim_index(int i, int j, int k);
  CellInfo rim_cell(int i, int j, int k) const;
  // Keeps the rim of `cells` and gives the buffer back.
  void keep_rim();
};

// Every block of a lattice: the ones the surface may cross are kept, the others are known to be all
// inside or all outside.
class BlockGrid {
 public:
  static constexpr int32_t kAllInside = -1, kAllOutside = -2;
  BlockGrid(const Lattice& g, const BrickMap* bricks);
  // A grid of blocks made elsewhere (dc_slabs.h): per block position (x fastest) its index in
  // `blocks` (in the order of the positions) or kAllInside / kAllOutside.
  BlockGrid(const Lattice& g, std::vector<int32_t> slots, std::vector<Block> blocks);
  // Blocks per axis for a lattice: n + 1 dual cells per axis, kBlock to a block.
  static int blocks_along(const Lattice& g, int axis) { return (g.n[axis] + 1 + kBlock - 1) / kBlock; }
  int32_t slot(size_t position) const { return slot_[position]; }
  const Lattice& lattice() const { return g_; }
  std::vector<Block>& blocks() { return blocks_; }
  const std::vector<Block>& blocks() const { return blocks_; }
  // The block at position b, or nullptr where none is kept.
  const Block* at(int bi, int bj, int bk) const;
  // Its slot: an index into blocks(), kAllInside, or kAllOutside (also past the grid's ends).
  int32_t slot_at(int bi, int bj, int bk) const;
  // Whether lattice sample s (from -1 per axis) is inside; the padding is not.
  bool inside(int i, int j, int k) const;
  // The inside corners of dual cell c.
  unsigned mask(const int c[3]) const;

 private:
  Lattice g_;
  int nb_[3];
  std::vector<int32_t> slot_;  // per block: its index in blocks_, or kAllInside / kAllOutside
  std::vector<Block> blocks_;  // in the order of their positions
};

// Samples the block (open bricks evaluated, decided ones signed), finds its sign-change edges and
// evaluates the decided samples at their ends (so regula falsi starts from the dense lattice's values).
bool sample_block(const Field& f, const BrickMap* bricks, const Lattice& g, Block& b, backends::RuntimeError& err);
// The Hermite data of each crossing, planes[e]: the crossing by regula falsi, the normal from the
// gradient; the box face where an end is padding.
bool hermite(const Field& f, const Lattice& g, Block& b, std::vector<Plane>& planes, backends::RuntimeError& err);
// The cells' signs and face choices, and the sheets of the crossings; qefs[s]: sheet s's planes;
// the cuts of tube faces (record_cuts, looking across the faces `look_across` names).
void cell_sheets(const BlockGrid& grid, Block& b, const std::vector<Plane>& planes, std::vector<Qef>& qefs,
                 uint8_t look_across = 0);

}  // namespace fscript::mesh
