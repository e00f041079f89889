// springlab-web-<lab>: the viewer on one scene in the browser page (index.html). The page
// passes the URL's choices as arguments: main.js's Module.arguments.
//   --scene FILE     a scene in /scenes (preloaded from scenes/), e.g. rope.json
//   --paused         start paused (the tests step it through the hook instead)
//   --compact        the panel collapsed to its title bar (?embed: a frame in a handout)
//   --width W --height H   the canvas in CSS pixels
#include <cstdlib>
#include <iostream>
#include <string>

#include <springlab/registry.hpp>
#include <springlab/viewer.hpp>

namespace springlab {
void registerLabs(Registry& registry);  // register_<lab>.cpp, generated
}

int main(int argc, char** argv) {
  using namespace springlab;
  // The page runs the frames after main returns: what the viewer refers to lives on.
  static Registry registry;
  registerFramework(registry);
  registerLabs(registry);

  ViewerOptions options;
  options.tree = SPRINGLAB_TREE;
  std::string scene;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--scene" && hasValue) {
      scene = argv[++i];
    } else if (arg == "--paused") {
      options.paused = true;
    } else if (arg == "--compact") {
      options.compact = true;
    } else if (arg == "--width" && hasValue) {
      options.width = std::atoi(argv[++i]);
    } else if (arg == "--height" && hasValue) {
      options.height = std::atoi(argv[++i]);
    } else {
      std::cerr << "springlab web: unknown argument " << arg << "\n";
      return 1;
    }
  }
  if (scene.empty() || scene.find('/') != std::string::npos) {
    std::cerr << "springlab web: name a scene file of scenes/ (?scene=rope.json)\n";
    return 1;
  }
  return runViewer(registry, "/scenes/" + scene, options);
}
