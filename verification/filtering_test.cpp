// Verification of the filters of thesis §5.5 (src/boxsim/filtering/): the box filter against
// closed forms (linear motion, uniform rotation), its independence of quaternion signs, the
// thesis' claims on the chattering die made measurable, the envelope filter's two promises
// (still chatter, no lag for fast bodies), the causal forms against the offline ones, the
// measures against closed forms, bad parameters, and determinism.
#include <gsl/gsl_movstat.h>
#include <gsl/gsl_vector.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <memory>

#include "boxsim/filtering/box_filter.hpp"
#include "boxsim/filtering/envelope_filter.hpp"
#include "boxsim/filtering/filter_choice.hpp"
#include "boxsim/filtering/orientation_average.hpp"
#include "boxsim/filtering/trajectory_measures.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/simulate.hpp"
#include "boxsim/io/trajectory.hpp"
#include "boxsim/techniques.hpp"

using namespace boxsim;
using Catch::Matchers::Contains;

namespace {

constexpr double kDt = 1.0 / 60.0;

/// A ground and one unit cube moving as `pose(t)` for n frames of kDt.
template <class Pose>
Trajectory synthetic(int n, Pose pose) {
  Trajectory t;
  t.bodies.push_back({"ground", Vec3(10.0, 0.5, 10.0), true});
  t.bodies.push_back({"cube", Vec3::Constant(0.5), false});
  for (int k = 0; k < n; ++k) {
    TrajectoryFrame f;
    f.t = k * kDt;
    f.x = {Vec3(0.0, -0.5, 0.0), Vec3::Zero()};
    f.q = {Quat::Identity(), Quat::Identity()};
    pose(f.t, f.x[1], f.q[1]);
    t.frames.push_back(f);
  }
  return t;
}

/// A scene of chapters/impulse_damped/scenes/ under the plain impulse step for `duration` s,
/// recorded every step.
Trajectory impulseRun(const std::string& scene, double duration) {
  const std::string path = std::string(BOXSIM_SOURCE_DIR) + "/chapters/impulse_damped/scenes/" + scene + ".json";
  Scene loaded = loadScene(path);
  std::unique_ptr<Stepper> stepper = makeStepper("impulse");
  Recorder recorder(loaded.world, runParameters(*stepper, loaded.world, path, kDt, duration));
  SimulateOptions options;
  options.duration = duration;
  simulate(loaded.world, *stepper, options, recorder);
  return recorder.trajectory();
}

/// The die of die.json under the plain impulse step for 12 s: it topples off the edge it
/// balanced on at 7.5 s and rests on a face from 10 s, where the step leaves micrometre chatter.
const Trajectory& chatteringDie() {
  static const Trajectory die = impulseRun("die", 12.0);
  return die;
}

/// The base-10 pyramid of Fig. 6.6 (pyramid10_shot.json) under the plain impulse step for 7 s:
/// it stands, chattering by millimetres (visible chatter), until the box shot at it hits at
/// about 5 s.
const Trajectory& chatteringPyramid() {
  static const Trajectory pyramid = impulseRun("pyramid10_shot", 7.0);
  return pyramid;
}

/// The resting bodies of a raw run over [t0, t1] s and its measures there.
struct RestingRun {
  FrameWindow window;
  std::vector<std::size_t> bodies;
  MotionMeasures raw;
};

RestingRun restingRun(const Trajectory& raw, double t0, double t1) {
  RestingRun r;
  r.window = frameWindow(raw, t0, t1);
  r.bodies = restingBodies(raw, r.window);
  r.raw = motionMeasures(raw, r.window, r.bodies);
  return r;
}

/// GSL's centred moving mean of `values` over ±h samples, truncated at the ends: an independent
/// reference for the box filter's positions.
std::vector<double> gslMovingMean(const std::vector<double>& values, std::size_t h) {
  std::vector<double> out(values.size());
  gsl_movstat_workspace* workspace = gsl_movstat_alloc2(h, h);
  const gsl_vector_const_view in = gsl_vector_const_view_array(values.data(), values.size());
  gsl_vector_view result = gsl_vector_view_array(out.data(), out.size());
  gsl_movstat_mean(GSL_MOVSTAT_END_TRUNCATE, &in.vector, &result.vector, workspace);
  gsl_movstat_free(workspace);
  return out;
}

/// A sink that counts what it is given and keeps the last frame.
struct CountingSink : FrameSink {
  std::map<std::string, std::string> meta;
  long frames = 0;
  bool finished = false;
  TrajectoryFrame last;
  void begin(const std::map<std::string, std::string>& m, const std::vector<TrajectoryBody>&) override {
    meta = m;
  }
  void push(const TrajectoryFrame& f) override {
    ++frames;
    last = f;
  }
  void finish() override { finished = true; }
};

/// Quaternions equal as orientations and bit for bit up to the sign.
bool sameUpToSign(const Quat& a, const Quat& b) {
  return a.coeffs() == b.coeffs() || a.coeffs() == -b.coeffs();
}

}  // namespace

TEST_CASE("The box filter returns a motion linear in time unchanged away from the ends",
          "[filtering][closed_form]") {
  // x(t) = x0 + v t, and a uniform rotation at 3 rad/s about a fixed axis: every centred
  // window of either is symmetric about its centre, so its mean is the centre (for the
  // quaternions, the sin terms cancel and the cos terms scale the centre). The rotation passes
  // 2π over 2.5 s, so the recorded quaternions change sign along the way.
  const Vec3 x0(1.0, 2.0, -3.0), v(4.0, -1.5, 0.25);
  const Vec3 axis = Vec3(1.0, 2.0, 3.0).normalized();
  const Trajectory raw = synthetic(150, [&](double t, Vec3& x, Quat& q) {
    x = x0 + v * t;
    q = Quat(Eigen::AngleAxisd(3.0 * t, axis));
  });
  for (OrientationAverage average : {OrientationAverage::SignAlignedMean, OrientationAverage::Markley}) {
    for (int h : {1, 2, 5}) {
      BoxFilterParams p;
      p.halfWidth = h;
      p.orientationAverage = average;
      const Trajectory box = boxFilter(raw, p);
      double worstX = 0.0, worstAngle = 0.0;
      for (std::size_t k = h; k + h < raw.frames.size(); ++k) {
        worstX = std::max(worstX, (box.frames[k].x[1] - raw.frames[k].x[1]).norm());
        worstAngle = std::max(worstAngle, rotationAngle(box.frames[k].q[1], raw.frames[k].q[1]));
      }
      // Rounding: a sum of up to 11 positions (|x| < 10 m) carries a few ulp of 10 m.
      CHECK(worstX < 1e-12);
      CHECK(worstAngle < 1e-12);
    }
  }
}

TEST_CASE("The box filter at the ends averages the frames that exist (truncated window)",
          "[filtering][closed_form]") {
  const Trajectory raw = synthetic(20, [](double t, Vec3& x, Quat&) { x = Vec3(6.0 * t, 0.0, 0.0); });
  const Trajectory box = boxFilter(raw);  // H = 2: frame 0 is the mean of frames 0, 1, 2
  CHECK(box.frames[0].x[1].x() == Approx(6.0 * kDt).epsilon(1e-12));
  CHECK(box.frames[19].x[1].x() == Approx(6.0 * 18 * kDt).epsilon(1e-12));
  CHECK(box.frames[0].x[0] == raw.frames[0].x[0]);  // the ground is immovable: untouched
}

TEST_CASE("Quaternion sign flips in the input do not change the box filter's output",
          "[filtering][invariant]") {
  const Vec3 axis = Vec3(0.3, 1.0, -0.2).normalized();
  const Trajectory raw = synthetic(60, [&](double t, Vec3& x, Quat& q) {
    x = Vec3(0.0, 0.5 + 1e-3 * std::sin(40.0 * t), 0.0);
    q = Quat(Eigen::AngleAxisd(0.05 * std::sin(25.0 * t), axis));
  });
  Trajectory flipped = raw;
  for (std::size_t k = 0; k < flipped.frames.size(); k += 3) flipped.frames[k].q[1].coeffs() *= -1.0;
  for (OrientationAverage average : {OrientationAverage::SignAlignedMean, OrientationAverage::Markley}) {
    BoxFilterParams p;
    p.orientationAverage = average;
    const Trajectory a = boxFilter(raw, p);
    const Trajectory b = boxFilter(flipped, p);
    for (std::size_t k = 0; k < a.frames.size(); ++k) {
      CHECK(a.frames[k].x[1] == b.frames[k].x[1]);
      if (average == OrientationAverage::SignAlignedMean) {
        // Every sample is aligned with the centre before the sum: the same sum, or its negative.
        CHECK(sameUpToSign(a.frames[k].q[1], b.frames[k].q[1]));
      } else {
        CHECK(rotationAngle(a.frames[k].q[1], b.frames[k].q[1]) < 1e-12);
      }
    }
  }
}

TEST_CASE("Sign-aligned mean and Markley's average agree for a window of chatter",
          "[filtering][reference]") {
  // Orientations within 0.05 rad of each other: the two averages differ at third order in the
  // spread, (0.05)^3 ~ 1e-4 rad at most; measured far below.
  const Vec3 axes[] = {Vec3::UnitX(), Vec3(0.0, 1.0, 1.0).normalized(), Vec3::UnitZ()};
  std::vector<Quat> q;
  for (int i = 0; i < 5; ++i) q.push_back(Quat(Eigen::AngleAxisd(0.05 * std::sin(1.7 * i), axes[i % 3])));
  const Quat a = averageOrientations(q.data(), q.size(), q[2], OrientationAverage::SignAlignedMean);
  const Quat m = averageOrientations(q.data(), q.size(), q[2], OrientationAverage::Markley);
  CHECK(rotationAngle(a, m) < 1e-4);
  CHECK_THROWS_AS(averageOrientations(q.data(), 0, q[0], OrientationAverage::Markley), std::invalid_argument);
}

TEST_CASE("On the resting die the box filter lowers chatter at least 20-fold, the envelope "
          "filter stills it",
          "[filtering][chatter]") {
  const Trajectory& raw = chatteringDie();
  const auto [rest, resting, before] = restingRun(raw, 10.5, 12.0);
  REQUIRE(resting.size() == 1);
  REQUIRE(before.chatterPosition > 0.0);  // the plain step does chatter here (micrometres)
  const MotionMeasures box = motionMeasures(boxFilter(raw), rest, resting);
  // Measured: 37-fold (position), 22-fold (rotation). A lone one-frame spike of the position
  // becomes a 5-frame plateau a fifth as high: 6 a^2 of squared second differences falls to
  // 4 (a/5)^2, 37-fold; the margin allows for the spikes not being alone.
  CHECK(box.chatterPosition < before.chatterPosition / 20.0);
  CHECK(box.chatterAngle < before.chatterAngle / 10.0);
  // The squirm stays: the box filter turns chatter into slow motion (thesis §5.5), measured
  // 0.80 of raw; it cannot fall below a box filter's share of it by much.
  CHECK(box.squirmPosition > 0.5 * before.squirmPosition);
  const MotionMeasures envelope = motionMeasures(envelopeFilter(raw), rest, resting);
  CHECK(envelope.chatterPosition == 0.0);
  CHECK(envelope.chatterAngle == 0.0);
  CHECK(pops(envelopeFilter(raw), rest, resting).position == 0.0);
}

TEST_CASE("On the standing pyramid, whose chatter is visible, the box filter turns chatter into "
          "squirm and draws boxes into each other, and the envelope filter pops by its radius",
          "[filtering][chatter][pyramid]") {
  const Trajectory& raw = chatteringPyramid();
  const auto [rest, resting, before] = restingRun(raw, 1.0, 4.5);
  REQUIRE(resting.size() >= 10);  // 16 of the 55 cubes measured
  // Visible: a mean second difference of a millimetre (1e-6 m^2), where the die's is 6e-8 mm.
  REQUIRE(before.chatterPosition > 1e-7);
  const Trajectory boxed = boxFilter(raw);
  const MotionMeasures box = motionMeasures(boxed, rest, resting);
  INFO("raw: chatter " << before.chatterPosition << " m^2, squirm " << before.squirmPosition
                       << " m/s, displayed speed " << before.displayedSpeedPosition << " m/s; box: chatter "
                       << box.chatterPosition << ", squirm " << box.squirmPosition << ", displayed speed "
                       << box.displayedSpeedPosition);
  // The chatter falls by the same order as on the die (a 5-frame box, 37-fold on a lone spike).
  CHECK(box.chatterPosition < before.chatterPosition / 20.0);
  // What is left is mostly squirm: the displayed motion falls, the slow part of it does not,
  // so the share of the motion a viewer sees that is slow wandering rises. Raw, most of the
  // displayed path is jitter back and forth.
  CHECK(box.displayedSpeedPosition < before.displayedSpeedPosition);
  CHECK(box.squirmPosition > 0.5 * before.squirmPosition);
  // Measured: 0.43 of the displayed motion raw, 0.79 box-filtered.
  CHECK(before.squirmSharePosition() < 0.5);
  CHECK(box.squirmSharePosition() > 2.0 / 3.0);
  // Filtering creates interpenetration (§5.5): the average of neighbours' poses puts cubes
  // inside each other by more than a millimetre where the simulation had them less deep.
  CHECK(overlapIntroduced(raw, boxed, rest).boxBox > 1e-3);
  // The envelope filter pops: a cube that wanders out of its 2.5 cm envelope is shown jumping
  // to where the simulation has it, by at least the radius and at most the radius plus the
  // largest raw move of a frame.
  const Trajectory held = envelopeFilter(raw);
  const double radius = kEnvelopeRadiusFraction * 0.5;  // the default, for unit cubes
  const double rawJump = pops(raw, rest, resting).position;
  const double pop = pops(held, rest, resting).position;
  INFO("envelope pop " << pop << " m, radius " << radius << " m, largest raw frame move " << rawJump << " m");
  CHECK(pop >= radius);
  CHECK(pop <= radius + rawJump);
  CHECK(pop > 2.0 * rawJump);
  // Between pops the held cubes stand still: their rotation chatter falls tenfold or more.
  CHECK(motionMeasures(held, rest, resting).chatterAngle < before.chatterAngle / 10.0);
}

TEST_CASE("A wider box kernel blunts the pyramid's collisions more: the peak acceleration of the "
          "shot falls as 1/(2H+1), while chatter falls faster",
          "[filtering][impact][pyramid]") {
  const Trajectory& raw = chatteringPyramid();
  const FrameWindow shot = frameWindow(raw, 4.9, 5.6);
  const FrameWindow rest = frameWindow(raw, 1.0, 4.5);
  const std::vector<std::size_t> all = movableBodies(raw);
  const std::vector<std::size_t> resting = restingBodies(raw, rest);
  const double rawPeak = peakAcceleration(raw, shot, all).linear;
  const double rawChatter = motionMeasures(raw, rest, resting).chatterPosition;
  double lastPeak = rawPeak, lastChatter = rawChatter;
  for (const int h : {1, 2, 4, 8}) {
    BoxFilterParams params;
    params.halfWidth = h;
    const Trajectory filtered = boxFilter(raw, params);
    const double peak = peakAcceleration(filtered, shot, all).linear / rawPeak;
    const double chatter = motionMeasures(filtered, rest, resting).chatterPosition / rawChatter;
    INFO("H = " << h << ": peak acceleration " << peak << " of raw, chatter " << chatter << " of raw");
    // A velocity step spread over 2H + 1 frames peaks at 1/(2H + 1) of its raw acceleration;
    // impacts a few frames apart (the shot box and the cubes it hits) add a little to it
    // (measured 0.3333, 0.2000, 0.1113, 0.0592 against 1/3, 1/5, 1/9, 1/17).
    CHECK(peak < lastPeak / rawPeak);
    CHECK(peak > 0.99 / (2 * h + 1));
    CHECK(peak < 1.1 / (2 * h + 1));
    CHECK(chatter < lastChatter / rawChatter);
    CHECK(chatter < peak);
    lastPeak = peak * rawPeak;
    lastChatter = chatter * rawChatter;
  }
}

TEST_CASE("The box filter softens the die's landing as a box of 2H+1 frames does", "[filtering][impact]") {
  const Trajectory& raw = chatteringDie();
  const FrameWindow landing = frameWindow(raw, 0.35, 0.75);
  const std::vector<std::size_t> die = movableBodies(raw);
  const double rawPeak = peakAcceleration(raw, landing, die).linear;
  const double boxPeak = peakAcceleration(boxFilter(raw), landing, die).linear;
  // One step in velocity spread over 2H + 1 = 5 frames peaks at 1/5 of its raw acceleration;
  // the landing's rotation adds to it (measured 0.31).
  CHECK(boxPeak < 0.4 * rawPeak);
  CHECK(boxPeak > 0.2 * rawPeak * 0.99);
  CHECK(peakAcceleration(envelopeFilter(raw), landing, die).linear == rawPeak);
}

TEST_CASE("The envelope filter shows a body faster than its radius per frame with no lag",
          "[filtering][closed_form]") {
  // Free flight at 3 m/s horizontally, spinning: 5 cm per frame, twice the 2.5 cm envelope.
  const Trajectory raw = synthetic(90, [](double t, Vec3& x, Quat& q) {
    x = Vec3(3.0 * t, 5.0 - 0.5 * 9.81 * t * t, 0.0);
    q = Quat(Eigen::AngleAxisd(2.0 * t, Vec3::UnitZ()));
  });
  const Trajectory envelope = envelopeFilter(raw);
  for (std::size_t k = 0; k < raw.frames.size(); ++k) {
    CHECK(envelope.frames[k].x[1] == raw.frames[k].x[1]);
    CHECK(envelope.frames[k].q[1].coeffs() == raw.frames[k].q[1].coeffs());
  }
}

TEST_CASE("The envelope filter holds the pose inside the envelope and jumps when the body leaves it",
          "[filtering][closed_form]") {
  // A slow creep at 0.3 m/s: 5 mm per frame, so the stable pose jumps every 6th frame, by
  // 3 cm (the first position past r = 2.5 cm).
  const Trajectory raw = synthetic(40, [](double t, Vec3& x, Quat&) { x = Vec3(0.3 * t, 0.5, 0.0); });
  const Trajectory envelope = envelopeFilter(raw);
  CHECK(envelope.frames[5].x[1] == raw.frames[0].x[1]);
  CHECK(envelope.frames[6].x[1] == raw.frames[6].x[1]);
  CHECK(envelope.frames[11].x[1] == raw.frames[6].x[1]);
  CHECK(pops(envelope, FrameWindow{0, 40}, {1}).position == Approx(0.03).epsilon(1e-9));
  CausalEnvelopeFilter defaults(raw.bodies);
  CHECK(defaults.radius(1) == 0.025);
  CHECK(defaults.angle(1) == Approx(0.025 / std::sqrt(0.75)));
}

TEST_CASE("Filters keep the frame count, the times, the bodies and the other columns", "[filtering][invariant]") {
  const Trajectory& raw = chatteringDie();
  for (const Trajectory& out : {boxFilter(raw), envelopeFilter(raw)}) {
    REQUIRE(out.frames.size() == raw.frames.size());
    REQUIRE(out.bodies.size() == raw.bodies.size());
    for (std::size_t k = 0; k < raw.frames.size(); ++k) {
      CHECK(out.frames[k].t == raw.frames[k].t);
      CHECK(out.frames[k].kinetic == raw.frames[k].kinetic);
      CHECK(out.frames[k].potential == raw.frames[k].potential);
      CHECK(out.frames[k].contacts == raw.frames[k].contacts);
      CHECK(out.frames[k].events == raw.frames[k].events);
      CHECK(out.frames[k].x.size() == raw.bodies.size());
    }
    CHECK(out.frames.front().t == 0.0);
    CHECK(out.frames.back().t == raw.frames.back().t);
    CHECK(out.meta.count("filter") == 1);
  }
  CHECK(boxFilter(raw).meta.at("box_half_width") == "2");
  CHECK(envelopeFilter(raw, {0.01, 0.02}).meta.at("envelope_radius") == "0.01 m");
  CHECK(envelopeFilter(boxFilter(raw)).meta.at("filter") == "box, then envelope");
}

TEST_CASE("The causal filters agree with the offline ones: envelope exactly, box H frames late",
          "[filtering][reference]") {
  const Trajectory& raw = chatteringDie();
  const Trajectory envelope = envelopeFilter(raw);
  CausalEnvelopeFilter causalEnvelope(raw.bodies);
  for (std::size_t k = 0; k < raw.frames.size(); ++k) {
    const TrajectoryFrame shown = causalEnvelope.push(raw.frames[k]);
    CHECK(shown.x[1] == envelope.frames[k].x[1]);
    CHECK(shown.q[1].coeffs() == envelope.frames[k].q[1].coeffs());
  }
  for (int h : {0, 2, 4}) {
    BoxFilterParams p;
    p.halfWidth = h;
    const Trajectory box = boxFilter(raw, p);
    CausalBoxFilter causalBox(raw.bodies, p);
    CHECK(causalBox.lag() == h);
    for (std::size_t k = 0; k < raw.frames.size(); ++k) {
      const TrajectoryFrame shown = causalBox.push(raw.frames[k]);
      CHECK(shown.t == raw.frames[k].t);
      if (k < static_cast<std::size_t>(h)) continue;
      const TrajectoryFrame& centred = box.frames[k - h];
      // The same samples, order and sign reference: bit for bit.
      CHECK(shown.q[1].coeffs() == centred.q[1].coeffs());
      CHECK(shown.x[1] == centred.x[1]);
    }
  }
}

TEST_CASE("The measures give their closed forms", "[filtering][closed_form]") {
  // A jitter of ±a about a rest height: second differences ±4a, so chatter 16 a^2; the largest
  // frame-to-frame jump is 2a.
  const double a = 1e-3;
  const Trajectory jitter = synthetic(61, [&](double t, Vec3& x, Quat&) {
    x = Vec3(0.0, 0.5 + (std::lround(t / kDt) % 2 == 0 ? a : -a), 0.0);
  });
  const FrameWindow all{0, 61};
  const MotionMeasures m = motionMeasures(jitter, all, {1});
  CHECK(m.chatterPosition == Approx(16.0 * a * a).epsilon(1e-9));
  CHECK(m.chatterAngle == 0.0);
  CHECK(pops(jitter, all, {1}).position == Approx(2.0 * a).epsilon(1e-9));
  CHECK(restingBodies(jitter, all) == std::vector<std::size_t>{1});
  // Free fall: the second difference of an exact parabola over Δt² is g.
  const Trajectory fall = synthetic(30, [](double t, Vec3& x, Quat&) { x = Vec3(0.0, 10.0 - 0.5 * 9.81 * t * t, 0.0); });
  CHECK(peakAcceleration(fall, FrameWindow{0, 30}, {1}).linear == Approx(9.81).epsilon(1e-6));
  CHECK(restingBodies(fall, FrameWindow{0, 30}).empty());
  // A cube sunk 0.1 m into the ground (top at y = 0): overlap 0.1 m, which a filter that left
  // it there did not introduce.
  const Trajectory sunk = synthetic(3, [](double, Vec3& x, Quat&) { x = Vec3(0.0, 0.4, 0.0); });
  CHECK(deepestOverlap(sunk, FrameWindow{0, 3}).boxGround == Approx(0.1).epsilon(1e-9));
  CHECK(deepestOverlap(sunk, FrameWindow{0, 3}).boxBox == 0.0);
  const Trajectory resting = synthetic(3, [](double, Vec3& x, Quat&) { x = Vec3(0.0, 0.5, 0.0); });
  CHECK(overlapIntroduced(resting, sunk, FrameWindow{0, 3}).boxGround == Approx(0.1).epsilon(1e-9));
  CHECK(overlapIntroduced(sunk, sunk, FrameWindow{0, 3}).boxGround == 0.0);
}

TEST_CASE("Bad filter parameters and windows are refused with the parameter named", "[filtering][input]") {
  const Trajectory raw = synthetic(10, [](double, Vec3&, Quat&) {});
  BoxFilterParams box;
  box.halfWidth = -1;
  CHECK_THROWS_WITH(boxFilter(raw, box), Contains("half width"));
  CHECK_THROWS_AS(CausalBoxFilter(raw.bodies, box), std::invalid_argument);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(envelopeFilter(raw, {-0.1, {}}), Contains("radius"));
  CHECK_THROWS_WITH(envelopeFilter(raw, {nan, {}}), Contains("radius"));
  CHECK_THROWS_WITH(envelopeFilter(raw, {{}, inf}), Contains("angle"));
  CHECK_THROWS_WITH(envelopeFilter(raw, {{}, -1.0}), Contains("angle"));
  CHECK_THROWS_WITH(applyFilter(raw, {"blur", {}, {}, {}}), Contains("unknown filter 'blur'"));
  CHECK_THROWS_WITH(applyFilter(raw, {"box", {}, 0.1, {}}), Contains("--envelope-radius"));
  CHECK_THROWS_WITH(applyFilter(raw, {"envelope", 3, {}, {}}), Contains("--filter-half-width"));
  CHECK_THROWS_WITH(applyFilter(raw, {"", 3, {}, {}}), Contains("--filter box"));
  CHECK_THROWS_AS(frameWindow(raw, 5.0, 6.0), std::invalid_argument);
  CHECK_THROWS_AS(motionMeasures(raw, FrameWindow{0, 2}, {1}), std::invalid_argument);
  CHECK_THROWS_AS(motionMeasures(raw, FrameWindow{0, 10}, {7}), std::invalid_argument);
  Trajectory broken = raw;
  broken.frames[3].x.pop_back();
  CHECK_THROWS_WITH(boxFilter(broken), Contains("poses for 2 bodies"));
}

TEST_CASE("Filtering is deterministic", "[filtering][determinism]") {
  const Trajectory& raw = chatteringDie();
  BoxFilterParams markley;
  markley.orientationAverage = OrientationAverage::Markley;
  for (int pass = 0; pass < 2; ++pass) {
    CHECK(formatTrajectory(boxFilter(raw)) == formatTrajectory(boxFilter(raw)));
    CHECK(formatTrajectory(boxFilter(raw, markley)) == formatTrajectory(boxFilter(raw, markley)));
    CHECK(formatTrajectory(envelopeFilter(raw)) == formatTrajectory(envelopeFilter(raw)));
  }
}

TEST_CASE("The streamed box filter gives GSL's moving mean to rounding, frame k once frame k + H "
          "has come in",
          "[filtering][reference]") {
  const Trajectory& raw = chatteringDie();
  for (int h : {1, 2, 7}) {
    BoxFilterParams p;
    p.halfWidth = h;
    TrajectoryCollector out;
    BoxFilterStage stage(p, out);
    stage.begin(raw.meta, raw.bodies);
    for (std::size_t k = 0; k < raw.frames.size(); ++k) {
      stage.push(raw.frames[k]);
      // Frame k − H goes on as soon as frame k is in, not before.
      CHECK(out.trajectory().frames.size() == (k >= static_cast<std::size_t>(h) ? k - h + 1 : 0));
    }
    stage.finish();
    REQUIRE(out.trajectory().frames.size() == raw.frames.size());
    CHECK(out.trajectory().meta.at("box_half_width") == std::to_string(h));
    for (int c = 0; c < 3; ++c) {
      std::vector<double> series;
      for (const TrajectoryFrame& f : raw.frames) series.push_back(f.x[1][c]);
      const std::vector<double> mean = gslMovingMean(series, static_cast<std::size_t>(h));
      // GSL keeps a running mean, updated frame by frame over the whole run; the filter sums
      // each window afresh. Both round at a few ulp of the die's coordinates (|x| < 4 m,
      // ulp 4.4e-16 m) per operation; over the run's frames the running mean's error is a
      // random walk of a few hundred steps. 1e-12 m bounds both by far and is a millionth of
      // anything visible.
      double worst = 0.0;
      for (std::size_t k = 0; k < mean.size(); ++k)
        worst = std::max(worst, std::abs(out.trajectory().frames[k].x[1][c] - mean[k]));
      CHECK(worst < 1e-12);
    }
  }
}

TEST_CASE("The streamed filters end runs shorter than their window as the offline ones do",
          "[filtering][reference]") {
  const Trajectory& raw = chatteringDie();
  for (std::size_t n : {0, 1, 2, 3, 6}) {
    Trajectory shortRun = raw;
    shortRun.frames.resize(n);
    BoxFilterParams p;
    p.halfWidth = 3;
    const Trajectory box = boxFilter(shortRun, p);
    REQUIRE(box.frames.size() == n);
    for (std::size_t k = 0; k < n; ++k) {
      // Truncated windows: frame k is the mean of frames 0 … min(n − 1, k + 3).
      const std::size_t hi = std::min(n - 1, k + 3);
      const std::size_t lo = k >= 3 ? k - 3 : 0;
      Vec3 sum = Vec3::Zero();
      for (std::size_t j = lo; j <= hi; ++j) sum += raw.frames[j].x[1];
      CHECK((box.frames[k].x[1] - sum / static_cast<double>(hi - lo + 1)).norm() < 1e-13);
    }
    CountingSink sink;
    const std::unique_ptr<FrameSink> stage = makeFilterStage(FilterChoice{"envelope", {}, {}, {}}, sink);
    replayTrajectory(shortRun, *stage);
    CHECK(sink.frames == static_cast<long>(n));
    CHECK(sink.finished);
    CHECK(sink.meta.at("filter") == "envelope");
  }
}
