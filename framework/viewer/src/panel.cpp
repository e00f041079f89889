#include "panel.hpp"

#include <imgui.h>

#include <cmath>
#include <cstdio>

namespace springlab::viewer {

namespace {
const ImVec4 kYellow(1.0f, 0.85f, 0.2f, 1.0f);
const ImVec4 kRed(1.0f, 0.3f, 0.3f, 1.0f);
constexpr ImGuiWindowFlags kOverlay = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                      ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                      ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove;
}  // namespace

void drawHud(const HudInfo& hud) {
  // Top left, translucent, not movable: the facts a student compares between runs.
  ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.55f);
  if (ImGui::Begin("##hud", nullptr, kOverlay)) {
    ImGui::Text("%s", hud.sceneName.c_str());
    ImGui::Text("%s code%s%s", hud.tree.c_str(), hud.kind.empty() ? "" : ", ", hud.kind.c_str());
    if (hud.masses > 0) ImGui::Text("%d masses", hud.masses);
    ImGui::Separator();
    ImGui::Text("t = %.3f s%s", hud.time, hud.paused ? "   (paused)" : "");
    ImGui::Text("dt = %.3g s x %d substeps", hud.dt, hud.substeps);
    ImGui::Text("integrator: %s", hud.integrator.c_str());
    if (hud.energies) {
      ImGui::Separator();
      ImGui::Text("kinetic       %10.4f J", hud.energies->kinetic);
      ImGui::Text("gravitational %10.4f J", hud.energies->gravitational);
      ImGui::Text("elastic       %10.4f J", hud.energies->elastic);
      if (hud.energies->other != 0.0) ImGui::Text("other         %10.4f J", hud.energies->other);
      ImGui::Text("total         %10.4f J", hud.energies->total());
    }
    if (!hud.observables.empty()) {
      ImGui::Separator();
      for (const Observable& o : hud.observables) {
        ImGui::Text("%-13s %10.4g %s", o.name.c_str(), o.value, o.unit.c_str());
      }
    }
    ImGui::Separator();
    ImGui::Text("%.0f frames/s", static_cast<double>(hud.rate.fps));
    ImGui::Text("physics %.1f ms, drawing %.1f ms", static_cast<double>(hud.rate.physicsMs),
                static_cast<double>(hud.rate.drawMs));
  }
  ImGui::End();
}

namespace {
// The width of every slider and combo of the panel; their labels sit to the right of them
// and the window grows to hold the longest (it resizes to its content), so no label is cut.
constexpr float kSliderWidth = 190.0f;

// Whether the last item (a slider or combo with its label) ends inside the window's content
// region; records its label in `cut` when it does not.
void noteIfCut(const char* label, std::vector<std::string>& cut) {
  const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
  if (ImGui::GetItemRectMax().x > right + 0.5f) cut.emplace_back(label);
}
}  // namespace

void drawControls(Simulation* sim, const std::vector<std::string>& integratorNames, const std::string& integrator,
                  double stableDt, RunControl& control) {
  // Top right; the pivot keeps the right edge there as the window sizes itself to its
  // widest line (the buttons, or the longest slider label).
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - 10.0f, 10.0f), ImGuiCond_FirstUseEver, ImVec2(1.0f, 0.0f));
  ImGui::SetNextWindowBgAlpha(0.8f);
  ImGui::SetNextWindowCollapsed(control.panelCollapsed, ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Controls", nullptr, ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::End();
    return;
  }
  control.cutLabels.clear();
  ImGui::PushItemWidth(kSliderWidth);

  // Run control: buttons mirror the keys P, N, R and S.
  if (ImGui::Button(control.paused ? "Run (P)" : "Pause (P)")) control.paused = !control.paused;
  ImGui::SameLine();
  ImGui::BeginDisabled(!control.paused);
  if (ImGui::Button("Step (N)")) control.stepRequested = true;
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("Reset (R)")) control.resetRequested = true;
  ImGui::SameLine();
  if (ImGui::Button("Screenshot (S)")) control.screenshotRequested = true;

  // Time step (log slider: the interesting values span decades) and substeps.
  const double dtMin = 1e-5, dtMax = 0.05;
  ImGui::SliderScalar("dt (s)", ImGuiDataType_Double, &control.dt, &dtMin, &dtMax, "%.2e",
                      ImGuiSliderFlags_Logarithmic);
  noteIfCut("dt (s)", control.cutLabels);
  ImGui::SliderInt("substeps", &control.substeps, 1, 200, "%d", ImGuiSliderFlags_AlwaysClamp);
  noteIfCut("substeps", control.cutLabels);
  if (control.substeps < 1) control.substeps = 1;

  // Integrators by name; the loop swaps it in.
  if (ImGui::BeginCombo("integrator", integrator.c_str())) {
    for (const std::string& name : integratorNames) {
      const bool selected = name == integrator;
      if (ImGui::Selectable(name.c_str(), selected) && !selected) control.integratorRequested = name;
      if (selected) ImGui::SetItemDefaultFocus();
    }
    ImGui::EndCombo();
  }
  noteIfCut("integrator", control.cutLabels);

  // The warning a student should see before the run blows up.
  if (sim && stableDt >= 0.0 && control.dt > stableDt) {
    if (stableDt == 0.0) {
      ImGui::TextColored(kYellow, "%s has no stable dt on this scene", integrator.c_str());
    } else {
      ImGui::TextColored(kYellow, "dt is past the stable limit\n%.3g s of %s on this scene", stableDt, integrator.c_str());
    }
  }

  // The scene's own parameters, one slider each: it shows get(); an edit is recorded for the
  // loop, which writes it with set().
  if (sim) {
    const std::vector<Parameter> parameters = sim->parameters();
    if (!parameters.empty()) {
      ImGui::Separator();
      ImGui::TextDisabled("parameters");
    }
    for (std::size_t k = 0; k < parameters.size(); ++k) {
      const Parameter& p = parameters[k];
      if (!p.get || !p.set) continue;
      const std::string label = p.unit.empty() ? p.label : p.label + " (" + p.unit + ")";
      const bool logarithmic = p.logarithmic && p.min > 0.0;
      double value = p.get();
      if (ImGui::SliderScalar(label.c_str(), ImGuiDataType_Double, &value, &p.min, &p.max, "%.4g",
                              logarithmic ? ImGuiSliderFlags_Logarithmic : ImGuiSliderFlags_None)) {
        control.parameterEdit = RunControl::ParameterEdit{k, value};
      }
      noteIfCut(label.c_str(), control.cutLabels);
    }
  }

  ImGui::Separator();
  ImGui::Checkbox(sim && !sim->triangles.empty() ? "wireframe (W)" : "masses (W)",
                  sim && !sim->triangles.empty() ? &control.wireframe : &control.drawMasses);
  ImGui::SameLine();
  ImGui::Checkbox("spring kinds (K)", &control.springsByKind);
  if (ImGui::CollapsingHeader("mouse and keys")) {
    ImGui::TextUnformatted(
        "left drag: orbit   right drag, wheel: zoom\n"
        "middle drag: pan\n"
        "shift + left: drag a mass   alt + left: pin\n"
        "ctrl + left: drag a collider\n"
        "arrows: move the fixed end in x, z\n"
        "page up/down: move it in y\n"
        "P pause  N step  R reset  W wireframe  K kinds\n"
        "S, F12 screenshot  Esc quit");
  }
  ImGui::PopItemWidth();
  ImGui::End();
}

void drawMissingExercise(const MissingExercise& missing) {
  // Big, red and in the middle: the first thing a student sees before writing any code.
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0.5f * io.DisplaySize.x, 0.5f * io.DisplaySize.y), ImGuiCond_Always,
                          ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(0.62f * io.DisplaySize.x, 0.0f), ImGuiCond_Always);
  ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.72f, 0.06f, 0.06f, 0.95f));
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 1.0f, 1.0f, 1.0f));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(28.0f, 24.0f));
  if (ImGui::Begin("##missing", nullptr, kOverlay & ~ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::SetWindowFontScale(2.0f);
    ImGui::PushTextWrapPos(0.0f);
    ImGui::Text("Exercise %s (%s) is not implemented yet", missing.id.c_str(), missing.title.c_str());
    ImGui::PopTextWrapPos();
    ImGui::SetWindowFontScale(1.4f);
    ImGui::Spacing();
    ImGui::TextWrapped("See %s.", missing.handoutSection.c_str());
    ImGui::TextWrapped("Write it, rebuild, and run the scene again. The viewer stops stepping until then.");
  }
  ImGui::End();
  ImGui::PopStyleVar();
  ImGui::PopStyleColor(2);
}

void drawRunError(const std::string& headline, const std::string& message) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0.5f * io.DisplaySize.x, io.DisplaySize.y - 10.0f), ImGuiCond_Always,
                          ImVec2(0.5f, 1.0f));
  ImGui::SetNextWindowSize(ImVec2(0.7f * io.DisplaySize.x, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.85f);
  if (ImGui::Begin("##runerror", nullptr, kOverlay & ~ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::SetWindowFontScale(1.3f);
    ImGui::PushStyleColor(ImGuiCol_Text, kRed);
    ImGui::TextWrapped("%s: %s", headline.c_str(), message.c_str());
    ImGui::PopStyleColor();
    ImGui::TextWrapped("Press R to reset; a smaller dt or another integrator may help.");
  }
  ImGui::End();
}

}  // namespace springlab::viewer
