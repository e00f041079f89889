#pragma once
// Writing the frame being drawn to a PNG file.
#include <string>

namespace springlab::viewer {

// Read the back buffer (call after ImGui rendered and before the swap, so the overlay is in
// the picture) and write it as an RGB PNG. Returns false and sets `error` on failure.
bool writeSnapshot(const std::string& path, int width, int height, std::string& error);

// A fresh file name in the current folder: springlab-YYYYMMDD-HHMMSS.png (-2, -3, ... if taken).
std::string screenshotName();

}  // namespace springlab::viewer
