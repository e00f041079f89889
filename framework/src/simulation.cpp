#include "springlab/simulation.hpp"

#include <stdexcept>
#include <utility>

#include "springlab/symplectic_euler.hpp"

namespace springlab {

Simulation::Simulation(int dim) : dimension(dim), integrator_(std::make_unique<SymplecticEuler>()) {
  if (dim != 2 && dim != 3) throw std::invalid_argument("Simulation: dimension must be 2 or 3");
}

Simulation::~Simulation() = default;

void Simulation::init() {
  force.assign(masses.size(), Vec3::Zero());
}

void Simulation::solve() {
  evaluateForces(state, force);
}

void Simulation::simulate(double dt) {
  // Integrate, then let the scene move its kinematic masses and project contacts. What the
  // integrator does besides evaluating forces is its "integration" phase; the lab's
  // afterStep charges its corrections to their own phases.
  const PhaseProfile::Scope step(profile, Phase::kOther);
  // A state set by hand since the last step (a test giving the masses velocities, a script
  // moving them) is energy the user put in, not the step's: the check starts from it.
  if (blowUpCheckEnabled_ && blowUpCheck_.changedSinceLastCheck(*this)) {
    blowUpCheck_.admitUserEnergy(*this);
    sourcePowerAfter_.reset();
  }
  // The energy sources' work over the step (the wind's): the trapezoid rule on their power at
  // its two ends, the start's kept from the last step's end.
  const bool sourced = suppliesEnergy();
  std::optional<double> powerBefore;
  if (sourced) {
    powerBefore = sourcePowerAfter_ && sourcePowerAfter_->first == stats.steps ? std::optional(sourcePowerAfter_->second)
                                                                               : sourcePower(state);
  }
  {
    const PhaseProfile::Scope integration(profile, Phase::kIntegration);
    integrator_->step(*this, dt);
  }
  ++stats.steps;
  // The corrections' work: the energy before and after afterStep, where it changed the state
  // (the integrator's result kept in buffers that outlive the step: no allocation).
  const bool tracking = blowUpCheckEnabled_ || trackCorrections_;
  if (tracking) {
    integrated_.pos = state.pos;
    integrated_.vel = state.vel;
  }
  afterStep(dt);
  stepEnd_.reset();
  if (tracking && (state.pos != integrated_.pos || state.vel != integrated_.vel)) {
    stepEnd_ = energies();  // the blow-up check's too, unless a drag moves a mass below
    std::swap(state.pos, integrated_.pos);
    std::swap(state.vel, integrated_.vel);
    const double integrated = energies().total();
    std::swap(state.pos, integrated_.pos);
    std::swap(state.vel, integrated_.vel);
    correctionWork_ += stepEnd_->total() - integrated;
  }

  // A mass the user drags is held at the mouse, at rest: the mouse may jump by a whole
  // frame in one substep, and that jump must not turn into a velocity.
  // The energy the drag stores in the springs is the user's doing, not a blow-up.
  if (grabbed_) {
    state.pos[*grabbed_] = grabTarget_;
    state.vel[*grabbed_].setZero();
    stepEnd_.reset();
    blowUpCheck_.admitUserEnergy(*this);
  }

  lastStepWorkKnown_ = true;
  sourcePowerAfter_.reset();
  if (sourced) {
    const std::optional<double> powerAfter = sourcePower(state);
    lastStepWorkKnown_ = powerBefore && powerAfter;
    if (lastStepWorkKnown_) sourceWork_ += 0.5 * (*powerBefore + *powerAfter) * dt;
    if (powerAfter) sourcePowerAfter_ = std::pair(stats.steps, *powerAfter);
  }

  if (blowUpCheckEnabled_) blowUpCheck_.check(*this, dt);
}

void Simulation::operate(double dt) {
  // The integrator evaluates the forces itself, as often as its method needs (once for
  // symplectic Euler, four times for RK4), so the handout's init() and solve() are in there.
  simulate(dt);
}

void Simulation::evaluateForces(const State& s, std::vector<Vec3>& f) {
  const PhaseProfile::Scope forces(profile, Phase::kForces);
  f.assign(masses.size(), Vec3::Zero());
  accumulateForces(s, f);
  if (holdingLoad_.size() == f.size())
    for (std::size_t i = 0; i < f.size(); ++i) f[i] += holdingLoad_[i];
  ++stats.forceEvaluations;
}

void Simulation::forceJacobian(const State& s, ForceJacobian& J, std::string_view who) {
  J.clear();
  if (!addForceJacobian(s, J)) {
    throw std::invalid_argument(std::string(who) + " needs the force Jacobians dF/dx and dF/dv, which the \"" + kind() +
                                "\" scene does not provide (Simulation::addForceJacobian); choose an explicit "
                                "integrator such as symplectic_euler");
  }
}

void Simulation::setIntegrator(std::unique_ptr<Integrator> integrator) {
  if (!integrator) throw std::invalid_argument("Simulation::setIntegrator: null integrator");
  integrator_ = std::move(integrator);
  knownStepLimit_.reset();  // it was the old method's
  const auto options = integratorOptions.find(integrator_->name());
  if (options != integratorOptions.end()) {
    for (const auto& [option, value] : options->second) integrator_->setOption(option, value);
  }
  integrator_->reset();
}

void Simulation::markInitialState() {
  if (state.pos.size() != masses.size() || state.vel.size() != masses.size()) {
    throw std::logic_error("Simulation: state and masses differ in size after building the scene");
  }
  initialState_ = state;
  force.assign(masses.size(), Vec3::Zero());
  building_ = false;
  onModelEdited();
  blowUpCheck_.arm(*this);
}

std::unique_ptr<Integrator> Simulation::exchangeIntegrator(std::unique_ptr<Integrator> integrator) {
  std::unique_ptr<Integrator> before = std::move(integrator_);
  try {
    setIntegrator(std::move(integrator));
  } catch (...) {
    integrator_ = std::move(before);
    throw;
  }
  return before;
}

void Simulation::reset() {
  state = initialState_;
  force.assign(masses.size(), Vec3::Zero());
  stats = Stats{};
  grabbed_.reset();
  integrator_->reset();
  sourceWork_ = 0.0;
  lastStepWorkKnown_ = true;
  sourcePowerAfter_.reset();
  correctionWork_ = 0.0;
  stepEnd_.reset();
  onReset();
  blowUpCheck_.arm(*this);
}

Simulation::SavedRun Simulation::saveRun() const {
  return {state, force, stats, grabbed_, grabTarget_, sourceWork_, correctionWork_, lastStepWorkKnown_,
          sourcePowerAfter_, stepEnd_, saveLabData(), blowUpCheck_};
}

void Simulation::resumeRun(const SavedRun& saved) {
  state = saved.state;
  force = saved.force;
  stats = saved.stats;
  grabbed_ = saved.grabbed;
  grabTarget_ = saved.grabTarget;
  sourceWork_ = saved.sourceWork;
  correctionWork_ = saved.correctionWork;
  lastStepWorkKnown_ = saved.lastStepWorkKnown;
  sourcePowerAfter_ = saved.sourcePowerAfter;
  stepEnd_ = saved.stepEnd;
  restoreLabData(saved.labData);
  blowUpCheck_ = saved.blowUpCheck;
  integrator_->reset();
}

Energies Simulation::energies() const {
  Energies e;
  for (int i = 0; i < numOfMasses(); ++i) {
    e.kinetic += 0.5 * masses[i].m * state.vel[i].squaredNorm();
    e.gravitational -= masses[i].m * gravitation.dot(state.pos[i]);
  }
  for (const Spring& s : springs_) {
    const double stretch = (state.pos[s.mass1] - state.pos[s.mass2]).norm() - s.springLength;
    e.elastic += 0.5 * s.springConstant * stretch * stretch;
  }
  e.other = otherPotentialEnergy(state);
  return e;
}

Vec3 Simulation::momentum() const {
  Vec3 p = Vec3::Zero();
  for (int i = 0; i < numOfMasses(); ++i) p += masses[i].m * state.vel[i];
  return p;
}

double Simulation::angularFrequencyBound() const { return springGershgorinBound(*this); }

Bounds Simulation::reach() const {
  Bounds b;
  if (state.pos.empty()) return b;
  b.lo = b.hi = state.pos.front();
  for (const Vec3& p : state.pos) {
    b.lo = b.lo.cwiseMin(p);
    b.hi = b.hi.cwiseMax(p);
  }
  return b;
}

void Simulation::grab(int index, const Vec3& target) {
  if (index < 0 || index >= numOfMasses()) throw std::out_of_range("Simulation::grab: no such mass");
  grabbed_ = index;
  grabTarget_ = target;
}

void Simulation::release() {
  grabbed_.reset();
  blowUpCheck_.admitUserEnergy(*this);
}

void Simulation::editModel(const std::function<void(Simulation&)>& edit) {
  // editSprings() is allowed during the edit (and stays allowed in an edit inside one).
  const bool wasBuilding = building_;
  building_ = true;
  try {
    edit(*this);
  } catch (...) {
    building_ = wasBuilding;
    throw;
  }
  building_ = wasBuilding;
  if (state.pos.size() != masses.size() || state.vel.size() != masses.size()) {
    throw std::logic_error("Simulation::editModel: the edit changed the number of masses but not the state");
  }
  onModelEdited();
  knownStepLimit_.reset();  // it was the old model's
  // The integrator's history (Verlet's previous positions) belongs to the old model, and
  // the edited model may hold more energy than the old one: neither is a blow-up.
  integrator_->reset();
  sourcePowerAfter_.reset();  // the old model's
  stepEnd_.reset();
  blowUpCheck_.admitUserEnergy(*this);
}

std::vector<Spring>& Simulation::editSprings() {
  if (!building_) {
    throw std::logic_error(
        "Simulation::editSprings: the springs change only inside editModel, so the lab derives again what it "
        "keeps from them: sim.editModel([&](Simulation& model) { model.editSprings()... })");
  }
  return springs_;
}

void Simulation::swapSprings(std::vector<Spring>& other) {
  springs_.swap(other);
  onModelEdited();
}

void Simulation::togglePinned(int index) {
  if (index < 0 || index >= numOfMasses()) throw std::out_of_range("Simulation::togglePinned: no such mass");
  editModel([index](Simulation& sim) {
    sim.masses[index].pinned = !sim.masses[index].pinned;
    sim.state.vel[index].setZero();
  });
}

std::vector<Parameter> Simulation::parameters() {
  // The lab's setters only assign; each runs here as a model edit.
  std::vector<Parameter> declared = declareParameters();
  for (Parameter& p : declared) {
    if (!p.set) continue;
    p.set = [this, assign = std::move(p.set)](double value) { editModel([&](Simulation&) { assign(value); }); };
  }
  return declared;
}

}  // namespace springlab
