// The LLJIT instance, the optimisation pipeline, runtime symbols and the compiled-code cache.
#include "backends/llvm/llvm_jit.h"

#include <llvm/ExecutionEngine/Orc/JITTargetMachineBuilder.h>
#include <llvm/ExecutionEngine/Orc/LLJIT.h>
#include <llvm/ExecutionEngine/Orc/ThreadSafeModule.h>
#include <llvm/IR/Instructions.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/LegacyPassManager.h>
#include <llvm/IR/Module.h>
#include <llvm/Passes/PassBuilder.h>
#include <llvm/Support/TargetSelect.h>
#include <llvm/Support/raw_ostream.h>
#include <llvm/Target/TargetMachine.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <deque>
#include <iterator>
#include <mutex>
#include <unordered_map>

#include "backends/lane_arrays.h"
#include "backends/llvm/llvm_disk_cache.h"
#include "runtime/math/math.h"
#include "runtime/support/cancel.h"

namespace fscript::llvmjit {
namespace {

// runtime/math's batch functions under the names generated code calls: fs_rt_NAME for every
// Batch and Trig row of ir/math_ops.def.
extern "C" {
#define FS_RT_Lane(FN, A)
#define FS_RT_Batch(FN, A) \
  void fs_rt_##FN(FS_BATCH_PARAMS_##A) { math::FN##_batch(FS_BATCH_ARGS_##A); }
#define FS_RT_Trig FS_RT_Batch
#define FS_MATH(N, FN, A, HOW) FS_RT_##HOW(FN, A)
#include "ir/math_ops.def"
#undef FS_RT_Batch
}

// Every symbol generated code may call, the one table the JIT resolves them from.
struct RuntimeSymbol {
  const char* name;
  const void* address;
};
#define FS_SYM(f) {#f, reinterpret_cast<const void*>(&f)}
const RuntimeSymbol kRuntimeSymbols[] = {
#define FS_RT_Batch(FN, A) FS_SYM(fs_rt_##FN),
#define FS_MATH(N, FN, A, HOW) FS_RT_##HOW(FN, A)
#include "ir/math_ops.def"
#undef FS_RT_Lane
#undef FS_RT_Batch
#undef FS_RT_Trig
#define FS_LANES(f) {#f, reinterpret_cast<const void*>(&backends::f)}
    FS_LANES(fs_lanes_reset), FS_LANES(fs_lanes_anew),  FS_LANES(fs_lanes_aload), FS_LANES(fs_lanes_astore),
    FS_LANES(fs_lanes_alen),  FS_LANES(fs_lanes_enter), FS_LANES(fs_lanes_leave),
};
#undef FS_SYM
#undef FS_LANES

// Until the loader says otherwise, this module's own copy (a process that links the backend in).
std::atomic<const void*> g_cancel_slot{support::cancel_slot()};

std::string message(llvm::Error e) {
  std::string s;
  llvm::handleAllErrors(std::move(e), [&](const llvm::ErrorInfoBase& info) { s += info.message(); });
  return s;
}

// One LLJIT for the process, with a target machine for the optimiser and the assembly printer;
// the mutex serialises compiles (the target machine is not shared across threads).
struct State {
  std::unique_ptr<llvm::orc::LLJIT> jit;
  std::unique_ptr<llvm::TargetMachine> tm;
  std::string error;
  std::mutex mutex;
  uint64_t next_dylib = 0;
  std::unordered_map<std::string, std::weak_ptr<Program>> cache;
  size_t sweep_at = 64;  // the cache's size that triggers dropping the keys of freed programs
  std::deque<std::shared_ptr<Program>> recent;  // the last programs stay compiled when unused
  CacheStats stats;
  bool cache_on = true;
  DiskCache* disk = make_disk_cache();
};
constexpr size_t kRecentPrograms = 16;

State& state() {
  static State* s = [] {
    auto* st = new State;  // never destroyed: kernels may outlive static destruction order
    llvm::InitializeNativeTarget();
    llvm::InitializeNativeTargetAsmPrinter();
    llvm::InitializeNativeTargetAsmParser();
    auto jtmb = llvm::orc::JITTargetMachineBuilder::detectHost();
    if (!jtmb) {
      st->error = message(jtmb.takeError());
      return st;
    }
    jtmb->setCodeGenOptLevel(llvm::CodeGenOptLevel::Aggressive);
    // Constants rip-relative (JITLink keeps a program's code and data together), not through
    // 64-bit absolute addresses: on prospero that removes 1,387 movabs.
    jtmb->setCodeModel(llvm::CodeModel::Small);
    auto tm = jtmb->createTargetMachine();
    if (!tm) {
      st->error = message(tm.takeError());
      return st;
    }
    st->tm = std::move(*tm);
    DiskCache* disk = st->disk;
    auto jit = llvm::orc::LLJITBuilder()
                   .setJITTargetMachineBuilder(std::move(*jtmb))
                   .setCompileFunctionCreator(
                       [disk](llvm::orc::JITTargetMachineBuilder j) { return make_compiler(std::move(j), disk); })
                   .create();
    if (!jit) {
      st->error = message(jit.takeError());
      return st;
    }
    st->jit = std::move(*jit);
    // Errors reach the caller through lookup's result; nothing goes to stderr.
    st->jit->getExecutionSession().setErrorReporter([](llvm::Error e) { llvm::consumeError(std::move(e)); });
    return st;
  }();
  return *s;
}

void prepare(Lowered& l, State& s) {
  l.module->setDataLayout(s.tm->createDataLayout());
  l.module->setTargetTriple(s.tm->getTargetTriple().str());
}

// Past this many basic blocks or instructions a module is compiled quickly: cheap clean-ups and
// code generation without optimisation. LLVM's pipeline and greedy register allocation grow
// faster than linearly with the blocks and the length of one function: a 230-byte generated
// program whose inlined calls made 5,172 blocks took 45 s to compile at one lane (884 blocks
// 0.9 s, 1,752 about 3 s), a straight-line script of 100,000 operations 196 s (20,000: 5.5 s for
// its two compiles of 20,032 and 36,721 instructions; docs/performance.md). Our lowering makes a
// block for a few of the script's branches and loops (the benchmarks: 6 to 18; the corpus and
// examples: under 30), and prospero's 7,866 operations make 6,382 instructions (20,788 in its
// one-point code, with the NaN tests): only scripts of hundreds of loops and branches, or tens of
// thousands of operations, get here, where a bounded compile matters more than fast code.
constexpr size_t kQuickCompileBlocks = 1000;
constexpr size_t kQuickCompileInstructions = 25000;

bool quick_compile(const llvm::Module& m) {
  size_t blocks = 0, instructions = 0;
  for (const llvm::Function& f : m) blocks += f.size(), instructions += f.getInstructionCount();
  return blocks > kQuickCompileBlocks || instructions > kQuickCompileInstructions;
}

// Instruction selection builds one DAG per basic block, and its combiner grows faster than
// linearly with the block (a straight-line script of 100,000 operations: 97 s, mostly in
// SelectionDAG::Combine). Blocks longer than this are cut into blocks of this length, joined by
// unconditional branches, after the optimiser (which would merge them again); prospero's
// 6,382-instruction block is left whole.
constexpr size_t kMaxBlockInstructions = 8192;

void split_long_blocks(llvm::Module& m) {
  for (llvm::Function& f : m) {
    std::vector<llvm::BasicBlock*> work;
    for (llvm::BasicBlock& b : f) work.push_back(&b);
    while (!work.empty()) {
      llvm::BasicBlock* b = work.back();
      work.pop_back();
      if (b->size() <= kMaxBlockInstructions) continue;
      auto cut = b->begin();
      std::advance(cut, kMaxBlockInstructions);
      while (llvm::isa<llvm::PHINode>(*cut)) ++cut;  // phis stay at the head
      work.push_back(b->splitBasicBlock(cut));
    }
  }
}

// Runs the module pipeline `make` builds, with every analysis registered.
template <typename Make>
void run_pipeline(llvm::Module& m, llvm::TargetMachine* tm, const Make& make) {
  llvm::LoopAnalysisManager lam;
  llvm::FunctionAnalysisManager fam;
  llvm::CGSCCAnalysisManager cgam;
  llvm::ModuleAnalysisManager mam;
  llvm::PassBuilder pb(tm);
  pb.registerModuleAnalyses(mam);
  pb.registerCGSCCAnalyses(cgam);
  pb.registerFunctionAnalyses(fam);
  pb.registerLoopAnalyses(lam);
  pb.crossRegisterProxies(lam, fam, cgam, mam);
  llvm::ModulePassManager mpm = make(pb);
  mpm.run(m, mam);
}

// The quick compile's pipeline: cheap clean-ups only. Values used across blocks stay in their
// allocas: turning them into SSA values (SROA) builds phi webs that grow with blocks times
// allocas (the pending lane mask of every block is one), slower to compile than the rest.
void optimize_quickly(llvm::Module& m, llvm::TargetMachine* tm) {
  run_pipeline(m, tm, [](llvm::PassBuilder& pb) {
    llvm::ModulePassManager mpm;
    if (llvm::Error e = pb.parsePassPipeline(mpm, "function(early-cse,instcombine<no-verify-fixpoint>,simplifycfg)"))
      llvm::consumeError(std::move(e));  // a fixed pipeline LLVM 19 knows; without it, unoptimised code
    return mpm;
  });
  m.addModuleFlag(llvm::Module::Warning, kQuickFlag, 1);
}

void optimize(llvm::Module& m, llvm::TargetMachine* tm) {
  // FSCRIPT_LLVM_OPT=1|2|3 overrides the level, to measure the choice (docs/performance.md).
  static const int opt = [] {
    const char* v = std::getenv("FSCRIPT_LLVM_OPT");
    return v && (v[0] == '1' || v[0] == '2' || v[0] == '3') && !v[1] ? v[0] - '0' : kOptLevel;
  }();
  llvm::OptimizationLevel level = opt == 3 ? llvm::OptimizationLevel::O3
      : opt == 1                           ? llvm::OptimizationLevel::O1
                                           : llvm::OptimizationLevel::O2;
  run_pipeline(m, tm, [&](llvm::PassBuilder& pb) { return pb.buildPerModuleDefaultPipeline(level); });
}

// The module as code generation gets it: the full or the quick pipeline, long blocks cut. True
// for a quick compile (the module then carries kQuickFlag).
bool optimize_for_codegen(llvm::Module& m, llvm::TargetMachine* tm) {
  bool quick = quick_compile(m);
  if (quick) optimize_quickly(m, tm);
  else optimize(m, tm);
  split_long_blocks(m);
  return quick;
}

}  // namespace

Program::~Program() {
  if (!dylib_) return;
  State& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  llvm::consumeError(s.jit->getExecutionSession().removeJITDylib(*static_cast<llvm::orc::JITDylib*>(dylib_)));
}

uint32_t host_width() {
  // FSCRIPT_ISA (as for the VM's variants, runtime/math/isa.h) narrows it, so tests run every width.
  const char* isa = std::getenv("FSCRIPT_ISA");
  std::string want = isa ? isa : "";
  if (want == "base") return 4;
  if (want == "avx2" && __builtin_cpu_supports("avx2")) return 8;
  if (__builtin_cpu_supports("avx512f")) return 16;
  if (__builtin_cpu_supports("avx2")) return 8;
  return 4;
}

std::shared_ptr<Program> compile(Lowered&& lowered, const std::string& key, double& compile_ms, std::string& error) {
  compile_ms = 0;
  State& s = state();
  if (!s.jit) {
    error = "the llvm backend could not start LLVM's JIT: " + s.error;
    return nullptr;
  }
  std::shared_ptr<Program> evicted;  // destroyed after the lock is released (its destructor locks)
  std::unique_lock<std::mutex> lock(s.mutex);
  auto start = std::chrono::steady_clock::now();
  prepare(lowered, s);
  lowered.module->setModuleIdentifier(disk_name(key));
  disk_expect(s.disk, key);
  if (disk_has(s.disk, key)) ++s.stats.disk_hits;  // the object is loaded instead of compiled
  else if (optimize_for_codegen(*lowered.module, s.tm.get())) ++s.stats.quick_compiles;
  auto dylib = s.jit->createJITDylib("fs_program_" + std::to_string(s.next_dylib++));
  if (!dylib) {
    error = message(dylib.takeError());
    return nullptr;
  }
  llvm::orc::SymbolMap symbols;
  for (const auto& r : kRuntimeSymbols)
    symbols[s.jit->mangleAndIntern(r.name)] = {llvm::orc::ExecutorAddr::fromPtr(r.address),
                                               llvm::JITSymbolFlags::Exported | llvm::JITSymbolFlags::Callable};
  symbols[s.jit->mangleAndIntern("fs_cancel_slot")] = {llvm::orc::ExecutorAddr::fromPtr(g_cancel_slot.load()),
                                                       llvm::JITSymbolFlags::Exported};
  auto program = std::make_shared<Program>();
  program->dylib_ = &*dylib;
  program->num_inputs = lowered.num_inputs;
  program->num_outputs = lowered.num_outputs;
  program->array_names = lowered.array_names;
  program->param_bound = lowered.param_bound;
  llvm::Error e = dylib->define(llvm::orc::absoluteSymbols(std::move(symbols)));
  if (!e)
    e = s.jit->addIRModule(*dylib, llvm::orc::ThreadSafeModule(std::move(lowered.module), std::move(lowered.context)));
  if (e) {
    error = message(std::move(e));
    lock.unlock();
    return nullptr;  // the program's destructor removes the dylib
  }
  auto entry = s.jit->lookup(*dylib, lowered.point_entry ? kPointSymbol : kKernelSymbol);  // compiles
  if (!entry) {
    error = message(entry.takeError());
    lock.unlock();
    return nullptr;
  }
  if (lowered.point_entry) program->point_ = entry->toPtr<PointFn>();
  else program->entry_ = entry->toPtr<KernelFn>();
  compile_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ++s.stats.compiles;
  // Keys of freed programs go, or the map grew with every distinct compile of the process (each
  // key holds the program's IR text: a --serve session kept every saved version's).
  if (s.cache.size() >= s.sweep_at) {
    std::erase_if(s.cache, [](const auto& e) { return e.second.expired(); });
    s.sweep_at = std::max<size_t>(64, 2 * s.cache.size());
  }
  s.cache[key] = program;
  s.recent.push_back(program);
  if (s.recent.size() > kRecentPrograms) {
    evicted = std::move(s.recent.front());
    s.recent.pop_front();
  }
  return program;
}

std::shared_ptr<Program> cached(const std::string& key) {
  State& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  if (!s.cache_on) return nullptr;
  auto it = s.cache.find(key);
  if (it == s.cache.end()) return nullptr;
  auto hit = it->second.lock();
  if (hit) ++s.stats.hits;
  return hit;
}

bool has_code(const std::string& key) {
  State& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  if (s.cache_on) {
    auto it = s.cache.find(key);
    if (it != s.cache.end() && !it->second.expired()) return true;
  }
  return disk_has(s.disk, key);
}

namespace {
// `use` on the optimised module, under the JIT's lock (the target machine is shared).
template <typename Use>
std::string with_optimized(Lowered& lowered, std::string& error, Use use) {
  State& s = state();
  if (!s.jit) {
    error = "the llvm backend could not start LLVM: " + s.error;
    return "";
  }
  std::lock_guard<std::mutex> lock(s.mutex);
  prepare(lowered, s);
  optimize_for_codegen(*lowered.module, s.tm.get());
  return use(s);
}
}  // namespace

std::string optimized_ir(Lowered& lowered, std::string& error) {
  return with_optimized(lowered, error, [&](State&) {
    std::string text;
    llvm::raw_string_ostream os(text);
    lowered.module->print(os, nullptr);
    return os.str();
  });
}

std::string assembly(Lowered& lowered, std::string& error) {
  return with_optimized(lowered, error, [&](State& s) -> std::string {
    llvm::SmallString<0> buffer;
    llvm::raw_svector_ostream os(buffer);
    llvm::legacy::PassManager pm;
    // A quick compile's code comes from the unoptimised code generator: print that.
    llvm::CodeGenOptLevel level = s.tm->getOptLevel();
    if (lowered.module->getModuleFlag(kQuickFlag)) s.tm->setOptLevel(llvm::CodeGenOptLevel::None);
    bool refused = s.tm->addPassesToEmitFile(pm, os, nullptr, llvm::CodeGenFileType::AssemblyFile);
    if (!refused) pm.run(*lowered.module);
    s.tm->setOptLevel(level);
    if (refused) error = "LLVM cannot print assembly for this target";
    return refused ? "" : std::string(buffer.str());
  });
}

std::string set_disk_cache_enabled(bool on) {
  State& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  return set_disk_cache(s.disk, on);
}

void set_cancel_slot(const void* slot) { g_cancel_slot = slot; }

void set_cache_enabled(bool on) {
  State& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  s.cache_on = on;
}

CacheStats cache_stats() {
  State& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  CacheStats out = s.stats;
  out.keys = s.cache.size();
  return out;
}

}  // namespace fscript::llvmjit
