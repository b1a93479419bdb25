#pragma once
// Forward-mode differentiation of a straight-line kernel: a new module whose kernel returns the
// first output and its partial derivatives in the first three inputs (the polygonizers' normals).
#include <memory>

#include "ir/ir.h"

namespace fscript::ir {

// The kernel (f, df/dp0, df/dp1, df/dp2) of m's kernel function (p0..p2 its first three
// parameters, every other parameter held fixed), optimised; its other parameters are m's.
// nullptr when the kernel is not one block of pure operations, or uses an operation without a
// derivative here (noise). Where f is not differentiable the rules take one side: min, max and
// select the derivative of the operand they return, abs sign(a) (0 at 0), floor and the
// comparisons 0; fmod(a, b) the derivative of a - b * trunc(a / b) with the quotient held fixed.
// Singular points (sqrt at 0, log at 0, pow of a negative base) give infinities or NaN.
std::unique_ptr<Module> gradient_module(const Module& m);

}  // namespace fscript::ir
