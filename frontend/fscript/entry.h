#pragma once
// Kernel specifications for a script's entry points (language spec, "Entry points"): which
// inputs set which globals, and which outputs a kernel returns.
#include <string>

#include "frontend/fscript/lower.h"
#include "frontend/fscript/sema.h"

namespace fscript::frontend {

// The script's own entry point: FRep, else parametric_x/y/z, else parametric_r/g/b, else the
// script's only function; an expression-form script yields its value, an assignment list its
// assigned outputs.
bool default_spec(const SemaResult& sema, KernelSpec& spec, std::string& error);

// A call of the function NAME (exact name first, then ignoring case) with its parameters as the
// kernel's inputs. Entry-point functions also set the input globals (x, y, z, u, v, w, t).
bool function_spec(const SemaResult& sema, const std::string& name, KernelSpec& spec, std::string& error);

// FRep(x, y, z[, t]) as a 4-input, 1-output kernel (x, y, z, t).
bool frep_spec(const SemaResult& sema, KernelSpec& spec, std::string& error);

// Inputs that each set the global of the same name (an FTransform operation: f, g, f1..., t);
// the output is the value of the expression-form script.
bool named_inputs_spec(const SemaResult& sema, const std::vector<std::string>& names, KernelSpec& spec,
                       std::string& error);

// A kernel of a surface point for colours and textures: 7 inputs (x, y, z, u, v, w, t), each
// setting its global, and 4 outputs (value, r, g, b). The value is FRep's result or the
// expression's; r, g, b come from parametric_r/g/b or from the globals the script assigns.
// `rgb` tells whether the script defines r, g, b (else the value is mapped through a pattern).
bool point_spec(const SemaResult& sema, KernelSpec& spec, bool& rgb, std::string& error);

}  // namespace fscript::frontend
