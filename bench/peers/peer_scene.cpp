#include <algorithm>
#include <memory>
#include <stdexcept>

#include "boxsim/core/stepper.hpp"
#include "boxsim/impulse_damped/damped_integration.hpp"
#include "boxsim/techniques.hpp"
#include "peer_engine.hpp"

namespace boxsim::peers {

PeerScene peerSceneFromWorld(const std::string& name, const World& world, double duration) {
  PeerScene scene;
  scene.name = name;
  scene.gravity = world.gravity;
  scene.restitution = world.restitution;
  scene.duration = duration;
  scene.world = world;
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    const RigidBody& b = world.bodies[i];
    PeerBox box;
    box.name = world.names[i];
    box.halfExtents = b.halfExtents;
    box.immovable = b.immovable;
    box.mass = b.immovable ? 0.0 : b.mass;
    box.x = b.s.x;
    box.q = b.s.q;
    box.v = b.v;
    box.omega = b.omega;
    scene.boxes.push_back(box);
  }
  // A launched body waits immovable at its pose; it gets its mass and velocities at launch.
  for (const Launch& l : world.launches) {
    PeerBox& box = scene.boxes[static_cast<std::size_t>(l.body)];
    box.immovable = false;
    box.mass = l.mass;
    box.v = l.velocity;
    box.omega = l.angularVelocity;
    box.launchTime = l.time;
  }
  return scene;
}

namespace {

/// boxsim itself, through the same Stepper interface the command line uses.
class BoxsimEngine : public PeerEngine {
 public:
  /// `engine` is a method, optionally with a contact gathering after a slash
  /// ("damped/every_pass"), optionally ending in "+friction": every body then gets the scene's
  /// Coulomb friction, as the peers have it ("damped+friction"), in "+chatter": chatter
  /// detected from history (SleepParams::chatterDetection, "damped+chatter"), and in
  /// "+under_load": geometric stability with stability under load (\thesis{§6.3.1},
  /// "damped+under_load"), in "+threads2": two threads (ImpulseParams::threads), in
  /// "+impact": 20 impact passes (DampedIntegrationParams::impactPasses, "damped+impact"), in
  /// "+supported": damping of supported bodies only (DampingParams::supportedOnly,
  /// "damped+supported"), in "+anchor": the slow pairs found where the first pass predicts the
  /// bodies fast at the step's start (ImpulseParams::predictedAnchor, "damped+anchor"), in
  /// "+exact_edges": edge-edge pairs gathered exactly in every pass
  /// (ImpulseParams::exactEdgePairs, "damped+exact_edges"), in "+corners": an edge-edge pair's
  /// corners of its best face kept beside its point (ImpulseParams::edgeCorners,
  /// "damped+corners"), and
  /// in "+shared_work": the work its threads would share measured (sharedWork()); the suffixes
  /// in any order.
  explicit BoxsimEngine(std::string engine) {
    const auto strip = [&engine](const std::string& plus) {
      const bool ends = engine.size() > plus.size() &&
                        engine.compare(engine.size() - plus.size(), plus.size(), plus) == 0;
      if (ends) engine.erase(engine.size() - plus.size());
      return ends;
    };
    for (bool stripped = true; stripped;) {
      const bool chatter = strip("+chatter"), friction = strip("+friction"),
                 underLoad = strip("+under_load"), threads = strip("+threads2"),
                 shared = strip("+shared_work"), impact = strip("+impact"),
                 supported = strip("+supported"), anchor = strip("+anchor"),
                 exactEdges = strip("+exact_edges"), corners = strip("+corners");
      if (chatter) options_.chatterDetection = true;
      if (friction) friction_ = true;
      if (underLoad) options_.geometricStability = GeometricStabilityMode::UnderLoad;
      if (threads) options_.threads = 2;
      if (shared) measureShared_ = true;
      if (impact) options_.impactPasses = 20;
      if (supported) options_.dampSupportedOnly = true;
      if (anchor) options_.predictedAnchor = true;
      if (exactEdges) options_.exactEdgePairs = true;
      if (corners) options_.edgeCorners = true;
      stripped = chatter || friction || underLoad || threads || shared || impact || supported ||
                 anchor || exactEdges || corners;
    }
    const std::size_t slash = engine.find('/');
    method_ = engine.substr(0, slash);
    if (slash != std::string::npos) {
      gathering_ = engine.substr(slash + 1);
      options_.contactGathering = parseContactGathering(gathering_);
    }
    stepper_ = makeStepper(method_, options_);  // refuses an unknown method now, not at load
  }
  std::string name() const override {
    return "boxsim " + method_ + (gathering_.empty() ? "" : " " + gathering_) + (friction_ ? " μ" : "") +
           (options_.chatterDetection.value_or(false) ? " chatter" : "") +
           (options_.geometricStability == GeometricStabilityMode::UnderLoad ? " under load" : "") +
           (options_.dampSupportedOnly.value_or(false) ? " supported" : "") +
           (options_.impactPasses.value_or(0) > 0 ? " impact" : "") +
           (options_.predictedAnchor.value_or(false) ? " anchor" : "") +
           (options_.exactEdgePairs.value_or(false) ? " exact edges" : "") +
           (options_.edgeCorners.value_or(false) ? " corners" : "") +
           (options_.threads.value_or(1) > 1 ? " " + std::to_string(*options_.threads) + " threads"
                                             : "");
  }
  std::string settings() const override {
    std::string text;
    for (const auto& [key, value] : stepper_->parameters())
      if (key == "integrator" || key == "sleep" || key == "contact_gathering" ||
          (key == "chatter_detection" && value == "on") ||
          (key == "geometric_stability" && value == "under_load") ||
          (key == "threads" && value != "1") || (key == "impact_passes" && value != "0") ||
          (key == "damp_supported_only" && value == "on") ||
          (key == "predicted_anchor" && value == "on") ||
          (key == "exact_edge_pairs" && value == "on") ||
          (key == "edge_corners" && value == "on"))
        text += (text.empty() ? "" : ", ") + key + " " + value;
    return (text.empty() ? "defaults" : text) +
           (friction_ ? ", Coulomb friction as the peers (patch friction at each contact's centroid)"
                      : ", frictionless as the thesis (damping stands in, §5.2)");
  }
  void load(const PeerScene& scene) override {
    world_ = scene.world;
    if (friction_)
      for (RigidBody& body : world_.bodies) body.friction = {scene.friction, scene.friction};
    // Sleeping (§4.5) belongs to damped integration alone; the other methods never sleep.
    if (method_ == "damped") {
      options_.sleep = scene.sleep;
      stepper_ = makeStepper(method_, options_);
      profile_ = DampedStepProfile{};
      profile_.measureParallelWork = measureShared_;
      if (auto* damped = dynamic_cast<DampedIntegrationStepper*>(stepper_.get()))
        damped->setProfile(&profile_);
    }
  }
  void step(double dt, double t) override {
    // As simulate(): a body launched at T starts moving with the step that begins at T.
    world_.applyLaunches(t + 1e-9 * dt);
    asleep_ = stepper_->step(world_, dt).sleeping;
  }
  void read(std::vector<PeerPose>& poses) const override {
    poses.resize(world_.bodies.size());
    for (std::size_t i = 0; i < world_.bodies.size(); ++i) {
      const RigidBody& b = world_.bodies[i];
      poses[i] = PeerPose{b.s.x, b.s.q, b.v, b.omega};
    }
  }
  int asleep() const override { return asleep_; }
  std::vector<std::pair<std::string, double>> stages() const override {
    if (profile_.steps == 0) return {};
    std::vector<std::pair<std::string, double>> stages = {
        {"contacts at the step's start", profile_.stepContacts},
        {"collision passes (DAMPEDINTEGRATION L1)", profile_.collisionPasses},
        {"contact passes (DAMPEDINTEGRATION L2)", profile_.contactPasses},
        {"shock propagation sweep (friction only)", profile_.shockSweep},
        {"gravity and damping (DAMPEDINTEGRATION L3-L4)", profile_.velocitiesAndDamping},
        {"FIXCONTACTCONSTRAINTS (DAMPEDINTEGRATION L5)", profile_.fixContacts},
        {"geometric stability (DAMPEDINTEGRATION L6)", profile_.stability},
        {"sleeping (§4.5)", profile_.sleeping}};
    std::stable_sort(stages.begin(), stages.end(),
                     [](const auto& x, const auto& y) { return x.second > y.second; });
    return stages;
  }
  std::optional<StepWork> work() const override {
    if (profile_.workSteps == 0) return std::nullopt;
    const double pairs = static_cast<double>(std::max(1L, profile_.touchingPairs));
    return StepWork{static_cast<double>(profile_.narrowPhases) / pairs,
                    static_cast<double>(profile_.passNarrowPhases) / pairs,
                    static_cast<double>(profile_.keptNarrowPhases) / pairs,
                    static_cast<double>(profile_.axisChecks) / pairs,
                    static_cast<double>(profile_.passes) / static_cast<double>(profile_.workSteps)};
  }
  std::optional<SharedWork> sharedWork() const override {
    if (!measureShared_ || profile_.steps == 0) return std::nullopt;
    return SharedWork{profile_.total(), profile_.parallelWork, profile_.steps};
  }

 private:
  std::string method_;
  std::string gathering_;  ///< empty: the method's default
  bool friction_ = false;  ///< the scene's friction on every body
  bool measureShared_ = false;  ///< "+shared_work"
  TechniqueOptions options_;
  std::unique_ptr<Stepper> stepper_;
  DampedStepProfile profile_;  ///< damped: the stage times of the steps since load()
  World world_;
  int asleep_ = 0;
};

}  // namespace

std::unique_ptr<PeerEngine> makeBoxsimEngine(const std::string& method) {
  return std::make_unique<BoxsimEngine>(method);
}

}  // namespace boxsim::peers
