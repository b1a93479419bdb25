// llvm::ObjectCache over files: <hash>.o and <hash>.key, written atomically (temporary + rename).
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
    write(base + ".key", expected_key.data(), expected_key.size());
    write(base + ".o", obj.getBufferStart(), obj.getBufferSize());
  }
  std::unique_ptr<llvm::MemoryBuffer> getObject(const llvm::Module* m) override {
    std::lock_guard<std::mutex> lock(mutex);
    if (dir.empty() || !matches(m->getModuleIdentifier(), expected_key)) return nullptr;
    auto buffer = llvm::MemoryBuffer::getFile((fs::path(dir) / (m->getModuleIdentifier() + ".o")).string());
    return buffer ? std::move(*buffer) : nullptr;
  }
  bool matches(const std::string& name, const std::string& key) {
    std::ifstream in(fs::path(dir) / (name + ".key"), std::ios::binary);
    if (!in) return false;
    std::ostringstream text;
    text << in.rdbuf();
    return text.str() == key && fs::exists(fs::path(dir) / (name + ".o"));
  }

 private:
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

llvm::Expected<std::unique_ptr<llvm::orc::IRCompileLayer::IRCompiler>> make_compiler(
    llvm::orc::JITTargetMachineBuilder jtmb, DiskCache* cache) {
  auto tm = jtmb.createTargetMachine();
  if (!tm) return tm.takeError();
  return std::make_unique<llvm::orc::TMOwningSimpleCompiler>(std::move(*tm), cache);
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
