#pragma once
// The optimisation passes, one file each; every pass returns true when it changed the IR.
// The pass manager (pass_manager.cpp) runs them in the pipeline drawn at its top.
#include <string>
#include <vector>

#include "ir/ir.h"

namespace fscript::ir {

bool run_inline(Module& m);            // inline calls of non-recursive functions; drop dead functions
bool run_promote_globals(Module& m);   // globals -> SSA values within each function
bool run_const_fold(Function& fn);     // fold constant operands (via runtime/math), exact identities
bool run_dce(Function& fn);            // delete unused pure values and phis
bool run_gvn(Function& fn);            // global value numbering over the dominator tree
bool run_simplify_cfg(Function& fn);   // unreachable blocks, jump threading, block merging, trivial phis
bool run_if_convert(Function& fn);     // small diamonds and triangles of pure code -> select

struct PassOptions {
  bool verify_each = false;  // run the verifier after every pass (tests); abort with its message
  std::vector<std::string>* trace = nullptr;  // names of the passes that changed something
};

// The standard pipeline. Returns "" or the verifier's complaint when verify_each is set.
std::string optimize(Module& m, const PassOptions& opts = {});
// Runs the named passes in order ("inline,promote,fold,dce,gvn,simplify,ifconv"); for golden tests.
std::string run_passes(Module& m, const std::string& names, const PassOptions& opts = {});

}  // namespace fscript::ir
