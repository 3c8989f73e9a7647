/// \file
/// How render_scene.hpp computes a frame. Everything is worked out in world coordinates (y up)
/// and turned into gnuplot's z-up frame only when it is stored in a FrameDrawing, so the ground
/// geometry (clipping, hulls, grid) can drop y and work in (x, z). Shadows and grid lines are
/// then lifted back onto the floor's plane, which holds for a tilted floor as well.
#include "boxsim/io/render_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace boxsim::render {

namespace {

// Lambert shading, ambient plus diffuse; the light comes from above, a little from the front
// and the right, so the three faces a box shows the camera get three distinct shades. The
// diffuse term is rounded to sixteenths: a GIF frame holds at most 256 colours, and few
// distinct shades also mean few plot elements.
constexpr double kAmbient = 0.45;
constexpr double kDiffuse = 0.55;
constexpr double kShadeLevels = 16.0;
Vec3 towardsLight() { return Vec3(0.25, 1.0, 0.5).normalized(); }

// Body colours, cycled over the movable bodies in body order.
constexpr std::array<int, 10> kBodyColours = {0x4c72b0, 0xdd8452, 0x55a868, 0xc44e52, 0x8172b3,
                                              0x937860, 0xda8bc3, 0x64b5cd, 0xccb974, 0x7f3c8d};
constexpr int kImmovableColour = 0x8d939c;  // walls, steps and other small immovable boxes
constexpr int kGroundColour = 0xf0f0f0;     // before shading
// An immovable body this many times wider than the largest moving box is a floor.
constexpr double kFloorWidthRatio = 20.0;
constexpr int kShadowColour = 0xcacaca;

// The share of the plot area (after the text bands and margins) the scene may fill, so the
// outermost edges do not touch the picture's border.
constexpr double kFill = 0.94;

// World y-up to gnuplot z-up: (x, y, z) -> (x, -z, y), a rotation by +90° about x (det +1).
Vec3 toGnuplot(const Vec3& w) { return Vec3(w.x(), -w.z(), w.y()); }

int shadeColour(int rgb, const Vec3& worldNormal) {
  const double lambert = std::round(std::max(0.0, worldNormal.dot(towardsLight())) * kShadeLevels);
  const double shade = kAmbient + kDiffuse * lambert / kShadeLevels;
  int out = 0;
  for (int shift = 16; shift >= 0; shift -= 8) {
    const double channel = static_cast<double>((rgb >> shift) & 0xff) * shade;
    out = (out << 8) | static_cast<int>(std::clamp(std::lround(channel), 0L, 255L));
  }
  return out;
}

// A face of a box: corners in world coordinates and its outward normal. The face on side s
// (±1) of box axis i has normal s·e_i; with (j, k) = (i+1, i+2) mod 3, corner c lies at
// s·h_i e_i + σ_j h_j e_j + σ_k h_k e_k, (σ_j, σ_k) running (−,−) (+,−) (+,+) (−,+). Because
// e_j × e_k = e_i that is anticlockwise about the outward normal; s = −1 faces reverse it.
// The +y face (i = y, j = z, k = x) seen from above:
//
//              −z
//          0 ------ 3
//          |        |
//       −x |   +y   | +x
//          |        |
//          1 ------ 2
//              +z
struct Face {
  std::array<Vec3, 4> corners;
  Vec3 normal;
};

std::array<Face, 6> boxFaces(const Vec3& x, const Quat& q, const Vec3& h) {
  const Mat3 R = q.normalized().toRotationMatrix();
  std::array<Face, 6> faces;
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const int k = (i + 2) % 3;
    for (const double s : {1.0, -1.0}) {
      constexpr std::array<std::array<double, 2>, 4> kSigns = {
          {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}}};
      Face& face = faces[n++];
      for (int c = 0; c < 4; ++c) {
        const int slot = s > 0.0 ? c : 3 - c;
        Vec3 local = Vec3::Zero();
        local[i] = s * h[i];
        local[j] = kSigns[c][0] * h[j];
        local[k] = kSigns[c][1] * h[k];
        face.corners[slot] = x + R * local;
      }
      face.normal = R.col(i) * s;
    }
  }
  return faces;
}

// The half plane a·x + b·z + c >= 0 on the ground.
struct HalfPlane {
  double a, b, c;
  double operator()(const Vec3& p) const { return a * p.x() + b * p.z() + c; }
};

// Sutherland–Hodgman: the part of a convex polygon (world points) inside a vertical half
// space. Interpolating whole 3D points keeps a planar polygon planar.
std::vector<Vec3> clipPolygon(const std::vector<Vec3>& polygon, const HalfPlane& plane) {
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec3& p = polygon[i];
    const Vec3& q = polygon[(i + 1) % polygon.size()];
    const double fp = plane(p);
    const double fq = plane(q);
    if (fp >= 0.0) out.push_back(p);
    if ((fp >= 0.0) != (fq >= 0.0)) {
      const double t = fp / (fp - fq);
      out.push_back(p + t * (q - p));
    }
  }
  return out;
}

double cross2(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }
Vec2 groundPoint(const Vec3& p) { return Vec2(p.x(), p.z()); }

// The edges of a convex polygon (seen from above) as inward half planes.
std::vector<HalfPlane> insideOf(const std::vector<Vec3>& convex) {
  double area = 0.0;
  for (std::size_t i = 0; i < convex.size(); ++i) {
    area += cross2(groundPoint(convex[i]), groundPoint(convex[(i + 1) % convex.size()]));
  }
  const double orientation = area >= 0.0 ? 1.0 : -1.0;
  std::vector<HalfPlane> planes;
  for (std::size_t i = 0; i < convex.size(); ++i) {
    const Vec2 p = groundPoint(convex[i]);
    const Vec2 d = groundPoint(convex[(i + 1) % convex.size()]) - p;
    if (d.squaredNorm() == 0.0) continue;
    // orientation · cross2(d, q - p) >= 0
    planes.push_back({-orientation * d.y(), orientation * d.x(), orientation * cross2(p, d)});
  }
  return planes;
}

double groundArea(const std::vector<Vec3>& polygon) {
  double area = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    area += cross2(groundPoint(polygon[i]), groundPoint(polygon[(i + 1) % polygon.size()]));
  }
  return 0.5 * std::abs(area);
}

// Andrew's monotone chain on the ground shadows of the points (y dropped).
std::vector<Vec3> groundHull(std::vector<Vec3> points) {
  std::sort(points.begin(), points.end(), [](const Vec3& p, const Vec3& q) {
    return p.x() < q.x() || (p.x() == q.x() && p.z() < q.z());
  });
  std::vector<Vec3> hull(2 * points.size());
  std::size_t k = 0;
  const auto turn = [](const Vec3& o, const Vec3& a, const Vec3& b) {
    return cross2(groundPoint(a) - groundPoint(o), groundPoint(b) - groundPoint(o));
  };
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k > 1 ? k - 1 : k);
  return hull;
}

// A plane y = f(x, z) through a point with an upward normal.
struct GroundPlane {
  Vec3 point;
  Vec3 normal;
  double heightAt(double x, double z) const {
    return point.y() - (normal.x() * (x - point.x()) + normal.z() * (z - point.z())) / normal.y();
  }
  Vec3 lift(const Vec3& p) const { return Vec3(p.x(), heightAt(p.x(), p.z()), p.z()); }
};

// A round grid step (1, 2 or 5 times a power of ten) near `approximate`.
double niceStep(double approximate) {
  const double decade = std::pow(10.0, std::floor(std::log10(approximate)));
  const double m = approximate / decade;
  return decade * (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0);
}

// The four sides of the ground square as inward half planes.
std::array<HalfPlane, 4> squareSides(const Vec2& squareCentre, double squareHalf) {
  const double x = squareCentre.x();
  const double z = squareCentre.y();
  return {HalfPlane{1.0, 0.0, squareHalf - x}, HalfPlane{-1.0, 0.0, squareHalf + x},
          HalfPlane{0.0, 1.0, squareHalf - z}, HalfPlane{0.0, -1.0, squareHalf + z}};
}

std::vector<Vec3> toGnuplotAll(const std::vector<Vec3>& world) {
  std::vector<Vec3> out;
  out.reserve(world.size());
  for (const Vec3& p : world) out.push_back(toGnuplot(p));
  return out;
}

// Straight-down shadows: they show how high a box is above the ground, which a single
// orthographic view otherwise hides.
void drawShadows(const std::vector<TrajectoryBody>& bodies, const TrajectoryFrame& frame,
                 const std::vector<std::size_t>& boxes, const GroundPlane& ground,
                 const std::vector<Vec3>& groundPolygon, FrameDrawing& drawing) {
  const std::vector<HalfPlane> inside = insideOf(groundPolygon);
  for (const std::size_t b : boxes) {
    const Vec3& centre = frame.x[b];
    if (centre.y() < ground.heightAt(centre.x(), centre.z())) continue;
    std::vector<Vec3> corners;
    for (const Face& face : boxFaces(frame.x[b], frame.q[b], bodies[b].halfExtents)) {
      corners.insert(corners.end(), face.corners.begin(), face.corners.end());
    }
    std::vector<Vec3> shadow = groundHull(corners);
    for (const HalfPlane& side : inside) shadow = clipPolygon(shadow, side);
    if (shadow.size() < 3) continue;
    for (Vec3& p : shadow) p = ground.lift(p);
    drawing.shadows.push_back({toGnuplotAll(shadow), shadeColour(kShadowColour, ground.normal)});
  }
}

// Grid lines at round multiples of a step near a sixth of the square, clipped to the ground.
void drawGrid(const Vec2& squareCentre, double squareHalf, const GroundPlane& ground,
              const std::vector<Vec3>& groundPolygon, FrameDrawing& drawing) {
  const std::vector<HalfPlane> inside = insideOf(groundPolygon);
  const double step = niceStep(squareHalf / 3.0);
  for (int axis = 0; axis < 2; ++axis) {
    const double centreAlong = squareCentre[axis];
    const double centreAcross = squareCentre[1 - axis];
    const long first = std::lround(std::ceil((centreAlong - squareHalf) / step));
    const long last = std::lround(std::floor((centreAlong + squareHalf) / step));
    for (long n = first; n <= last; ++n) {
      const double at = static_cast<double>(n) * step;
      if (std::abs(std::abs(at - centreAlong) - squareHalf) < 1e-3 * step) continue;
      Vec3 from = axis == 0 ? Vec3(at, 0.0, centreAcross - squareHalf)
                            : Vec3(centreAcross - squareHalf, 0.0, at);
      Vec3 to = axis == 0 ? Vec3(at, 0.0, centreAcross + squareHalf)
                          : Vec3(centreAcross + squareHalf, 0.0, at);
      // Cyrus–Beck against the convex ground polygon.
      double t0 = 0.0;
      double t1 = 1.0;
      for (const HalfPlane& side : inside) {
        const double f0 = side(from);
        const double f1 = side(to);
        if (f0 < 0.0 && f1 < 0.0) {
          t0 = 1.0;
          t1 = 0.0;
          break;
        }
        if (f0 < 0.0) t0 = std::max(t0, f0 / (f0 - f1));
        if (f1 < 0.0) t1 = std::min(t1, f0 / (f0 - f1));
      }
      if (t1 - t0 < 1e-9) continue;
      const Vec3 a = from + t0 * (to - from);
      const Vec3 c = from + t1 * (to - from);
      drawing.grid.push_back({toGnuplot(ground.lift(a)), toGnuplot(ground.lift(c))});
    }
  }
}

// Fill colours before shading: the palette cycled over the movable bodies, grey for immovable
// ones, unless bodyColours names the body.
std::vector<int> fillColours(const Trajectory& trajectory,
                             const std::map<std::string, int>& bodyColours) {
  const std::size_t bodyCount = trajectory.bodies.size();
  std::vector<int> colour(bodyCount, kImmovableColour);
  std::size_t movableOrdinal = 0;
  for (std::size_t b = 0; b < bodyCount; ++b)
    if (!trajectory.bodies[b].immovable)
      colour[b] = kBodyColours[movableOrdinal++ % kBodyColours.size()];
  for (const auto& [name, rgb] : bodyColours) {
    std::size_t b = 0;
    while (b < bodyCount && trajectory.bodies[b].name != name) ++b;
    if (b == bodyCount)
      throw std::invalid_argument("render: a colour is given for body '" + name +
                                  "', but the trajectory has no body of that name");
    if (rgb < 0 || rgb > 0xffffff)
      throw std::invalid_argument("render: the colour of body '" + name +
                                  "' must be 0xRRGGBB (0 to 0xffffff)");
    colour[b] = rgb;
  }
  return colour;
}

// Every frame has one finite, non-zero pose per body.
void checkPoses(const Trajectory& trajectory) {
  const std::size_t bodyCount = trajectory.bodies.size();
  for (std::size_t f = 0; f < trajectory.frames.size(); ++f) {
    const TrajectoryFrame& frame = trajectory.frames[f];
    if (frame.x.size() != bodyCount || frame.q.size() != bodyCount) {
      throw std::invalid_argument("render: frame " + std::to_string(f) + " has " +
                                  std::to_string(frame.x.size()) + " positions and " +
                                  std::to_string(frame.q.size()) + " orientations for " +
                                  std::to_string(bodyCount) + " bodies");
    }
    for (std::size_t b = 0; b < bodyCount; ++b) {
      if (!frame.x[b].allFinite() || !frame.q[b].coeffs().allFinite() ||
          frame.q[b].norm() == 0.0) {
        throw std::invalid_argument("render: frame " + std::to_string(f) + " gives body '" +
                                    trajectory.bodies[b].name + "' a non-finite pose");
      }
    }
  }
}

// The ground shadow (x, z) of a box, m, widens [low, high].
void widenByBox(const TrajectoryFrame& frame, std::size_t b, const Vec3& halfExtents, Vec2& low,
                Vec2& high) {
  for (const Face& face : boxFaces(frame.x[b], frame.q[b], halfExtents)) {
    for (const Vec3& c : face.corners) {
      low = low.cwiseMin(groundPoint(c));
      high = high.cwiseMax(groundPoint(c));
    }
  }
}

// The movable boxes' footprint on the ground over the whole run, (x, z) in m, and their
// largest half extent; a unit square at the origin (half extent 0.5) when nothing moves.
struct Footprint {
  Vec2 low = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 high = Vec2::Constant(-std::numeric_limits<double>::infinity());
  double largestHalfExtent = 0.0;
};

Footprint movableFootprint(const Trajectory& trajectory) {
  Footprint footprint;
  for (std::size_t b = 0; b < trajectory.bodies.size(); ++b) {
    if (trajectory.bodies[b].immovable) continue;
    footprint.largestHalfExtent =
        std::max(footprint.largestHalfExtent, trajectory.bodies[b].halfExtents.maxCoeff());
    for (const TrajectoryFrame& frame : trajectory.frames)
      widenByBox(frame, b, trajectory.bodies[b].halfExtents, footprint.low, footprint.high);
  }
  if (footprint.largestHalfExtent == 0.0) {  // nothing moves: a unit square at the origin
    footprint.low = Vec2::Constant(-0.5);
    footprint.high = Vec2::Constant(0.5);
    footprint.largestHalfExtent = 0.5;
  }
  return footprint;
}

}  // namespace

ViewAxes viewAxes() {
  const double a = kViewRotX * kPi / 180.0;
  const double b = kViewRotZ * kPi / 180.0;
  return {Vec3(std::cos(b), std::sin(b), 0.0),
          Vec3(-std::sin(b) * std::cos(a), std::cos(b) * std::cos(a), std::sin(a)),
          Vec3(std::sin(a) * std::sin(b), -std::sin(a) * std::cos(b), std::cos(a))};
}

SceneDrawer::SceneDrawer(const Trajectory& trajectory, double groundHalfSize,
                         const std::map<std::string, int>& bodyColours)
    : trajectory_(trajectory), view_(viewAxes()) {
  const std::size_t bodyCount = trajectory.bodies.size();
  colour_ = fillColours(trajectory, bodyColours);
  checkPoses(trajectory);
  // The square the ground is drawn in: the movable boxes' footprint over the whole run plus
  // room for two box sizes, so boxes near the edge still stand on visible ground.
  const Footprint footprint = movableFootprint(trajectory);
  squareCentre_ = 0.5 * (footprint.low + footprint.high);
  squareHalf_ = groundHalfSize > 0.0 ? groundHalfSize
                                     : 0.5 * (footprint.high - footprint.low).maxCoeff() +
                                           2.0 * footprint.largestHalfExtent;
  // An immovable body that does not fit in the square, or is far wider than any moving box, is
  // a floor: only its top face is drawn. (Boxes that slide off a floor widen the square past
  // it; drawn as a box, that floor's sides then covered the picture in dark grey.)
  huge_.assign(bodyCount, false);
  for (std::size_t b = 0; b < bodyCount; ++b) {
    if (!trajectory.bodies[b].immovable || trajectory.frames.empty()) continue;
    Vec2 bodyLow = Vec2::Constant(std::numeric_limits<double>::infinity());
    Vec2 bodyHigh = -bodyLow;
    widenByBox(trajectory.frames.front(), b, trajectory.bodies[b].halfExtents, bodyLow, bodyHigh);
    const double width = (bodyHigh - bodyLow).maxCoeff();
    huge_[b] = width > 2.0 * squareHalf_ ||
               width > kFloorWidthRatio * 2.0 * footprint.largestHalfExtent;
  }
}

FrameDrawing SceneDrawer::draw(int frameIndex) const {
  const TrajectoryFrame& frame = trajectory_.frames[frameIndex];
  FrameDrawing drawing;
  std::vector<std::size_t> boxes;
  // The largest floor in view receives the shadows and the grid.
  GroundPlane mainGround{};
  std::vector<Vec3> mainGroundPolygon;
  double mainGroundArea = 0.0;
  for (std::size_t b = 0; b < trajectory_.bodies.size(); ++b) {
    const TrajectoryBody& body = trajectory_.bodies[b];
    const std::array<Face, 6> faces = boxFaces(frame.x[b], frame.q[b], body.halfExtents);
    if (huge_[b]) {
      const Face* top = &faces[0];
      for (const Face& face : faces) {
        if (face.normal.y() > top->normal.y()) top = &face;
      }
      if (top->normal.y() < 0.2) continue;  // no face looks up: not a floor
      std::vector<Vec3> polygon(top->corners.begin(), top->corners.end());
      for (const HalfPlane& side : squareSides(squareCentre_, squareHalf_)) {
        polygon = clipPolygon(polygon, side);
      }
      if (polygon.size() < 3) continue;
      drawing.grounds.push_back({toGnuplotAll(polygon), shadeColour(kGroundColour, top->normal)});
      const double area = groundArea(polygon);
      if (area > mainGroundArea) {
        mainGroundArea = area;
        mainGround = GroundPlane{top->corners[0], top->normal};
        mainGroundPolygon = polygon;
      }
      continue;
    }
    const int colour = colour_[b];
    boxes.push_back(b);
    for (const Face& face : faces) {
      // Orthographic camera: a face is seen exactly when its normal points at the viewer.
      if (toGnuplot(face.normal).dot(view_.towards) <= 1e-9) continue;
      drawing.faces.push_back({toGnuplotAll({face.corners.begin(), face.corners.end()}),
                               shadeColour(colour, face.normal)});
    }
  }
  if (!mainGroundPolygon.empty()) {
    drawShadows(trajectory_.bodies, frame, boxes, mainGround, mainGroundPolygon, drawing);
    drawGrid(squareCentre_, squareHalf_, mainGround, mainGroundPolygon, drawing);
  }
  return drawing;
}

void SceneBounds::include(const FrameDrawing& drawing) {
  for (const std::vector<Polygon>* list : {&drawing.faces, &drawing.grounds, &drawing.shadows}) {
    for (const Polygon& polygon : *list) {
      for (const Vec3& p : polygon.corners) include(p);
    }
  }
  for (const Segment& segment : drawing.grid) {
    include(segment.from);
    include(segment.to);
  }
}

void SceneBounds::include(const Vec3& p) {
  low = low.cwiseMin(p);
  high = high.cwiseMax(p);
  const Vec2 s(view_.right.dot(p), view_.up.dot(p));
  screenLow = screenLow.cwiseMin(s);
  screenHigh = screenHigh.cwiseMax(s);
}

Framing frameScene(const SceneBounds& bounds, double areaWidth, double areaHeight) {
  const ViewAxes view = viewAxes();
  const Vec3& low = bounds.low;
  const Vec3& high = bounds.high;
  Framing framing;
  if (!(low.x() <= high.x())) return framing;  // nothing to draw
  const Vec3 boxCentre = 0.5 * (low + high);
  const Vec2 screenCentre = 0.5 * (bounds.screenLow + bounds.screenHigh);
  const Vec2 screenHalf = 0.5 * (bounds.screenHigh - bounds.screenLow);
  // Move the range centre within the screen plane until it projects to the picture's middle.
  framing.centre = boxCentre + (screenCentre.x() - view.right.dot(boxCentre)) * view.right +
                   (screenCentre.y() - view.up.dot(boxCentre)) * view.up;
  const double side = std::min(areaWidth, areaHeight);
  double span = std::max(2.0 * screenHalf.x() * side / (kFill * areaWidth),
                         2.0 * screenHalf.y() * side / (kFill * areaHeight));
  // Everything drawn must lie inside the ranges, or pm3d would clip it.
  for (int axis = 0; axis < 2; ++axis) {
    span = std::max(
        span, 2.0 * std::max(high[axis] - framing.centre[axis], framing.centre[axis] - low[axis]));
  }
  framing.span = std::max(span * (1.0 + 1e-6), 1e-6);
  framing.zHalf =
      std::max(std::max(high.z() - framing.centre.z(), framing.centre.z() - low.z()) * 1.001, 1e-6);
  return framing;
}

}  // namespace boxsim::render
