#pragma once
// The probe: a script's variables at a point, or their intervals over a box (fscript probe, the
// REPL's :probe and :bound). The script is lowered with a probe slot at every variable write
// (frontend::KernelSpec::probe) and run on the VM, so the values are the backends' bits.
#include <string>
#include <vector>

namespace fscript::cli {

// `at`: the entry's inputs (x, y, z, t; missing ones 0). Appends the listing to `out`; returns an
// exit status (errors printed).
int probe_point(const std::string& path, const std::string& entry, const std::vector<float>& at, std::string& out);
// `box`: lo, hi per input (missing inputs 0). The intervals of every variable, and what each if,
// min and max does over the whole box.
int probe_box(const std::string& path, const std::string& entry, const std::vector<float>& box, std::string& out);

// fscript probe FILE (--at P | --bound BOX) [--entry NAME].
int cmd_probe(const std::string& file, const std::string& entry, const std::string& at, const std::string& box);

}  // namespace fscript::cli
