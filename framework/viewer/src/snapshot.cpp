#include "snapshot.hpp"

#include "gl.hpp"

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <vector>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

namespace springlab::viewer {

bool writeSnapshot(const std::string& path, int width, int height, std::string& error) {
  if (width <= 0 || height <= 0) {
    error = "the window has no pixels to save";
    return false;
  }
  const auto w = static_cast<std::size_t>(width);
  const auto h = static_cast<std::size_t>(height);
  // RGBA, the one format OpenGL ES (WebGL2) is sure to read.
  std::vector<unsigned char> pixels(w * h * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());

  // OpenGL's rows run bottom-up, PNG's top-down; the alpha channel is left out.
  std::vector<unsigned char> flipped(w * h * 3);
  for (std::size_t row = 0; row < h; ++row) {
    const unsigned char* from = pixels.data() + (h - 1 - row) * w * 4;
    unsigned char* to = flipped.data() + row * w * 3;
    for (std::size_t x = 0; x < w; ++x) std::copy_n(from + 4 * x, 3, to + 3 * x);
  }
  if (!stbi_write_png(path.c_str(), width, height, 3, flipped.data(), width * 3)) {
    error = "could not write " + path;
    return false;
  }
  return true;
}

std::string screenshotName() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &local);
  std::string name = std::string("springlab-") + stamp + ".png";
  for (int k = 2; std::filesystem::exists(name); ++k) {
    name = std::string("springlab-") + stamp + "-" + std::to_string(k) + ".png";
  }
  return name;
}

}  // namespace springlab::viewer
