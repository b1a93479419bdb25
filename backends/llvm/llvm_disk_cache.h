#pragma once
// The optional on-disk cache of the llvm backend's object code, under the user's cache directory
// ($XDG_CACHE_HOME/fscript/llvm, else ~/.cache/fscript/llvm): a scene run again with unchanged
// scripts loads its machine code instead of optimising and compiling. Files are named by a hash
// of the program's key; the key is stored beside the object and compared on every load.
#include <memory>
#include <string>

#include <llvm/ExecutionEngine/Orc/IRCompileLayer.h>
#include <llvm/ExecutionEngine/Orc/JITTargetMachineBuilder.h>

namespace fscript::llvmjit {

class DiskCache;

// The module flag that asks for code generation without optimisation (a quick compile).
constexpr const char* kQuickFlag = "fs.quick";

// The compiler the LLJIT uses: LLVM's, consulting `cache` (compiled without RTTI, as LLVM is);
// modules with kQuickFlag are compiled with CodeGenOptLevel::None.
llvm::Expected<std::unique_ptr<llvm::orc::IRCompileLayer::IRCompiler>> make_compiler(
    llvm::orc::JITTargetMachineBuilder jtmb, DiskCache* cache);

DiskCache* make_disk_cache();  // lives for the process
// The directory in use ("" = off); turning on picks the user's cache directory.
std::string set_disk_cache(DiskCache* cache, bool on);
// The module name to give a program with this key, and whether its object is on disk.
std::string disk_name(const std::string& key);
bool disk_has(DiskCache* cache, const std::string& key);
void disk_expect(DiskCache* cache, const std::string& key);  // the next object stored is this key's

}  // namespace fscript::llvmjit
