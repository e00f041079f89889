// The viewer's window, main loop and input. Rendering (renderer.cpp), the GUI (panel.cpp),
// the camera (camera.cpp), picking (picking.cpp) and screenshots (snapshot.cpp) live apart;
// this file ties them to one Simulation and keeps running whatever the simulation throws.
#include "springlab/viewer.hpp"

#include "gl.hpp"
// The GL header before GLFW: GLFW must not pull in the system's gl.h first.
#include <GLFW/glfw3.h>
#ifdef __EMSCRIPTEN__
#include <emscripten.h>
#endif
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "springlab/energy_source.hpp"
#include "springlab/parameter.hpp"

#include "camera.hpp"
#include "force_colors.hpp"
#include "panel.hpp"
#include "picking.hpp"
#include "renderer.hpp"
#include "snapshot.hpp"
#include "step_limit_worker.hpp"
#include "to_glm.hpp"

namespace springlab {

namespace {

using viewer::toGlm;

using viewer::Camera;
using viewer::MissingExercise;
using viewer::RunControl;

constexpr double kControlSpeed = 3.0;  // m/s, the fixed end while an arrow key is held
constexpr float kPickPixels = 25.0f;   // how far from a mass a click may land

MissingExercise missingFrom(const NotImplemented& e) { return {e.exerciseId(), e.title(), e.handoutSection()}; }

// The scene: what loadScene gave, or only the settings when building it threw NotImplemented.
struct Scene {
  std::string path;  // the scene file, loaded again for the dt warning's copy
  SceneSettings settings;
  std::unique_ptr<Simulation> sim;
  std::optional<MissingExercise> missingAtLoad;
};

// The region the camera frames at the start and the ground drawn under it.
struct Framing {
  glm::vec3 lo{-2.0f, -1.5f, -2.0f};
  glm::vec3 hi{2.0f, 0.5f, 2.0f};
  float groundHeight = -1.5f;
};

Framing frameScene(const Simulation* sim) {
  Framing f;
  if (!sim || sim->state.pos.empty()) return f;
  // The scene's reach with a margin (a rope gives all it can reach, others their bounding
  // box); the ground where the scene has one, else under the lowest point.
  const Bounds reach = sim->reach();
  const glm::vec3 lo = toGlm(reach.lo), hi = toGlm(reach.hi);
  const float margin = 0.03f * std::max(glm::length(hi - lo), 0.1f);
  f.lo = lo - glm::vec3(margin);
  f.hi = hi + glm::vec3(margin);
  if (sim->dimension == 2) f.lo.z = f.hi.z = 0.5f * (lo.z + hi.z);
  f.groundHeight = sim->groundHeight() ? static_cast<float>(*sim->groundHeight()) : lo.y;
  return f;
}

// Whether the current context renders on the CPU (Mesa's llvmpipe or softpipe, and the like).
bool softwareRenderer() {
  const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (!name) return false;
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const char* software : {"llvmpipe", "softpipe", "software", "swrast"}) {
    if (lower.find(software) != std::string::npos) return true;
  }
  return false;
}

// A round grid spacing (1, 2 or 5 times a power of ten) giving about ten lines per half side.
float gridSpacing(float halfSize) {
  const float raw = halfSize / 10.0f;
  const float decade = std::pow(10.0f, std::floor(std::log10(raw)));
  for (float m : {1.0f, 2.0f, 5.0f}) {
    if (m * decade >= raw) return m * decade;
  }
  return 10.0f * decade;
}

// Time summed over some frames: all of each frame, and the part spent stepping the physics.
struct FrameTimes {
  int frames = 0;
  double seconds = 0.0;
  double physicsSeconds = 0.0;

  void add(double frame, double physics) {
    ++frames;
    seconds += frame;
    physicsSeconds += physics;
  }
  viewer::FrameRate rate() const {
    viewer::FrameRate r;
    if (frames == 0 || seconds <= 0.0) return r;
    r.fps = static_cast<float>(frames / seconds);
    r.physicsMs = static_cast<float>(1e3 * physicsSeconds / frames);
    r.drawMs = static_cast<float>(1e3 * (seconds - physicsSeconds) / frames);
    return r;
  }
};

// The viewer of this process, for liveViewer(); set while one runs.
LiveViewer* live = nullptr;

// Everything the window owns; GLFW callbacks find it through the window's user pointer.
class Viewer : public LiveViewer {
 public:
  Viewer(const Registry& registry, Scene scene, const ViewerOptions& options)
      : registry_(registry), options_(options), scene_(std::move(scene)) {
    control_.dt = scene_.settings.dt > 0.0 ? scene_.settings.dt : 0.002;
    control_.substeps = std::max(scene_.settings.substeps, 1);
    control_.paused = options.paused;
    control_.panelCollapsed = options.compact;
    missing_ = scene_.missingAtLoad;
  }
  ~Viewer() override {
    if (live == this) live = nullptr;
  }

  // Open the window, run the frames, close. In the browser it returns after the first steps:
  // the page calls the frames (browserFrame), and the viewer must outlive the call.
  int run();

  // LiveViewer: the page's hook.
  Simulation* simulation() override { return scene_.sim.get(); }
  int substeps() const override { return control_.substeps; }
  double dt() const override { return control_.dt; }
  std::string integratorName() const override {
    return scene_.sim ? scene_.sim->integrator().name() : scene_.settings.integrator;
  }
  std::string problem() const override {
    if (missing_) return "exercise " + missing_->id + " (" + missing_->title + ") is not implemented yet; see " +
                         missing_->handoutSection;
    return runError_;
  }
  void stepFrames(int frames) override {
    for (int k = 0; k < frames; ++k) {
      control_.stepRequested = true;
      advance();
    }
  }
  void setPaused(bool paused) override { control_.paused = paused; }
  void resize(int width, int height) override {
    if (window_ && width > 0 && height > 0) glfwSetWindowSize(window_, width, height);
  }

 private:
  enum class Drag { None, Orbit, Zoom, Pan, Grab, MoveShape };

  static Viewer& from(GLFWwindow* window) { return *static_cast<Viewer*>(glfwGetWindowUserPointer(window)); }
  void onKey(int key, int action, int mods);
  void onMouseButton(int button, int action, int mods);
  void onCursor(double x, double y);
  void onScroll(double dy);

  bool openWindow();
  void closeWindow();
  // run() in three parts: the window and the GUI made (0, or the exit code); one frame with
  // `physicsFrames` frames of physics (false after the last of a --frames run); the report of
  // a --frames run, the window closed (the exit code).
  int start();
  bool frame(int physicsFrames);
#ifdef __EMSCRIPTEN__
  void browserFrame();
#endif
  int finish();
  viewer::Ray cursorRay() const;
  std::optional<int> pickUnderCursor() const;

  // One frame: apply requests and held keys, draw, step.
  void interact();
  void advance();
  void draw(bool last);
  void drawGui(bool last);

  // Runs f; a missing exercise or a failing simulation is shown instead of ending the viewer.
  template <class F>
  void guarded(F&& f);

  const Registry& registry_;
  const ViewerOptions options_;
  Scene scene_;
  RunControl control_;
  Camera camera_;
  Framing framing_;
  std::unique_ptr<viewer::Renderer> renderer_;
  std::vector<glm::vec3> massColors_;  // this frame's force colours, kept between frames
  std::vector<float> colorWork_;
  GLFWwindow* window_ = nullptr;
  bool imguiReady_ = false;

  std::optional<MissingExercise> missing_;
  std::string runErrorHeadline_;
  std::string runError_;  // empty while the run is fine
  bool blewUp_ = false;   // the run stopped on a blow-up (a headless run then exits 4, as `sim`)
  // A force term that feeds energy in (energySourceWarning), tested every kEnergyCheckFrames
  // stepped frames and named once on the terminal.
  static constexpr long kEnergyCheckFrames = 60;
  long steppedFrames_ = 0;
  bool energyWarned_ = false;
  // The dt warning: the exact limit of the step that runs (stepStableDt), computed on a copy
  // of the scene beside the frames; again when the method or a parameter changes.
  void requestStepLimit();
  viewer::StepLimitWorker stepLimit_;
  bool stepLimitStale_ = true;
  std::string stepLimitNoted_;  // the last warning printed on the terminal (printed once)
  static constexpr double kLastFrameWait = 30.0;  // s a --frames run's last frame waits for the limit
  // The HUD's energies and observables, and the simulated time and wall time they are of.
  struct HudNumbers {
    double time = 0.0;
    std::chrono::steady_clock::time_point computed;
    Energies energies;
    std::vector<Observable> observables;
  };
  std::optional<HudNumbers> hudNumbers_;

  Drag drag_ = Drag::None;
  double cursorX_ = 0.0, cursorY_ = 0.0;
  std::optional<int> grabbed_;
  glm::vec3 grabPlanePoint_{0.0f};
  Vec3 grabFrom_ = Vec3::Zero();    // where the grabbed mass was held at the last frame
  Vec3 grabTarget_ = Vec3::Zero();  // where the cursor holds it now
  Vec3 controlVelocity_ = Vec3::Zero();
  std::optional<int> heldShape_;     // index into the scene's shapes() while Ctrl-dragging
  Vec3 shapeFrom_ = Vec3::Zero();    // where the held shape was at the last frame
  Vec3 shapeTarget_ = Vec3::Zero();  // where the cursor holds it now

  // Frame rate and where the time goes, over half-second windows for the HUD (recent_, rate_) and
  // over the whole run for --frames (total_, from the end of the first frame).
  viewer::FrameRate rate_;
  FrameTimes recent_, total_;
  int frameNumber_ = 0;
  std::chrono::steady_clock::time_point frameStart_;
  int exitCode_ = 0;
  double browserTime_ = -1.0;   // s, the page's clock at the last frame
  double browserBacklog_ = 0.0;  // s of wall time the physics has not caught up with yet
};

template <class F>
void Viewer::guarded(F&& f) {
  try {
    f();
  } catch (const NotImplemented& e) {
    // The student's next exercise: say which, stop stepping, keep drawing.
    if (!missing_) std::cerr << "springlab view: " << e.what() << "\n";
    missing_ = missingFrom(e);
  } catch (const BlowUp& e) {
    control_.paused = true;
    blewUp_ = true;
    runErrorHeadline_ = "Paused";
    runError_ = e.what();
    std::cerr << "springlab view: " << e.what() << "\n";
  } catch (const std::exception& e) {
    control_.paused = true;
    runErrorHeadline_ = "Paused, the simulation failed";
    runError_ = e.what();
    std::cerr << "springlab view: " << e.what() << "\n";
  }
}

bool Viewer::openWindow() {
  // OpenGL 3.3 core, with 4x multisampling where the GPU does it in hardware.
  glfwSetErrorCallback([](int, const char* description) { std::cerr << "glfw: " << description << "\n"; });
  if (!glfwInit()) return false;
#ifdef SPRINGLAB_GLES3
  // OpenGL ES 3.0: WebGL2 in the browser.
  glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
#else
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
#endif
#ifdef __APPLE__
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
#endif
  // Hidden until we know the renderer: a software one (llvmpipe under Xvfb, or a machine
  // without a GPU driver) shades every sample of every pixel on the CPU, and 4x multisampling
  // cost it two thirds of its frame rate. Then the window is made again without.
  glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  const std::string title = "springlab: " + scene_.settings.name + " (" + options_.tree + ")";
  for (const int samples : {4, 0}) {
    glfwWindowHint(GLFW_SAMPLES, samples);
    window_ = glfwCreateWindow(std::max(options_.width, 64), std::max(options_.height, 64), title.c_str(), nullptr,
                               nullptr);
    if (!window_) continue;  // no multisampled visual: try without
    glfwMakeContextCurrent(window_);
    if (samples == 0 || !softwareRenderer()) break;
    glfwDestroyWindow(window_);
    window_ = nullptr;
  }
  if (!window_) {
    glfwTerminate();
    return false;
  }
  glfwShowWindow(window_);
#ifndef __EMSCRIPTEN__
  // Interactive runs follow the display; --frames runs as fast as it can. (The browser
  // always follows the display: requestAnimationFrame.)
  glfwSwapInterval(options_.frames > 0 ? 0 : 1);
#endif
  return true;
}

void Viewer::closeWindow() {
  renderer_.reset();  // while its context is still current
  if (imguiReady_) {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    imguiReady_ = false;
  }
  if (window_) glfwDestroyWindow(window_);
  window_ = nullptr;
  glfwTerminate();
}

int Viewer::run() {
  if (const int code = start()) return code;
  live = this;
#ifdef __EMSCRIPTEN__
  // The page calls the frames from requestAnimationFrame; this returns at once.
  emscripten_set_main_loop_arg([](void* self) { static_cast<Viewer*>(self)->browserFrame(); }, this, 0, false);
  return 0;
#else
  while (!glfwWindowShouldClose(window_) && frame(1)) {
  }
  return finish();
#endif
}

int Viewer::start() {
  if (!openWindow()) {
    std::cerr << "springlab view: no display: run under xvfb-run, or use `./springlab run` which does it for you\n";
    return 6;
  }

#ifndef SPRINGLAB_GLES3
  glewExperimental = GL_TRUE;
  const GLenum glewStatus = glewInit();
  if (glewStatus != GLEW_OK) {
    std::cerr << "springlab view: could not load OpenGL functions: "
              << reinterpret_cast<const char*>(glewGetErrorString(glewStatus)) << "\n";
    closeWindow();
    return 6;
  }
  while (glGetError() != GL_NO_ERROR) {
  }  // glewInit may leave an error behind in a core context
#endif

  renderer_ = std::make_unique<viewer::Renderer>();
  std::string error;
  if (!renderer_->init(error)) {
    std::cerr << "springlab view: " << error << "\n";
    closeWindow();
    return 6;
  }

  // Our callbacks first: ImGui's backend installs its own and chains to these.
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int mods) { from(w).onKey(key, action, mods); });
  glfwSetMouseButtonCallback(window_,
                             [](GLFWwindow* w, int b, int action, int mods) { from(w).onMouseButton(b, action, mods); });
  glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) { from(w).onCursor(x, y); });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) { from(w).onScroll(dy); });

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the student's folder
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
#ifdef SPRINGLAB_GLES3
  ImGui_ImplOpenGL3_Init("#version 300 es");
#else
  ImGui_ImplOpenGL3_Init("#version 330 core");
#endif
  imguiReady_ = true;

  // Frame the region the scene can reach, in the part of the window between the HUD (top
  // left, about 250 pixels wide) and the control panel (top right, about 390 wide but only as
  // high as its sliders: 300 kept free of it), so neither
  // hides the scene; a narrow window keeps at least its middle half.
  framing_ = frameScene(scene_.sim.get());
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  const float w = static_cast<float>(std::max(width, 1));
  const float freeLeft = std::min(250.0f / w, 0.25f), freeRight = std::max(1.0f - 300.0f / w, 0.75f);
  camera_.frame(framing_.lo, framing_.hi, w / static_cast<float>(std::max(height, 1)), freeLeft, freeRight);

  frameStart_ = std::chrono::steady_clock::now();
  return 0;
}

bool Viewer::frame(int physicsFrames) {
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
  const int number = ++frameNumber_;
  int width = 0, height = 0;
  std::string error;
  glfwPollEvents();
  interact();
  // Draw the state, then step it while the picture is being made: glFlush hands the frame
  // to the GPU, or to llvmpipe's threads under Xvfb, which render it while this thread runs
  // the physics (on two cores that took the cloth from about 67 to 80-100 frames/s). What a
  // frame's input does is so seen one frame later.
  const bool last = options_.frames > 0 && number >= options_.frames;
  draw(last);
  glFlush();
  const Clock::time_point physicsStart = Clock::now();
  for (int k = 0; k < physicsFrames; ++k) advance();
  const double physics = seconds(Clock::now() - physicsStart);

  // The picture is complete (scene and GUI) in the back buffer: save it before the swap.
  const Clock::time_point savingStart = Clock::now();
  glfwGetFramebufferSize(window_, &width, &height);
  if (control_.screenshotRequested) {
    control_.screenshotRequested = false;
    const std::string name = viewer::screenshotName();
    if (viewer::writeSnapshot(name, width, height, error)) {
      std::cout << "screenshot: " << std::filesystem::absolute(name).string() << std::endl;
    } else {
      std::cerr << "springlab view: " << error << "\n";
    }
  }
  if (last && !options_.snapshot.empty()) {
    if (viewer::writeSnapshot(options_.snapshot, width, height, error)) {
      std::cout << "snapshot: " << options_.snapshot << std::endl;
    } else {
      std::cerr << "springlab view: " << error << "\n";
      exitCode_ = 5;
    }
  }
  const double saving = seconds(Clock::now() - savingStart);
  glfwSwapBuffers(window_);

  // The frame's time, from the end of the previous frame (so it includes waiting for the
  // display), split into the physics and the rest (input, drawing, GUI, and the wait at the
  // swap for the part of the picture not made while the physics ran); writing PNGs is left
  // out.
  const Clock::time_point now = Clock::now();
  const double elapsed = seconds(now - frameStart_) - saving;
  frameStart_ = now;
  recent_.add(elapsed, physics);
  if (number > 1) total_.add(elapsed, physics);  // the first frame compiles shaders
  if (recent_.seconds >= 0.5) {
    rate_ = recent_.rate();
    recent_ = FrameTimes{};
  }
  return !last;
}

#ifdef __EMSCRIPTEN__
// requestAnimationFrame follows the display (60, 120, 144 Hz): the physics runs one viewer
// frame (its substeps) per 1/60 s of wall time, whatever the display's rate, and at most four
// per picture, so a page slower than the physics slows down instead of falling behind.
void Viewer::browserFrame() {
  constexpr double kFrameSeconds = 1.0 / 60.0;
  const double now = emscripten_get_now() / 1e3;
  if (browserTime_ < 0.0) browserTime_ = now - kFrameSeconds;
  browserBacklog_ = std::min(browserBacklog_ + (now - browserTime_), 4.0 * kFrameSeconds);
  browserTime_ = now;
  int physicsFrames = 0;
  for (; browserBacklog_ >= kFrameSeconds; browserBacklog_ -= kFrameSeconds) ++physicsFrames;
  frame(physicsFrames);
}
#endif

int Viewer::finish() {
  int exitCode = exitCode_;
  if (options_.frames > 0) {
    // What the last frame's panel showed of its labels (the viewer tests read this line).
    if (control_.cutLabels.empty()) {
      std::cout << "viewer: the panel's labels fit" << std::endl;
    } else {
      std::cout << "viewer: the panel cuts labels:";
      for (const std::string& label : control_.cutLabels) std::cout << " \"" << label << "\"";
      std::cout << std::endl;
    }
    const viewer::FrameRate r = total_.frames > 0 ? total_.rate() : recent_.rate();
    std::cout << "viewer: " << std::fixed << std::setprecision(1) << r.fps << " frames/s, physics "
              << r.physicsMs << " ms + drawing " << r.drawMs << " ms a frame" << std::endl;
  }
  closeWindow();
  // A headless run ends as `sim` would: exit 3 when an exercise is missing (the panel has
  // named it on screen and on the terminal), so scripts and tests can tell.
  if (options_.frames > 0 && exitCode == 0 && missing_) {
    std::cerr << "springlab view: exercise " << missing_->id << " (" << missing_->title
              << ") is not implemented yet; see " << missing_->handoutSection << "\n";
    exitCode = 3;
  }
  // ... and 4 after a blow-up (the message is above, and on the snapshot's panel).
  if (options_.frames > 0 && exitCode == 0 && blewUp_) exitCode = 4;
  return exitCode;
}

// ---- input --------------------------------------------------------------------------------

void Viewer::onKey(int key, int action, int mods) {
  (void)mods;
  if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
  switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window_, GLFW_TRUE); break;
    case GLFW_KEY_P: control_.paused = !control_.paused; break;
    case GLFW_KEY_N: control_.stepRequested = true; break;
    case GLFW_KEY_R: control_.resetRequested = true; break;
    case GLFW_KEY_W:
      // A mesh switches between shaded and wireframe; a rope shows or hides its masses.
      if (scene_.sim && !scene_.sim->triangles.empty()) {
        control_.wireframe = !control_.wireframe;
      } else {
        control_.drawMasses = !control_.drawMasses;
      }
      break;
    case GLFW_KEY_K: control_.springsByKind = !control_.springsByKind; break;
    case GLFW_KEY_S:
    case GLFW_KEY_F12: control_.screenshotRequested = true; break;
    default: break;
  }
}

void Viewer::onMouseButton(int button, int action, int mods) {
  if (action == GLFW_RELEASE) {
    if (drag_ == Drag::Grab && scene_.sim) scene_.sim->release();
    drag_ = Drag::None;
    grabbed_.reset();
    heldShape_.reset();
    return;
  }
  if (ImGui::GetIO().WantCaptureMouse) return;
  glfwGetCursorPos(window_, &cursorX_, &cursorY_);

  if (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_ALT)) {
    // Alt + click: pin or unpin the mass under the cursor.
    if (const auto i = pickUnderCursor()) {
      guarded([&] { scene_.sim->togglePinned(*i); });
    }
  } else if (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_CONTROL)) {
    // Ctrl + drag: move a movable collider in the plane facing the screen through its centre.
    if (!scene_.sim) return;
    const std::vector<Shape> shapes = scene_.sim->shapes();
    if (const auto k = viewer::pickShape(shapes, cursorRay())) {
      heldShape_ = k;
      grabPlanePoint_ = toGlm(shapes[static_cast<std::size_t>(*k)].center);
      shapeFrom_ = shapeTarget_ = shapes[static_cast<std::size_t>(*k)].center;
      drag_ = Drag::MoveShape;
    }
  } else if (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_SHIFT)) {
    // Shift + drag: hold the mass under the cursor in the plane facing the screen through it.
    if (const auto i = pickUnderCursor()) {
      grabbed_ = i;
      grabPlanePoint_ = toGlm(scene_.sim->state.pos[*i]);
      grabFrom_ = grabTarget_ = scene_.sim->state.pos[*i];
      drag_ = Drag::Grab;
    }
  } else if (button == GLFW_MOUSE_BUTTON_LEFT) {
    drag_ = Drag::Orbit;
  } else if (button == GLFW_MOUSE_BUTTON_RIGHT) {
    drag_ = Drag::Zoom;
  } else if (button == GLFW_MOUSE_BUTTON_MIDDLE) {
    drag_ = Drag::Pan;
  }
}

void Viewer::onCursor(double x, double y) {
  const auto dx = static_cast<float>(x - cursorX_);
  const auto dy = static_cast<float>(y - cursorY_);
  cursorX_ = x;
  cursorY_ = y;
  int w = 0, h = 0;
  glfwGetWindowSize(window_, &w, &h);
  switch (drag_) {
    case Drag::Orbit: camera_.orbit(dx, dy); break;
    case Drag::Zoom: camera_.zoom(std::exp(0.005f * dy)); break;
    case Drag::Pan: camera_.pan(dx, dy, static_cast<float>(h)); break;
    default: break;  // a grab follows the cursor in interact()
  }
}

void Viewer::onScroll(double dy) {
  if (ImGui::GetIO().WantCaptureMouse) return;
  camera_.zoom(std::pow(0.9f, static_cast<float>(dy)));
}

viewer::Ray Viewer::cursorRay() const {
  int w = 0, h = 0;
  glfwGetWindowSize(window_, &w, &h);
  return camera_.ray(cursorX_, cursorY_, w, h);
}

std::optional<int> Viewer::pickUnderCursor() const {
  if (!scene_.sim) return std::nullopt;
  int w = 0, h = 0;
  glfwGetWindowSize(window_, &w, &h);
  return viewer::pickMass(scene_.sim->state.pos, cursorRay(), camera_.pixelAngle(h), kPickPixels);
}

// ---- one frame ------------------------------------------------------------------------------

void Viewer::interact() {
  Simulation* sim = scene_.sim.get();
  if (!sim) return;

  // Requests from keys and the panel.
  if (control_.resetRequested) {
    control_.resetRequested = false;
    guarded([&] { sim->reset(); });
    hudNumbers_.reset();
    if (!runError_.empty()) control_.paused = false;  // R resets and continues after a blow-up
    runError_.clear();
    if (!scene_.missingAtLoad) missing_.reset();  // try the student's code again
    controlVelocity_.setZero();
  }
  if (control_.integratorRequested) {
    const std::string name = *control_.integratorRequested;
    control_.integratorRequested.reset();
    guarded([&] { sim->setIntegrator(registry_.makeIntegrator(name)); });
    stepLimitStale_ = true;
    if (!scene_.missingAtLoad) missing_.reset();  // the missing piece may have been the old method
  }
  if (control_.parameterEdit) {
    const RunControl::ParameterEdit edit = *control_.parameterEdit;
    control_.parameterEdit.reset();
    // Parameter::set is a model edit (Simulation::editModel).
    guarded([&] {
      const std::vector<Parameter> parameters = sim->parameters();
      if (edit.index < parameters.size()) parameters[edit.index].set(edit.value);
    });
    stepLimitStale_ = true;
    hudNumbers_.reset();
  }

  // Held keys drive the fixed end; the velocity is sent only when it changes, so a scene's
  // own initial connection velocity stays until the user takes over.
  Vec3 v = Vec3::Zero();
  if (!ImGui::GetIO().WantCaptureKeyboard) {
    auto held = [&](int key) { return glfwGetKey(window_, key) == GLFW_PRESS; };
    if (held(GLFW_KEY_RIGHT)) v.x() += 1.0;
    if (held(GLFW_KEY_LEFT)) v.x() -= 1.0;
    if (held(GLFW_KEY_DOWN)) v.z() += 1.0;
    if (held(GLFW_KEY_UP)) v.z() -= 1.0;
    if (held(GLFW_KEY_PAGE_UP) || held(GLFW_KEY_HOME)) v.y() += 1.0;
    if (held(GLFW_KEY_PAGE_DOWN) || held(GLFW_KEY_END)) v.y() -= 1.0;
  }
  v *= kControlSpeed;
  if (v != controlVelocity_) {
    controlVelocity_ = v;
    guarded([&] { sim->setControlVelocity(v); });
  }

  // A grabbed mass follows the cursor in its plane (advance() moves it there).
  if (drag_ == Drag::Grab && grabbed_) {
    const glm::vec3 t = viewer::intersectPlane(cursorRay(), grabPlanePoint_, camera_.forward());
    grabTarget_ = Vec3(t.x, t.y, t.z);
  }
  if (drag_ == Drag::MoveShape && heldShape_) {
    const glm::vec3 t = viewer::intersectPlane(cursorRay(), grabPlanePoint_, camera_.forward());
    shapeTarget_ = Vec3(t.x, t.y, t.z);
  }
}

void Viewer::advance() {
  Simulation* sim = scene_.sim.get();
  const bool step = !control_.paused || control_.stepRequested;
  control_.stepRequested = false;
  if (!sim || missing_ || !runError_.empty() || !step) return;
  guarded([&] {
    // A grabbed mass moves to the cursor in even parts over the frame's substeps: in one
    // substep it would get the whole frame's motion as a velocity of distance / dt, a kick
    // of a hundred m/s that the stiff springs pass on to the rope.
    // A dragged collider moves the same way, so the lab sees a steady velocity.
    const bool grabbing = drag_ == Drag::Grab && grabbed_;
    const bool moving = drag_ == Drag::MoveShape && heldShape_;
    for (int k = 0; k < control_.substeps; ++k) {
      const double s = static_cast<double>(k + 1) / static_cast<double>(control_.substeps);
      if (grabbing) sim->grab(*grabbed_, grabFrom_ + s * (grabTarget_ - grabFrom_));
      if (moving) sim->moveShape(*heldShape_, shapeFrom_ + s * (shapeTarget_ - shapeFrom_));
      sim->operate(control_.dt);
    }
    if (grabbing) grabFrom_ = grabTarget_;
    if (moving) shapeFrom_ = shapeTarget_;
    if (!energyWarned_ && ++steppedFrames_ % kEnergyCheckFrames == 0) {
      if (const auto warning = energySourceWarning(*sim)) {
        std::cerr << "springlab view: warning: " << *warning << "\n";
        energyWarned_ = true;
      }
    }
  });
}

void Viewer::draw(bool last) {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(height, 1));
  const glm::mat4 viewProj = camera_.projection(aspect) * camera_.view();
  renderer_->clear(width, height);

  // The ground under the framed region, then the system coloured by its forces.
  const glm::vec3 centre = 0.5f * (framing_.lo + framing_.hi);
  const float halfSize = 1.0f * std::max({framing_.hi.x - framing_.lo.x, framing_.hi.z - framing_.lo.z, 1.0f});
  renderer_->drawGround(framing_.groundHeight, glm::vec2(centre.x, centre.z), halfSize, gridSpacing(halfSize),
                        viewProj);
  if (const Simulation* sim = scene_.sim.get()) {
    viewer::DrawOptions draw;
    const bool mesh = !sim->triangles.empty();
    draw.surfaces = mesh;
    draw.surfaceWireframe = mesh && control_.wireframe;
    draw.springs = !mesh || control_.wireframe;
    draw.masses = mesh ? control_.wireframe : control_.drawMasses;
    draw.springsByKind = control_.springsByKind;
    // Force colours where the forces are those of the current masses, else green.
    static const std::vector<Vec3> noForces;
    viewer::forceColors(sim->force.size() == sim->state.pos.size() ? sim->force : noForces, sim->state.pos.size(),
                        massColors_, colorWork_);
    renderer_->drawShadow(*sim, framing_.groundHeight, viewProj, static_cast<float>(height) / 800.0f);
    renderer_->drawSimulation(*sim, massColors_, sim->grabbed(), draw, viewProj, camera_.eye(),
                              static_cast<float>(height) / 800.0f);
    try {
      renderer_->drawShapes(sim->shapes(), heldShape_, halfSize, viewProj, camera_.eye(),
                            static_cast<float>(height) / 800.0f);
    } catch (const std::exception&) {
      // A lab's shapes() that throws (a missing exercise) draws nothing.
    }
  }

  drawGui(last);
}

void Viewer::requestStepLimit() {
  stepLimitStale_ = false;
  scene_.sim->setKnownStepLimit(std::nullopt);
  // The copy: the scene file again, with the sliders' values and the method the viewer runs.
  // Not for a method built to be stable at every dt (implicit Euler, XPBD, projective
  // dynamics): its limit, where it has one, lies far above any dt the panel offers, and on the
  // 64 x 64 cloth implicit Euler's solves to 1e-12 take 5.6 s of a core to find it has none.
  std::unique_ptr<Simulation> copy;
  if (std::isinf(scene_.sim->integrator().stabilityConstant())) {
    stepLimit_.start(nullptr);
    return;
  }
  try {
    LoadedScene loaded = registry_.loadScene(scene_.path);
    const std::vector<Parameter> shown = scene_.sim->parameters(), copied = loaded.sim->parameters();
    for (std::size_t i = 0; i < shown.size() && i < copied.size(); ++i) copied[i].set(shown[i].get());
    loaded.sim->setIntegrator(registry_.makeIntegrator(scene_.sim->integrator().name()));
    copy = std::move(loaded.sim);
  } catch (const std::exception&) {
    copy.reset();  // a missing exercise or an integrator that cannot be made: no warning
  }
  stepLimit_.start(std::move(copy));
}

void Viewer::drawGui(bool last) {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();

  Simulation* sim = scene_.sim.get();
  viewer::HudInfo hud;
  hud.sceneName = scene_.settings.name;
  hud.tree = options_.tree;
  hud.dt = control_.dt;
  hud.substeps = control_.substeps;
  hud.rate = rate_;
  hud.paused = control_.paused;
  hud.integrator = scene_.settings.integrator;
  double stableDt = -1.0;
  if (sim) {
    hud.kind = sim->kind();
    hud.masses = sim->numOfMasses();
    hud.time = sim->state.time;
    hud.integrator = sim->integrator().name();
    try {
      // Energies and observables (the ball's volume is a sum over its triangles) ten times a
      // second, as fast as anyone reads them; at once after a reset, an edit or a step, and
      // on the last frame of a --frames run, whose snapshot shows them.
      const auto now = std::chrono::steady_clock::now();
      const bool due = !hudNumbers_ || (sim->state.time != hudNumbers_->time &&
                                        (last || control_.paused ||
                                         now - hudNumbers_->computed >= std::chrono::milliseconds(100)));
      if (due) {
        hudNumbers_.reset();  // stays empty if the next line throws
        hudNumbers_ = HudNumbers{sim->state.time, now, sim->energies(), sim->observables()};
      }
      hud.time = hudNumbers_->time;  // the time the numbers are of
      hud.energies = hudNumbers_->energies;
      hud.observables = hudNumbers_->observables;
    } catch (const std::exception&) {
      // A missing exercise or a broken state: the HUD leaves the numbers out.
    }
  }
  // The step's exact limit, once the worker has it (the last frame of a --frames run waits for
  // it, so its snapshot shows the warning); the terminal gets each new warning once.
  if (sim && !missing_) {
    if (stepLimitStale_) requestStepLimit();
    if (last) stepLimit_.wait(kLastFrameWait);
    if (const std::optional<double> limit = stepLimit_.limit()) {
      stableDt = *limit;
      // The blow-up message takes it from here instead of computing it on this thread.
      if (sim->knownStepLimit() != limit) sim->setKnownStepLimit(limit);
    }
  }
  if (stableDt >= 0.0 && control_.dt > stableDt) {
    std::ostringstream note;
    if (stableDt == 0.0) {
      note << hud.integrator << " has no stable dt on this scene (its linearised step grows at every dt)";
    } else {
      note << "dt = " << control_.dt << " s is past the stability limit of " << hud.integrator << " on this scene, "
           << stableDt << " s (the linearised step, dampers and contacts included): expect a blow-up";
    }
    if (note.str() != stepLimitNoted_) {
      std::cerr << "springlab view: warning: " << note.str() << "\n";
      stepLimitNoted_ = note.str();
    }
  }
  viewer::drawHud(hud);
  viewer::drawControls(sim, registry_.integratorNames(), hud.integrator, stableDt, control_);
  if (!runError_.empty()) viewer::drawRunError(runErrorHeadline_, runError_);
  if (missing_) viewer::drawMissingExercise(*missing_);

  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace

LiveViewer* liveViewer() { return live; }

int runViewer(const Registry& registry, const std::string& scenePath, const ViewerOptions& options) {
  // Load before opening a window: a bad scene file is an error on the terminal (exit 2);
  // a missing exercise while building still opens the window and says which one.
  Scene scene;
  try {
    scene.path = scenePath;
    LoadedScene loaded = registry.loadScene(scenePath);
    scene.settings = loaded.settings;
    scene.sim = std::move(loaded.sim);
  } catch (const SceneError& e) {
    std::cerr << "springlab view: bad scene: " << e.what() << "\n";
    return 2;
  } catch (const NotImplemented& e) {
    std::cerr << "springlab view: " << e.what() << "\n";
    scene.settings = registry.readSceneSettings(scenePath);
    scene.missingAtLoad = missingFrom(e);
  }
  if (options.dt > 0.0) scene.settings.dt = options.dt;
  if (!options.integrator.empty()) {
    try {
      auto integrator = registry.makeIntegrator(options.integrator);
      if (scene.sim) scene.sim->setIntegrator(std::move(integrator));
      scene.settings.integrator = options.integrator;
    } catch (const std::invalid_argument& e) {
      std::cerr << "springlab view: " << e.what() << "\n";
      return 2;
    }
  }

#ifdef __EMSCRIPTEN__
  // The page calls its frames after this returns: the viewer lives as long as the page.
  static std::unique_ptr<Viewer> viewer;
  viewer = std::make_unique<Viewer>(registry, std::move(scene), options);
  return viewer->run();
#else
  Viewer viewer(registry, std::move(scene), options);
  return viewer.run();
#endif
}

}  // namespace springlab
