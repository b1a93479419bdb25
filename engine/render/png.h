#pragma once
// PNG output through libpng. Writes to a temporary file beside the target and renames it, so a
// failed write never leaves a half-written picture.
#include <cstdint>
#include <string>
#include <vector>

namespace fscript::render {

// channels: 1 (grey), 3 (RGB) or 4 (RGBA); pixels row-major from the top row.
bool write_png(const std::string& path, uint32_t width, uint32_t height, int channels,
               const std::vector<uint8_t>& pixels, std::string& error);

}  // namespace fscript::render
