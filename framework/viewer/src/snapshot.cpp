#include "snapshot.hpp"

#include <GL/glew.h>

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
  std::vector<unsigned char> pixels(w * h * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());

  // OpenGL's rows run bottom-up, PNG's top-down.
  std::vector<unsigned char> flipped(pixels.size());
  for (std::size_t row = 0; row < h; ++row) {
    std::copy_n(pixels.begin() + static_cast<std::ptrdiff_t>((h - 1 - row) * w * 3), w * 3,
                flipped.begin() + static_cast<std::ptrdiff_t>(row * w * 3));
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
