// Scene files on disk, with transparent gzip (zlib; the browser build has none: its page inflates
// files before they reach the toolchain).
#include "frontend/vrml/scene_file.h"

#if defined(FS_HAVE_ZLIB)
#include <zlib.h>
#endif

#include <string>

#include "frontend/source.h"
#include "runtime/support/files.h"

namespace fscript::vrml {

#if !defined(FS_HAVE_ZLIB)
bool gunzip(const std::string&, std::string&, std::string& error) {
  error = "gzip-compressed data: this build reads only inflated scenes";
  return false;
}
#else
bool gunzip(const std::string& data, std::string& out, std::string& error) {
  z_stream z{};
  if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK) {
    error = "cannot initialise zlib";
    return false;
  }
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  out.clear();
  char buf[1 << 16];
  int rc;
  do {
    z.next_out = reinterpret_cast<Bytef*>(buf);
    z.avail_out = sizeof buf;
    rc = inflate(&z, Z_NO_FLUSH);
    if (rc != Z_OK && rc != Z_STREAM_END) {
      inflateEnd(&z);
      error = "corrupt gzip data";
      return false;
    }
    out.append(buf, sizeof buf - z.avail_out);
    if (out.size() > support::kMaxInputBytes) {
      inflateEnd(&z);
      error = "the gzip data inflates to more than " + std::to_string(support::kMaxInputBytes >> 20) +
          " MiB, the limit for one scene";
      return false;
    }
    if (out.size() > kGzipRatioFloor && out.size() / kMaxGzipRatio > z.total_in) {
      inflateEnd(&z);
      error = "the gzip data inflates more than " + std::to_string(kMaxGzipRatio) +
          " times (a compression bomb?); scenes are refused past that ratio";
      return false;
    }
  } while (rc != Z_STREAM_END);
  inflateEnd(&z);
  return true;
}
#endif

bool read_scene_text(const std::string& path, std::string& text, std::string& error) {
  std::string raw;
  if (!support::read_file(path, raw, error, support::kMaxInputBytes)) {
    error = "cannot read the file: " + error;
    return false;
  }
  if (raw.size() >= 2 && static_cast<unsigned char>(raw[0]) == 0x1f && static_cast<unsigned char>(raw[1]) == 0x8b)
    return gunzip(raw, text, error);
  text = std::move(raw);
  return true;
}

}  // namespace fscript::vrml
