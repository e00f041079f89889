#pragma once
// A registry with the framework's and every lab's pieces, as the reference app has, and the
// shipped scenes as documents.
#include <string>

#include <springlab/registry.hpp>
#include <springlab/scene_document.hpp>

namespace springlab {
void registerLabs(Registry& registry);  // generated: framework/app/register_labs.cpp
}

namespace springlab::testing {

inline const Registry& allLabs() {
  static const Registry registry = [] {
    Registry r;
    registerFramework(r);
    registerLabs(r);
    return r;
  }();
  return registry;
}

inline SceneDocument shippedScene(const std::string& name) {
  return SceneDocument::read(std::string(SPRINGLAB_SOURCE_DIR) + "/scenes/" + name);
}

}  // namespace springlab::testing
