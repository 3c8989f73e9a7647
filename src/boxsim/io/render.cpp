/// \file
/// How render.hpp draws with gnuplot. For each frame the visible box faces become
/// `splot ... with polygons`, one plot element per shaded colour, which `pm3d depthorder` sorts
/// back to front across elements; the ground, its grid and the shadows are `set object`
/// polygons and arrows behind them. The axis ranges and margins are chosen so that, with
/// `set view equal xyz`, the whole run fills the picture at one fixed zoom.
#include "boxsim/io/render.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <locale>
#include <map>
#include <sstream>
#include <stdexcept>

#include "boxsim/io/atomic_file.hpp"

namespace boxsim {

namespace {


// gnuplot's `set view rot_x, rot_z`: the camera sits 28° above the horizon (rot_x = 90° - 28°)
// and looks from the front right, so a box at rest shows its top, its +x and its +z faces.
constexpr double kViewRotX = 62.0;  // degrees
constexpr double kViewRotZ = 30.0;  // degrees

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
constexpr int kGroundEdgeColour = 0xb0b0b0;
constexpr int kGridColour = 0xcdcdcd;
constexpr int kShadowColour = 0xcacaca;
constexpr int kEdgeColour = 0x2a2a2a;

// Browsers show GIF delays under 2/100 s as 1/10 s, so a real-time animation never asks for less.
constexpr double kMinGifDelay = 0.02;  // s

// Layout of one panel, pixels: a band for the title, a band for the time, a margin around the
// picture, and the share of the remaining area the scene may fill.
constexpr double kTextBand = 24.0;
constexpr double kPad = 6.0;
constexpr double kFill = 0.94;

enum class ImageType { png, svg, gif };

using Vec2 = Eigen::Vector2d;  // (x, z) on the ground

// World y-up to gnuplot z-up: (x, y, z) -> (x, -z, y), a rotation by +90° about x (det +1).
Vec3 toGnuplot(const Vec3& w) { return Vec3(w.x(), -w.z(), w.y()); }

// The camera's screen axes in gnuplot coordinates for `set view a, b`. gnuplot rotates the
// scene about z by b, then about the screen's x by a; these are the rows of that rotation, so
// screen x = right·p, screen y = up·p, and `towards` points from the scene to the viewer.
struct ViewAxes {
  Vec3 right;
  Vec3 up;
  Vec3 towards;
};

ViewAxes viewAxes() {
  const double a = kViewRotX * kPi / 180.0;
  const double b = kViewRotZ * kPi / 180.0;
  return {Vec3(std::cos(b), std::sin(b), 0.0),
          Vec3(-std::sin(b) * std::cos(a), std::cos(b) * std::cos(a), std::sin(a)),
          Vec3(std::sin(a) * std::sin(b), -std::sin(a) * std::cos(b), std::cos(a))};
}

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

std::string hexColour(int rgb) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "#%06x", rgb & 0xffffff);
  return buffer;
}

// A gnuplot single-quoted string: no escapes except '' for a quote; one line only.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) {
    if (c == '\'') {
      out += "''";
    } else if (c == '\n' || c == '\r') {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out + "'";
}

std::string shellQuoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

ImageType imageTypeOf(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".png") return ImageType::png;
  if (extension == ".svg") return ImageType::svg;
  if (extension == ".gif") return ImageType::gif;
  throw std::invalid_argument("render: cannot draw '" + path + "': unsupported extension '" +
                              extension + "' (supported: .png, .svg, .gif)");
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

struct Polygon {
  std::vector<Vec3> corners;  // gnuplot coordinates
  int rgb = 0;
};

struct Segment {
  Vec3 from, to;  // gnuplot coordinates
};

// What one frame draws, in gnuplot coordinates.
struct FrameDrawing {
  std::vector<Polygon> faces;    // box faces turned towards the camera, depth sorted by gnuplot
  std::vector<Polygon> grounds;  // top faces of the huge immovable bodies, drawn behind all
  std::vector<Polygon> shadows;  // on the main ground, drawn over it
  std::vector<Segment> grid;     // on the main ground, drawn over the shadows
};

// Decides once, from every frame, what the ground square is and which bodies are drawn as
// boxes, then draws any frame.
class SceneDrawer {
 public:
  SceneDrawer(const Trajectory& trajectory, const RenderOptions& options)
      : trajectory_(trajectory), view_(viewAxes()) {
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
    // The square the ground is drawn in: the movable boxes' footprint over the whole run plus
    // room for two box sizes, so boxes near the edge still stand on visible ground.
    Vec2 low = Vec2::Constant(std::numeric_limits<double>::infinity());
    Vec2 high = -low;
    double largestHalfExtent = 0.0;
    for (std::size_t b = 0; b < bodyCount; ++b) {
      if (trajectory.bodies[b].immovable) continue;
      largestHalfExtent = std::max(largestHalfExtent, trajectory.bodies[b].halfExtents.maxCoeff());
      for (const TrajectoryFrame& frame : trajectory.frames) {
        for (const Face& face :
             boxFaces(frame.x[b], frame.q[b], trajectory.bodies[b].halfExtents)) {
          for (const Vec3& c : face.corners) {
            low = low.cwiseMin(groundPoint(c));
            high = high.cwiseMax(groundPoint(c));
          }
        }
      }
    }
    if (largestHalfExtent == 0.0) {  // nothing moves: a unit square at the origin
      low = Vec2::Constant(-0.5);
      high = Vec2::Constant(0.5);
      largestHalfExtent = 0.5;
    }
    squareCentre_ = 0.5 * (low + high);
    squareHalf_ = options.groundHalfSize > 0.0
                      ? options.groundHalfSize
                      : 0.5 * (high - low).maxCoeff() + 2.0 * largestHalfExtent;
    // An immovable body that does not fit in the square is a floor: only its top face is drawn.
    huge_.assign(bodyCount, false);
    for (std::size_t b = 0; b < bodyCount; ++b) {
      if (!trajectory.bodies[b].immovable || trajectory.frames.empty()) continue;
      Vec2 bodyLow = Vec2::Constant(std::numeric_limits<double>::infinity());
      Vec2 bodyHigh = -bodyLow;
      const TrajectoryFrame& first = trajectory.frames.front();
      for (const Face& face : boxFaces(first.x[b], first.q[b], trajectory.bodies[b].halfExtents)) {
        for (const Vec3& c : face.corners) {
          bodyLow = bodyLow.cwiseMin(groundPoint(c));
          bodyHigh = bodyHigh.cwiseMax(groundPoint(c));
        }
      }
      huge_[b] = (bodyHigh - bodyLow).maxCoeff() > 2.0 * squareHalf_;
    }
  }

  FrameDrawing draw(int frameIndex) const {
    const TrajectoryFrame& frame = trajectory_.frames[frameIndex];
    FrameDrawing drawing;
    std::vector<std::size_t> boxes;
    int movableOrdinal = 0;
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
        for (const HalfPlane& side : squareSides()) polygon = clipPolygon(polygon, side);
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
      const int colour =
          body.immovable
              ? kImmovableColour
              : kBodyColours[static_cast<std::size_t>(movableOrdinal) % kBodyColours.size()];
      if (!body.immovable) ++movableOrdinal;
      boxes.push_back(b);
      for (const Face& face : faces) {
        // Orthographic camera: a face is seen exactly when its normal points at the viewer.
        if (toGnuplot(face.normal).dot(view_.towards) <= 1e-9) continue;
        drawing.faces.push_back({toGnuplotAll({face.corners.begin(), face.corners.end()}),
                                 shadeColour(colour, face.normal)});
      }
    }
    if (!mainGroundPolygon.empty()) {
      drawShadows(frame, boxes, mainGround, mainGroundPolygon, drawing);
      drawGrid(mainGround, mainGroundPolygon, drawing);
    }
    return drawing;
  }

 private:
  std::array<HalfPlane, 4> squareSides() const {
    const double x = squareCentre_.x();
    const double z = squareCentre_.y();
    return {HalfPlane{1.0, 0.0, squareHalf_ - x}, HalfPlane{-1.0, 0.0, squareHalf_ + x},
            HalfPlane{0.0, 1.0, squareHalf_ - z}, HalfPlane{0.0, -1.0, squareHalf_ + z}};
  }

  static std::vector<Vec3> toGnuplotAll(const std::vector<Vec3>& world) {
    std::vector<Vec3> out;
    out.reserve(world.size());
    for (const Vec3& p : world) out.push_back(toGnuplot(p));
    return out;
  }

  // Straight-down shadows: they show how high a box is above the ground, which a single
  // orthographic view otherwise hides.
  void drawShadows(const TrajectoryFrame& frame, const std::vector<std::size_t>& boxes,
                   const GroundPlane& ground, const std::vector<Vec3>& groundPolygon,
                   FrameDrawing& drawing) const {
    const std::vector<HalfPlane> inside = insideOf(groundPolygon);
    for (const std::size_t b : boxes) {
      const Vec3& centre = frame.x[b];
      if (centre.y() < ground.heightAt(centre.x(), centre.z())) continue;
      std::vector<Vec3> corners;
      for (const Face& face : boxFaces(frame.x[b], frame.q[b], trajectory_.bodies[b].halfExtents)) {
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
  void drawGrid(const GroundPlane& ground, const std::vector<Vec3>& groundPolygon,
                FrameDrawing& drawing) const {
    const std::vector<HalfPlane> inside = insideOf(groundPolygon);
    const double step = niceStep(squareHalf_ / 3.0);
    for (int axis = 0; axis < 2; ++axis) {
      const double centreAlong = squareCentre_[axis];
      const double centreAcross = squareCentre_[1 - axis];
      const long first = std::lround(std::ceil((centreAlong - squareHalf_) / step));
      const long last = std::lround(std::floor((centreAlong + squareHalf_) / step));
      for (long n = first; n <= last; ++n) {
        const double at = static_cast<double>(n) * step;
        if (std::abs(std::abs(at - centreAlong) - squareHalf_) < 1e-3 * step) continue;
        Vec3 from = axis == 0 ? Vec3(at, 0.0, centreAcross - squareHalf_)
                              : Vec3(centreAcross - squareHalf_, 0.0, at);
        Vec3 to = axis == 0 ? Vec3(at, 0.0, centreAcross + squareHalf_)
                            : Vec3(centreAcross + squareHalf_, 0.0, at);
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

  const Trajectory& trajectory_;
  ViewAxes view_;
  Vec2 squareCentre_ = Vec2::Zero();
  double squareHalf_ = 1.0;
  std::vector<bool> huge_;
};

// Axis ranges for gnuplot. With `set view equal xyz`, equal x and y spans and screen margins,
// gnuplot maps a point p to pixel (centre of the plot area) + side / span · (right·(p − c),
// up·(p − c)), where side is the smaller dimension of the plot area (graph3d.c normalises the
// range box to [−1, 1] and draws it at half the side). So the span sets the zoom and the range
// centre c is what appears in the middle.
struct Framing {
  Vec3 centre = Vec3::Zero();
  double span = 1.0;   // of x and of y, m
  double zHalf = 1.0;  // half of the z range, m
};

// The bounds of everything drawn, in gnuplot coordinates and on the screen.
class SceneBounds {
 public:
  void include(const FrameDrawing& drawing) {
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

  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 high = Vec3::Constant(-std::numeric_limits<double>::infinity());
  Vec2 screenLow = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 screenHigh = Vec2::Constant(-std::numeric_limits<double>::infinity());

 private:
  void include(const Vec3& p) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
    const Vec2 s(view_.right.dot(p), view_.up.dot(p));
    screenLow = screenLow.cwiseMin(s);
    screenHigh = screenHigh.cwiseMax(s);
  }
  ViewAxes view_ = viewAxes();
};

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

void checkFrames(const Trajectory& trajectory, const std::vector<int>& frames) {
  const int count = static_cast<int>(trajectory.frames.size());
  for (const int f : frames) {
    if (f < 0 || f >= count) {
      throw std::out_of_range("render: frame " + std::to_string(f) +
                              " is out of range; valid frames are 0.." + std::to_string(count - 1));
    }
  }
}

// The subsampling stride for a GIF: at most maxFrames frames, at least kMinGifDelay apart, and
// among the strides that satisfy both, the first whose spacing is a whole number of GIF delay
// units (1/100 s) to within 2 %, so the animation plays at real time (1/60 s frames: stride 3).
int gifStride(int count, double spacing, int maxFrames) {
  int stride = std::max(1, (count + std::max(1, maxFrames) - 1) / std::max(1, maxFrames));
  if (spacing <= 0.0) return stride;
  stride = std::max(stride, static_cast<int>(std::ceil(kMinGifDelay / spacing - 1e-9)));
  const auto timingError = [spacing](int s) {
    const double delay = 100.0 * spacing * s;
    return std::abs(std::max(1.0, std::round(delay)) / delay - 1.0);
  };
  int best = stride;
  for (int s = stride; s <= 2 * stride + 4; ++s) {
    if (timingError(s) <= 0.02) return s;
    if (timingError(s) < timingError(best)) best = s;
  }
  return best;
}

struct FramePlan {
  std::vector<int> frames;
  int gifDelay = 10;  // 1/100 s
};

FramePlan planFrames(const Trajectory& trajectory, ImageType type, const RenderOptions& options) {
  if (trajectory.frames.empty())
    throw std::invalid_argument("render: the trajectory has no frames");
  if (trajectory.bodies.empty())
    throw std::invalid_argument("render: the trajectory has no bodies to draw");
  checkFrames(trajectory, options.frames);
  FramePlan plan;
  if (type != ImageType::gif) {
    plan.frames = options.frames.empty() ? std::vector<int>{0} : options.frames;
    return plan;
  }
  std::vector<int> candidates = options.frames;
  if (candidates.empty()) {
    for (int f = 0; f < static_cast<int>(trajectory.frames.size()); ++f) candidates.push_back(f);
  }
  const int count = static_cast<int>(candidates.size());
  const double spacing =
      count > 1
          ? (trajectory.frames[candidates.back()].t - trajectory.frames[candidates.front()].t) /
                (count - 1)
          : 0.0;
  const int stride = options.gifDelaySeconds > 0.0
                         ? gifStride(count, 0.0, options.maxGifFrames)
                         : gifStride(count, spacing, options.maxGifFrames);
  for (int i = 0; i < count; i += stride) plan.frames.push_back(candidates[i]);
  const double delay = options.gifDelaySeconds > 0.0 ? options.gifDelaySeconds
                       : spacing > 0.0               ? spacing * stride
                                                     : 0.1;
  plan.gifDelay = std::max(1, static_cast<int>(std::lround(100.0 * delay)));
  return plan;
}

class ScriptWriter {
 public:
  ScriptWriter() {
    out_.imbue(std::locale::classic());
    out_.precision(7);
  }
  std::ostringstream& out() { return out_; }
  void point(const Vec3& p) { out_ << p.x() << ',' << p.y() << ',' << p.z(); }
  std::string str() const { return out_.str(); }

 private:
  std::ostringstream out_;
};

std::string terminalCommand(ImageType type, int width, int height, int gifDelay) {
  const std::string size = " size " + std::to_string(width) + "," + std::to_string(height);
  switch (type) {
    case ImageType::png:
      return "set terminal pngcairo" + size + " enhanced font 'Sans,10' background '#ffffff'";
    case ImageType::svg:
      return "set terminal svg" + size + " fixed enhanced font 'Sans,10' background '#ffffff'";
    case ImageType::gif:
      return "set terminal gif animate delay " + std::to_string(gifDelay) + " loop 0" + size +
             " background '#ffffff'";
  }
  return "";
}

std::string scriptFor(const Trajectory& trajectory, ImageType type, const std::string& outputPath,
                      const RenderOptions& options) {
  const FramePlan plan = planFrames(trajectory, type, options);
  const SceneDrawer drawer(trajectory, options);
  // The camera is fixed by every frame, drawn or not, so that all pictures of a run agree.
  SceneBounds bounds;
  for (int f = 0; f < static_cast<int>(trajectory.frames.size()); ++f) {
    bounds.include(drawer.draw(f));
  }
  std::vector<FrameDrawing> drawings;
  for (const int f : plan.frames) drawings.push_back(drawer.draw(f));

  // A strip puts the frames side by side; a GIF shows them one after another.
  const int panels = type == ImageType::gif ? 1 : static_cast<int>(plan.frames.size());
  const double panelWidth = std::max(16, options.width);
  const double height = std::max(16, options.height);
  const double canvasWidth = panelWidth * panels;
  const double titleBand = options.title.empty() ? 0.0 : std::min(kTextBand, 0.25 * height);
  const double timeBand = std::min(kTextBand, 0.25 * height);
  const double areaTop = height - titleBand - timeBand;
  const double areaWidth = panelWidth - 2.0 * kPad;
  const double areaHeight = areaTop - kPad;
  const Framing framing = frameScene(bounds, areaWidth, areaHeight);
  const Vec3& c = framing.centre;

  ScriptWriter script;
  std::ostringstream& s = script.out();
  s << "# boxsim render: " << plan.frames.size() << " frame(s) of " << trajectory.bodies.size()
    << " bodies\n";
  s << terminalCommand(type, static_cast<int>(canvasWidth), static_cast<int>(height), plan.gifDelay)
    << "\n";
  s << "set output " << quoted(outputPath) << "\n";
  s << "set encoding utf8\n";
  s << "unset key\nunset border\nunset tics\nunset colorbox\n";
  s << "set view " << kViewRotX << ", " << kViewRotZ << ", 1, 1\n";
  s << "set view equal xyz\n";
  s << "set xyplane relative 0\n";
  s << "set pm3d depthorder\n";
  s << "set pm3d border lc rgb '" << hexColour(kEdgeColour) << "' lw 0.6\n";
  s << "set xrange [" << c.x() - 0.5 * framing.span << ":" << c.x() + 0.5 * framing.span << "]\n";
  s << "set yrange [" << c.y() - 0.5 * framing.span << ":" << c.y() + 0.5 * framing.span << "]\n";
  s << "set zrange [" << c.z() - framing.zHalf << ":" << c.z() + framing.zHalf << "]\n";
  if (panels > 1) s << "set multiplot\n";

  for (std::size_t panel = 0; panel < plan.frames.size(); ++panel) {
    const int f = plan.frames[panel];
    const FrameDrawing& drawing = drawings[panel];
    const double left = type == ImageType::gif ? 0.0 : panelWidth * static_cast<double>(panel);
    s << "# frame " << f << "\n";
    s << "unset object\nunset arrow\nunset label\n";
    s << "set lmargin at screen " << (left + kPad) / canvasWidth << "\n";
    s << "set rmargin at screen " << (left + panelWidth - kPad) / canvasWidth << "\n";
    s << "set bmargin at screen " << kPad / height << "\n";
    s << "set tmargin at screen " << areaTop / height << "\n";
    if (!options.title.empty() && (panel == 0 || type == ImageType::gif)) {
      s << "set label 1 " << quoted(options.title) << " at screen 0.5, "
        << (height - 0.5 * titleBand) / height << " center noenhanced font ',12'\n";
    }
    char time[64];
    std::snprintf(time, sizeof time, "t = %.2f s", trajectory.frames[f].t);
    s << "set label 2 " << quoted(time) << " at screen " << (left + 0.5 * panelWidth) / canvasWidth
      << ", " << (areaTop + 0.5 * timeBand) / height << " center noenhanced\n";
    int object = 0;
    for (const Polygon& ground : drawing.grounds) {
      s << "set object " << ++object << " polygon from ";
      for (std::size_t i = 0; i < ground.corners.size(); ++i) {
        if (i > 0) s << " to ";
        script.point(ground.corners[i]);
      }
      s << " to ";
      script.point(ground.corners[0]);
      s << " behind fc rgb '" << hexColour(ground.rgb) << "' fillstyle solid 1.0 border lc rgb '"
        << hexColour(kGroundEdgeColour) << "' lw 0.6\n";
    }
    for (const Polygon& shadow : drawing.shadows) {
      s << "set object " << ++object << " polygon from ";
      for (std::size_t i = 0; i < shadow.corners.size(); ++i) {
        if (i > 0) s << " to ";
        script.point(shadow.corners[i]);
      }
      s << " to ";
      script.point(shadow.corners[0]);
      s << " behind fc rgb '" << hexColour(shadow.rgb) << "' fillstyle solid 1.0 noborder\n";
    }
    for (const Segment& line : drawing.grid) {
      s << "set arrow from ";
      script.point(line.from);
      s << " to ";
      script.point(line.to);
      s << " nohead back lc rgb '" << hexColour(kGridColour) << "' lw 0.6\n";
    }
    if (drawing.faces.empty()) {
      // splot needs data: one dot in the background colour at the far corner of the ranges.
      s << "$frame << EOD\n"
        << c.x() - 0.5 * framing.span << ' ' << c.y() + 0.5 * framing.span << ' '
        << c.z() - framing.zHalf << "\nEOD\n";
      s << "splot $frame using 1:2:3 with dots lc rgb '#ffffff' notitle\n";
      continue;
    }
    // The faces grouped by colour, one data set (index) per colour: `with polygons` takes one
    // fill colour per plot element, and the gif terminal would round per-point colours to its
    // own table. Polygons are separated by one blank line, data sets by two.
    std::map<int, std::vector<const Polygon*>> byColour;
    for (const Polygon& face : drawing.faces) byColour[face.rgb].push_back(&face);
    s << "$frame << EOD\n";
    for (const auto& [rgb, faces] : byColour) {
      for (const Polygon* face : faces) {
        for (const Vec3& p : face->corners) s << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
        s << '\n';
      }
      s << '\n';
    }
    s << "EOD\n";
    s << "splot";
    int index = 0;
    for (const auto& [rgb, faces] : byColour) {
      s << (index > 0 ? ", \\\n  ''" : " $frame") << " index " << index
        << " with polygons fillstyle solid 1.0 fc rgb '" << hexColour(rgb) << "' notitle";
      ++index;
    }
    s << "\n";
  }
  if (panels > 1) s << "unset multiplot\n";
  s << "unset output\n";
  return script.str();
}

// A file that is removed when this goes out of scope, unless released.
std::string readWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

std::string renderScript(const Trajectory& trajectory, const std::string& outputPath,
                         const RenderOptions& options) {
  return scriptFor(trajectory, imageTypeOf(outputPath), outputPath, options);
}

void renderTrajectory(const Trajectory& trajectory, const std::string& outputPath,
                      const RenderOptions& options) {
  const ImageType type = imageTypeOf(outputPath);
  // imageTypeOf() has checked the extension before any file exists.
  TemporaryFile image(makeTemporaryBeside(outputPath));
  const std::string script = scriptFor(trajectory, type, image.path(), options);

  const std::string scratch = std::filesystem::temp_directory_path().string();
  const TemporaryFile scriptFile(makeTemporaryIn(scratch, "boxsim-render-"));
  const TemporaryFile errorFile(makeTemporaryIn(scratch, "boxsim-render-stderr-"));
  {
    std::ofstream out(scriptFile.path(), std::ios::binary);
    out << script;
    out.close();
    if (!out) throw std::runtime_error("render: cannot write '" + scriptFile.path() + "'");
  }
  const char* fromEnvironment = std::getenv("BOXSIM_GNUPLOT");
  const std::string gnuplot =
      (fromEnvironment != nullptr && *fromEnvironment != '\0') ? fromEnvironment : "gnuplot";
  const std::string command = shellQuoted(gnuplot) + " " + shellQuoted(scriptFile.path()) +
                              " </dev/null >/dev/null 2>" + shellQuoted(errorFile.path());
  const int status = std::system(command.c_str());
  const bool succeeded = status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  std::error_code sizeError;
  const auto written = std::filesystem::file_size(image.path(), sizeError);
  if (!succeeded || sizeError || written == 0) {
    std::string message = readWholeFile(errorFile.path());
    while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) {
      message.pop_back();
    }
    if (message.empty()) message = succeeded ? "gnuplot wrote an empty image" : "no message";
    throw std::runtime_error("render: gnuplot ('" + gnuplot + "') failed to draw '" + outputPath +
                             "': " + message);
  }
  commitTemporary(image.path(), outputPath);
  image.release();
}

}  // namespace boxsim
