#pragma once
// The process's LLVM ORC LLJIT: optimisation of lowered modules, one JITDylib per compiled
// program (freed with it), runtime symbols from one table, a cache of compiled programs keyed by
// the IR's hash, and the text forms `fscript emit-asm` / `emit-ir --llvm` print.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "backends/llvm/llvm_lower.h"

namespace fscript::llvmjit {

// Compiled code alive as long as some kernel holds it (made by compile()).
struct Program {
  ~Program();
  KernelFn entry() const { return entry_; }
  PointFn point() const { return point_; }
  void* dylib_ = nullptr;  // the llvm::orc::JITDylib, removed with the program
  KernelFn entry_ = nullptr;  // one of the two, by Lowered::point_entry
  PointFn point_ = nullptr;
  // The kernel's shape, as lowering found it (a cache hit needs no lowering).
  uint32_t num_inputs = 0, num_outputs = 0;
  std::vector<std::string> array_names;
  double param_bound = 0;
};

// The optimisation level, chosen by measurement (docs/performance.md).
constexpr int kOptLevel = 1;

// The SIMD width of this CPU: 16 with AVX-512, 8 with AVX2, else 4 (FSCRIPT_ISA=base|avx2 asks
// for 4 or 8, as it picks the VM's instruction-set variant).
uint32_t host_width();

// The compiled program for `key` (the source program's IR text, width, budgets), if the cache
// has it alive.
std::shared_ptr<Program> cached(const std::string& key);
// Whether the program for `key` is alive in the cache or its object is in the disk cache.
bool has_code(const std::string& key);
// Compiles the lowered program and caches it under `key`; nullptr with a message on failure.
// compile_ms says how long LLVM took.
std::shared_ptr<Program> compile(Lowered&& lowered, const std::string& key, double& compile_ms, std::string& error);

// The optimised LLVM IR, or the host's assembly for it.
std::string optimized_ir(Lowered& lowered, std::string& error);
std::string assembly(Lowered& lowered, std::string& error);

// Compiled programs kept (cache hits) and compiles done, for tests and `--stats`.
struct CacheStats {
  uint64_t hits = 0, compiles = 0, disk_hits = 0;  // disk hits are also counted in compiles
  uint64_t quick_compiles = 0;  // modules with too many blocks for the full pipeline (also in compiles)
  uint64_t keys = 0;  // entries of the memory cache
};
CacheStats cache_stats();
// Off: every compile compiles (for measuring cold compile times); on by default.
void set_cache_enabled(bool on);
// The on-disk cache of object code (off by default); returns its directory, "" when off or when
// no cache directory can be made.
std::string set_disk_cache_enabled(bool on);
// The host's cancel slot (support::cancel_slot() of the executable, whose fs_support is not this
// module's copy): what generated code's fs_cancel_slot names. Set by the loader before any compile.
void set_cancel_slot(const void* slot);

}  // namespace fscript::llvmjit
