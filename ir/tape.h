#pragma once
// A flat tape (ir::IntervalTape) back as IR: a one-function kernel module that any backend compiles.
// Simplified tapes run on the VM straight from the tape (vm::compile_tape); this is how the JITs
// and the tests run them too.
#include <memory>

#include "ir/interval_eval.h"
#include "ir/ir.h"

namespace fscript::ir {

std::unique_ptr<Module> tape_module(const IntervalTape& t);

// Value operations of a straight-line kernel (its tape length).
size_t tape_length(const Function& fn);

}  // namespace fscript::ir
