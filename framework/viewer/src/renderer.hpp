#pragma once
// Draws a simulation with OpenGL 3.3 core: springs as lines, masses as round points,
// triangles shaded (or as wireframe) and a ground grid. It knows nothing of windows or GUI.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "springlab/simulation.hpp"

namespace springlab::viewer {

// What to draw this frame (the W key switches between the two looks of a mesh).
struct DrawOptions {
  bool masses = true;
  bool springs = true;
  bool surfaces = true;        // shaded triangles, when the scene has any
  bool surfaceWireframe = false;
  bool springsByKind = false;  // springs in the colour of their kind, not of their forces
};

class Renderer {
 public:
  Renderer() = default;
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Compile the shaders and create the buffers; needs a current GL context (after glewInit).
  bool init(std::string& error);

  // Start a frame: viewport, background colour, depth buffer.
  void clear(int width, int height);

  // A grey plane y = height with a grid of `spacing` metres, a square around centre (x, z).
  void drawGround(float height, const glm::vec2& centre, float halfSize, float spacing, const glm::mat4& viewProj);

  // A dark copy of the springs flattened onto the ground plane y = height: without it a rope
  // in the air and a rope on the ground look alike in perspective.
  void drawShadow(const Simulation& sim, float height, const glm::mat4& viewProj, float pixelScale);

  // Masses coloured by `massColors`, springs by the average of their two masses. Pinned
  // masses are drawn larger and white, the grabbed one yellow. pixelScale scales point sizes
  // (1 for an 800 pixel high window).
  void drawSimulation(const Simulation& sim, const std::vector<glm::vec3>& massColors, std::optional<int> grabbed,
                      const DrawOptions& options, const glm::mat4& viewProj, const glm::vec3& eye, float pixelScale);

  // Colliders and markers: spheres and boxes shaded, planes as a square of `planeHalfSize`
  // around their point, arrows as lines. Movable shapes are orange, fixed ones grey; the
  // shape the user drags (`held`) is yellow.
  void drawShapes(const std::vector<Shape>& shapes, std::optional<int> held, float planeHalfSize,
                  const glm::mat4& viewProj, const glm::vec3& eye, float pixelScale);

 private:
  struct Vertex {
    glm::vec3 position;
    glm::vec3 color;
    glm::vec3 normal;  // zero for unlit lines and points
  };
  enum class Shading : int { Flat = 0, Lit = 1, RoundPoint = 2 };

  void draw(unsigned mode, const std::vector<Vertex>& vertices, Shading shading, float pointSize,
            const glm::mat4& viewProj, const glm::vec3& eye);

  // One program per Shading, the same source with SHADING defined to its number.
  struct Program {
    unsigned id = 0;
    int uViewProj = -1;
    int uPointSize = -1;
    int uEye = -1;
  };
  Program programs_[3];
  // Vertices and normals built for a draw call, kept between frames so that drawing does not
  // allocate once they have grown to the scene's size.
  std::vector<Vertex> scratch_[3];
  std::vector<glm::vec3> normals_;
  unsigned vao_ = 0;
  unsigned vbo_ = 0;
  float maxLineWidth_ = 1.0f;
};

}  // namespace springlab::viewer
