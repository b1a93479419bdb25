#pragma once
// IR verifier: structural and SSA invariants. Runs after every pass in tests.
#include <string>

#include "ir/ir.h"

namespace fscript::ir {

// Returns "" when `m` is well formed, else a description of the first violation.
std::string verify(const Module& m);

}  // namespace fscript::ir
