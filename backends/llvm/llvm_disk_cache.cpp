// llvm::ObjectCache over files: <hash>.o and <hash>.key, written atomically (temporary + rename).
// The .key file holds the program's key and a digest of the object, so a damaged or truncated
// object is a miss (compiled again and stored afresh), never code handed to the linker.
#include "backends/llvm/llvm_disk_cache.h"

#include <llvm/ExecutionEngine/ObjectCache.h>
#include <llvm/ExecutionEngine/Orc/CompileUtils.h>
#include <llvm/IR/Module.h>
#include <llvm/Support/MemoryBuffer.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include <unistd.h>

namespace fscript::llvmjit {

namespace fs = std::filesystem;

class DiskCache : public llvm::ObjectCache {
 public:
  std::string dir;  // "" = off
  std::mutex mutex;
  std::string expected_key;  // the key of the module being compiled

  void notifyObjectCompiled(const llvm::Module* m, llvm::MemoryBufferRef obj) override {
    std::lock_guard<std::mutex> lock(mutex);
    if (dir.empty() || m->getModuleIdentifier() != disk_name(expected_key)) return;
    std::string base = (fs::path(dir) / m->getModuleIdentifier()).string();
    std::string stamp = expected_key + '\0' + digest(obj.getBufferStart(), obj.getBufferSize());
    write(base + ".o", obj.getBufferStart(), obj.getBufferSize());
    write(base + ".key", stamp.data(), stamp.size());
  }
  std::unique_ptr<llvm::MemoryBuffer> getObject(const llvm::Module* m) override {
    std::lock_guard<std::mutex> lock(mutex);
    std::string want;
    if (dir.empty() || !matches(m->getModuleIdentifier(), expected_key, &want)) return nullptr;
    auto buffer = llvm::MemoryBuffer::getFile((fs::path(dir) / (m->getModuleIdentifier() + ".o")).string());
    if (!buffer || digest((*buffer)->getBufferStart(), (*buffer)->getBufferSize()) != want) return nullptr;
    return std::move(*buffer);
  }
  // Whether the .key file names `key` and the object exists; `object_digest` gets the digest stored.
  bool matches(const std::string& name, const std::string& key, std::string* object_digest = nullptr) {
    std::ifstream in(fs::path(dir) / (name + ".key"), std::ios::binary);
    if (!in) return false;
    std::ostringstream text;
    text << in.rdbuf();
    std::string stamp = text.str();
    size_t cut = stamp.rfind('\0');
    if (cut == std::string::npos || stamp.compare(0, cut, key) != 0 || cut != key.size()) return false;
    if (object_digest) *object_digest = stamp.substr(cut + 1);
    return fs::exists(fs::path(dir) / (name + ".o"));
  }

 private:
  static std::string digest(const char* data, size_t size) {
    uint64_t h = 14695981039346656037ull;  // FNV-1a over the object's bytes, and its size
    for (size_t i = 0; i < size; ++i) h = (h ^ static_cast<unsigned char>(data[i])) * 1099511628211ull;
    char text[48];
    std::snprintf(text, sizeof text, "%016llx-%zx", static_cast<unsigned long long>(h), size);
    return text;
  }
  // A failed write leaves no file behind: the cache is an optimisation.
  static void write(const std::string& path, const char* data, size_t size) {
    std::string tmp = path + ".tmp" + std::to_string(::getpid());
    {
      std::ofstream out(tmp, std::ios::binary);
      if (!out.write(data, static_cast<std::streamsize>(size))) {
        std::error_code ec;
        fs::remove(tmp, ec);
        return;
      }
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) fs::remove(tmp, ec);
  }
};

namespace {
// Code generation at the builder's level, or with no optimisation (the fast register allocator)
// for a module that carries kQuickFlag: the greedy allocator's time grows faster than linearly in
// the size of a function with many blocks (llvm_jit.cpp, quick compiles).
class TwoLevelCompiler : public llvm::orc::IRCompileLayer::IRCompiler {
 public:
  TwoLevelCompiler(std::unique_ptr<llvm::TargetMachine> full, std::unique_ptr<llvm::TargetMachine> quick,
                   DiskCache* cache)
      : IRCompiler(llvm::orc::irManglingOptionsFromTargetOptions(full->Options)), full_(std::move(full), cache),
        quick_(std::move(quick), cache) {}
  llvm::Expected<std::unique_ptr<llvm::MemoryBuffer>> operator()(llvm::Module& m) override {
    return m.getModuleFlag(kQuickFlag) ? quick_(m) : full_(m);
  }

 private:
  llvm::orc::TMOwningSimpleCompiler full_, quick_;
};
}  // namespace

llvm::Expected<std::unique_ptr<llvm::orc::IRCompileLayer::IRCompiler>> make_compiler(
    llvm::orc::JITTargetMachineBuilder jtmb, DiskCache* cache) {
  auto full = jtmb.createTargetMachine();
  if (!full) return full.takeError();
  jtmb.setCodeGenOptLevel(llvm::CodeGenOptLevel::None);
  auto quick = jtmb.createTargetMachine();
  if (!quick) return quick.takeError();
  return std::make_unique<TwoLevelCompiler>(std::move(*full), std::move(*quick), cache);
}

DiskCache* make_disk_cache() { return new DiskCache; }

std::string set_disk_cache(DiskCache* cache, bool on) {
  std::lock_guard<std::mutex> lock(cache->mutex);
  cache->dir.clear();
  if (!on) return "";
  fs::path base;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) base = xdg;
  else if (const char* home = std::getenv("HOME"); home && *home) base = fs::path(home) / ".cache";
  else return "";
  std::error_code ec;
  fs::create_directories(base / "fscript" / "llvm", ec);
  if (ec) return "";
  cache->dir = (base / "fscript" / "llvm").string();
  return cache->dir;
}

std::string disk_name(const std::string& key) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : key) h = (h ^ c) * 1099511628211ull;
  char name[40];
  std::snprintf(name, sizeof name, "fs-%016llx-%zx", static_cast<unsigned long long>(h), key.size());
  return name;
}

bool disk_has(DiskCache* cache, const std::string& key) {
  std::lock_guard<std::mutex> lock(cache->mutex);
  return !cache->dir.empty() && cache->matches(disk_name(key), key);
}

void disk_expect(DiskCache* cache, const std::string& key) {
  std::lock_guard<std::mutex> lock(cache->mutex);
  cache->expected_key = key;
}

}  // namespace fscript::llvmjit
