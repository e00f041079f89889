#include "renderer.hpp"
#include "gl.hpp"
#include "to_glm.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <glm/gtc/type_ptr.hpp>

namespace springlab::viewer {

namespace {

// Structural, shear, bend and extra springs: four colours told apart at a glance.
glm::vec3 springKindColor(SpringKind kind) {
  switch (kind) {
    case SpringKind::Structural: return {0.35f, 0.65f, 1.0f};
    case SpringKind::Shear: return {0.35f, 0.9f, 0.45f};
    case SpringKind::Bend: return {1.0f, 0.6f, 0.2f};
    case SpringKind::Extra: break;
  }
  return {0.85f, 0.4f, 0.95f};
}

// The triangles of a unit UV sphere, their corners being their normals: made once.
const std::vector<glm::vec3>& unitSphere() {
  static const std::vector<glm::vec3> corners = [] {
    // 16 x 32 quads: round at the size colliders are drawn, and a quarter of the triangles
    // of 24 x 48 for a software renderer to set up.
    const int rings = 16, segments = 32;
    auto point = [&](int i, int j) {
      const float theta = 3.14159265f * static_cast<float>(i) / static_cast<float>(rings);
      const float phi = 6.28318531f * static_cast<float>(j) / static_cast<float>(segments);
      return glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    };
    std::vector<glm::vec3> v;
    v.reserve(6 * rings * segments);
    for (int i = 0; i < rings; ++i) {
      for (int j = 0; j < segments; ++j) {
        const glm::vec3 n00 = point(i, j), n10 = point(i + 1, j), n11 = point(i + 1, j + 1), n01 = point(i, j + 1);
        for (const glm::vec3& n : {n00, n10, n11, n00, n11, n01}) v.push_back(n);
      }
    }
    return v;
  }();
  return corners;
}

// Two unit vectors completing n (unit) to an orthonormal frame.
std::pair<glm::vec3, glm::vec3> tangents(const glm::vec3& n) {
  const glm::vec3 helper = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 t = glm::normalize(glm::cross(helper, n));
  return {t, glm::cross(n, t)};
}

// One shader source, compiled three times: flat colours for lines and the grid, a two-sided
// headlight for triangles (cloth has no inside), and round points cut out of square point
// sprites. Three programs rather than one with a branch on a uniform: llvmpipe (software
// OpenGL) pays per pixel for every varying and instruction, and most pixels are flat.
const char* const kVertexShader = R"(
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aColor;
layout(location = 2) in vec3 aNormal;
uniform mat4 uViewProj;
uniform float uPointSize;
out vec3 vColor;
#if SHADING == 1
out vec3 vNormal;
out vec3 vPosition;
#endif
void main() {
  gl_Position = uViewProj * vec4(aPosition, 1.0);
#if SHADING == 2
  gl_PointSize = uPointSize;
#endif
  vColor = aColor;
#if SHADING == 1
  vNormal = aNormal;
  vPosition = aPosition;
#endif
}
)";

const char* const kFragmentShader = R"(
in vec3 vColor;
#if SHADING == 1
in vec3 vNormal;
in vec3 vPosition;
uniform vec3 uEye;
#endif
out vec4 fragColor;
void main() {
  vec3 c = vColor;
#if SHADING == 1
  vec3 n = normalize(vNormal);
  vec3 l = normalize(uEye - vPosition);
  c *= 0.35 + 0.65 * abs(dot(n, l));
#elif SHADING == 2
  vec2 d = 2.0 * gl_PointCoord - 1.0;
  float r2 = dot(d, d);
  if (r2 > 1.0) discard;
  c *= 1.0 - 0.35 * r2;  // a hint of a sphere
#endif
  fragColor = vec4(c, 1.0);
}
)";

GLuint compile(GLenum type, const char* header, const char* source, std::string& error) {
  const GLuint shader = glCreateShader(type);
  const char* sources[2] = {header, source};
  glShaderSource(shader, 2, sources, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    error = std::string("shader compilation failed: ") + log;
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

}  // namespace

Renderer::~Renderer() {
  if (vbo_) glDeleteBuffers(1, &vbo_);
  if (vao_) glDeleteVertexArrays(1, &vao_);
  for (const Program& p : programs_) {
    if (p.id) glDeleteProgram(p.id);
  }
}

bool Renderer::init(std::string& error) {
  for (int shading = 0; shading < 3; ++shading) {
    const std::string header = std::string(kGlslVersion) + "#define SHADING " + std::to_string(shading) + "\n";
    const GLuint vs = compile(GL_VERTEX_SHADER, header.c_str(), kVertexShader, error);
    if (!vs) return false;
    const GLuint fs = compile(GL_FRAGMENT_SHADER, header.c_str(), kFragmentShader, error);
    if (!fs) {
      glDeleteShader(vs);
      return false;
    }
    Program& p = programs_[shading];
    p.id = glCreateProgram();
    glAttachShader(p.id, vs);
    glAttachShader(p.id, fs);
    glLinkProgram(p.id);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(p.id, GL_LINK_STATUS, &ok);
    if (!ok) {
      char log[2048] = {};
      glGetProgramInfoLog(p.id, sizeof log, nullptr, log);
      error = std::string("shader linking failed: ") + log;
      return false;
    }
    // -1 for the uniforms a variant does not use: glUniform ignores those.
    p.uViewProj = glGetUniformLocation(p.id, "uViewProj");
    p.uPointSize = glGetUniformLocation(p.id, "uPointSize");
    p.uEye = glGetUniformLocation(p.id, "uEye");
  }

  // One streaming buffer, refilled for every draw call (a few thousand vertices at most).
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  const auto stride = static_cast<GLsizei>(sizeof(Vertex));
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Vertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Vertex, color)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Vertex, normal)));
  glBindVertexArray(0);

  // Wide lines are optional in the core profile: use them only where the driver has them.
  GLfloat range[2] = {1.0f, 1.0f};
  glGetFloatv(GL_ALIASED_LINE_WIDTH_RANGE, range);
  maxLineWidth_ = range[1];
  while (glGetError() != GL_NO_ERROR) {
  }
  return true;
}

void Renderer::clear(int width, int height) {
  glViewport(0, 0, width, height);
  glClearColor(0.11f, 0.12f, 0.15f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
#ifndef SPRINGLAB_GLES3
  glEnable(GL_PROGRAM_POINT_SIZE);  // (always on in OpenGL ES)
#endif
}

void Renderer::draw(unsigned mode, const std::vector<Vertex>& vertices, Shading shading, float pointSize,
                    const glm::mat4& viewProj, const glm::vec3& eye) {
  if (vertices.empty()) return;
  const Program& p = programs_[static_cast<int>(shading)];
  glUseProgram(p.id);
  glUniformMatrix4fv(p.uViewProj, 1, GL_FALSE, glm::value_ptr(viewProj));
  glUniform1f(p.uPointSize, pointSize);
  glUniform3fv(p.uEye, 1, glm::value_ptr(eye));
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  // Orphan and refill: the driver hands out fresh storage while earlier draws still read the
  // old one, so no draw waits for another.
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(Vertex)), vertices.data(),
               GL_STREAM_DRAW);
  glDrawArrays(mode, 0, static_cast<GLsizei>(vertices.size()));
  glBindVertexArray(0);
}

void Renderer::drawGround(float height, const glm::vec2& centre, float halfSize, float spacing,
                          const glm::mat4& viewProj) {
  // The plane, then the grid lines a hair above it so that they win the depth test.
  const glm::vec3 plane(0.22f, 0.23f, 0.26f);
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  const float x0 = centre.x - halfSize, x1 = centre.x + halfSize;
  const float z0 = centre.y - halfSize, z1 = centre.y + halfSize;
  std::vector<Vertex>& quad = scratch_[0];
  quad.assign({
      {{x0, height, z0}, plane, up}, {{x1, height, z0}, plane, up}, {{x1, height, z1}, plane, up},
      {{x0, height, z0}, plane, up}, {{x1, height, z1}, plane, up}, {{x0, height, z1}, plane, up},
  });
  draw(GL_TRIANGLES, quad, Shading::Flat, 1.0f, viewProj, glm::vec3(0.0f));

  const glm::vec3 line(0.34f, 0.36f, 0.40f);
  const float y = height + 1e-3f * halfSize;
  std::vector<Vertex>& grid = scratch_[0];
  grid.clear();
  const int n = static_cast<int>(std::floor(halfSize / spacing));
  for (int i = -n; i <= n; ++i) {
    const float x = centre.x + static_cast<float>(i) * spacing;
    const float z = centre.y + static_cast<float>(i) * spacing;
    grid.push_back({{x, y, z0}, line, {}});
    grid.push_back({{x, y, z1}, line, {}});
    grid.push_back({{x0, y, z}, line, {}});
    grid.push_back({{x1, y, z}, line, {}});
  }
  glLineWidth(1.0f);
  draw(GL_LINES, grid, Shading::Flat, 1.0f, viewProj, glm::vec3(0.0f));
}

void Renderer::drawShadow(const Simulation& sim, float height, const glm::mat4& viewProj, float pixelScale) {
  const auto& pos = sim.state.pos;
  const glm::vec3 shade(0.07f, 0.075f, 0.085f);
  auto flat = [&](int i) {
    const glm::vec3 p = toGlm(pos[i]);
    return glm::vec3(p.x, height, p.z);
  };
  std::vector<Vertex>& lines = scratch_[0];
  lines.clear();
  for (const Spring& s : sim.springs()) {
    if (s.mass1 < 0 || s.mass2 < 0 || static_cast<std::size_t>(std::max(s.mass1, s.mass2)) >= pos.size()) continue;
    lines.push_back({flat(s.mass1), shade, {}});
    lines.push_back({flat(s.mass2), shade, {}});
  }
  // Drawn right after the ground and before the system: nothing but the ground can be under
  // it, so the depth test is off (no fighting with the plane).
  glDisable(GL_DEPTH_TEST);
  glLineWidth(std::min(3.0f * pixelScale, maxLineWidth_));
  draw(GL_LINES, lines, Shading::Flat, 1.0f, viewProj, glm::vec3(0.0f));
  glLineWidth(1.0f);
  glEnable(GL_DEPTH_TEST);
}

void Renderer::drawSimulation(const Simulation& sim, const std::vector<glm::vec3>& massColors,
                              std::optional<int> grabbed, const DrawOptions& options, const glm::mat4& viewProj,
                              const glm::vec3& eye, float pixelScale) {
  const auto& pos = sim.state.pos;
  const std::size_t n = std::min(pos.size(), massColors.size());
  auto valid = [n](int i) { return i >= 0 && static_cast<std::size_t>(i) < n; };

  // Triangles: smooth normals (the sum of the faces around each mass), a cloth colour tinted
  // by the force colours.
  if (options.surfaces && !sim.triangles.empty()) {
    std::vector<glm::vec3>& normals = normals_;
    normals.assign(n, glm::vec3(0.0f));
    for (const Triangle& t : sim.triangles) {
      if (!valid(t.a) || !valid(t.b) || !valid(t.c)) continue;
      const glm::vec3 a = toGlm(pos[t.a]), b = toGlm(pos[t.b]), c = toGlm(pos[t.c]);
      const glm::vec3 face = glm::cross(b - a, c - a);
      normals[t.a] += face;
      normals[t.b] += face;
      normals[t.c] += face;
    }
    const glm::vec3 cloth(0.55f, 0.65f, 0.85f);
    for (glm::vec3& normal : normals) {
      const float len = glm::length(normal);
      normal = len > 0.0f ? normal / len : glm::vec3(0, 1, 0);
    }
    std::vector<Vertex>& tris = scratch_[0];
    tris.clear();
    auto vertex = [&](int i) { return Vertex{toGlm(pos[i]), glm::mix(cloth, massColors[i], 0.3f), normals[i]}; };
    for (const Triangle& t : sim.triangles) {
      if (!valid(t.a) || !valid(t.b) || !valid(t.c)) continue;
      if (options.surfaceWireframe) {
        // The wireframe as the triangles' edges (OpenGL ES has no glPolygonMode): a, b; b, c;
        // c, a. An edge two triangles share is drawn twice, over itself.
        for (int i : {t.a, t.b, t.b, t.c, t.c, t.a}) tris.push_back(vertex(i));
      } else {
        for (int i : {t.a, t.b, t.c}) tris.push_back(vertex(i));
      }
    }
    if (options.surfaceWireframe) {
      draw(GL_LINES, tris, Shading::Flat, 1.0f, viewProj, eye);
    } else {
      draw(GL_TRIANGLES, tris, Shading::Lit, 1.0f, viewProj, eye);
    }
  }

  // Springs, coloured by the average force colour of their ends.
  if (options.springs) {
    std::vector<Vertex>& lines = scratch_[0];
    lines.clear();
    for (const Spring& s : sim.springs()) {
      if (!valid(s.mass1) || !valid(s.mass2)) continue;
      const glm::vec3 c = options.springsByKind ? springKindColor(s.kind)
                                                : 0.5f * (massColors[s.mass1] + massColors[s.mass2]);
      lines.push_back({toGlm(pos[s.mass1]), c, {}});
      lines.push_back({toGlm(pos[s.mass2]), c, {}});
    }
    glLineWidth(std::min(2.0f * pixelScale, maxLineWidth_));
    draw(GL_LINES, lines, Shading::Flat, 1.0f, viewProj, eye);
    glLineWidth(1.0f);
  }

  // Masses: free ones in their force colour, pinned ones larger and white, the grabbed one
  // yellow (drawn last, so it is on top of its neighbours).
  if (options.masses) {
    std::vector<Vertex>&free = scratch_[0], &pinned = scratch_[1], &held = scratch_[2];
    free.clear();
    pinned.clear();
    held.clear();
    for (std::size_t i = 0; i < n; ++i) {
      if (grabbed && static_cast<std::size_t>(*grabbed) == i) {
        held.push_back({toGlm(pos[i]), glm::vec3(1.0f, 0.9f, 0.2f), {}});
      } else if (i < sim.masses.size() && sim.masses[i].pinned) {
        pinned.push_back({toGlm(pos[i]), glm::vec3(0.95f, 0.95f, 1.0f), {}});
      } else {
        free.push_back({toGlm(pos[i]), massColors[i], {}});
      }
    }
    draw(GL_POINTS, free, Shading::RoundPoint, 8.0f * pixelScale, viewProj, eye);
    draw(GL_POINTS, pinned, Shading::RoundPoint, 12.0f * pixelScale, viewProj, eye);
    draw(GL_POINTS, held, Shading::RoundPoint, 14.0f * pixelScale, viewProj, eye);
  }
}

void Renderer::drawShapes(const std::vector<Shape>& shapes, std::optional<int> held, float planeHalfSize,
                          const glm::mat4& viewProj, const glm::vec3& eye, float pixelScale) {
  std::vector<Vertex>&tris = scratch_[0], &lines = scratch_[1];
  tris.clear();
  lines.clear();
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const Shape& shape = shapes[k];
    const glm::vec3 color = held && static_cast<std::size_t>(*held) == k ? glm::vec3(1.0f, 0.9f, 0.2f)
                            : shape.movable                               ? glm::vec3(0.95f, 0.55f, 0.2f)
                                                                          : glm::vec3(0.6f, 0.6f, 0.62f);
    const glm::vec3 c = toGlm(shape.center);
    switch (shape.type) {
      case ShapeType::Sphere: {
        // A UV sphere, slightly smaller than the collider so that cloth resting on it shows.
        const float r = 0.985f * static_cast<float>(shape.radius);
        for (const glm::vec3& n : unitSphere()) tris.push_back({c + r * n, color, n});
        break;
      }
      case ShapeType::Plane: {
        const glm::vec3 n = glm::normalize(toGlm(shape.normal));
        const auto [t, b] = tangents(n);
        const float h = planeHalfSize;
        const glm::vec3 p00 = c - h * t - h * b, p10 = c + h * t - h * b, p11 = c + h * t + h * b,
                        p01 = c - h * t + h * b;
        for (const glm::vec3& p : {p00, p10, p11, p00, p11, p01}) tris.push_back({p, 0.8f * color, n});
        break;
      }
      case ShapeType::Box: {
        const glm::vec3 e = toGlm(shape.halfExtents);
        // Each face: its normal and two in-plane axes, scaled by the half extents.
        for (int axis = 0; axis < 3; ++axis) {
          for (float side : {-1.0f, 1.0f}) {
            glm::vec3 n(0.0f), u(0.0f), v(0.0f);
            n[axis] = side;
            u[(axis + 1) % 3] = e[(axis + 1) % 3];
            v[(axis + 2) % 3] = e[(axis + 2) % 3];
            const glm::vec3 f = c + n * e[axis];
            for (const glm::vec3& p : {f - u - v, f + u - v, f + u + v, f - u - v, f + u + v, f - u + v}) {
              tris.push_back({p, color, n});
            }
          }
        }
        break;
      }
      case ShapeType::Arrow: {
        const glm::vec3 a = toGlm(shape.arrow);
        const float len = glm::length(a);
        if (len <= 0.0f) break;
        const glm::vec3 tip = c + a, d = a / len;
        const auto [t, b] = tangents(d);
        lines.push_back({c, color, {}});
        lines.push_back({tip, color, {}});
        for (const glm::vec3& side : {t, -t, b, -b}) {
          lines.push_back({tip, color, {}});
          lines.push_back({tip - 0.2f * len * d + 0.08f * len * side, color, {}});
        }
        break;
      }
    }
  }
  draw(GL_TRIANGLES, tris, Shading::Lit, 1.0f, viewProj, eye);
  glLineWidth(std::min(3.0f * pixelScale, maxLineWidth_));
  draw(GL_LINES, lines, Shading::Flat, 1.0f, viewProj, eye);
  glLineWidth(1.0f);
}

}  // namespace springlab::viewer
