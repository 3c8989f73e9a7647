/// \file
/// How render.hpp draws with gnuplot. render_scene.hpp computes each frame's geometry and the
/// fixed axis ranges; this file chooses the frames, writes them as a gnuplot script and runs
/// gnuplot. For each frame the visible box faces become `splot ... with polygons`, one plot
/// element per shaded colour, which `pm3d depthorder` sorts back to front across elements; the
/// ground, its grid and the shadows are `set object` polygons and arrows behind them.
#include "boxsim/io/render.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <locale>
#include <map>
#include <sstream>
#include <stdexcept>

#include "boxsim/io/atomic_file.hpp"
#include "boxsim/io/render_scene.hpp"

namespace boxsim {

namespace {

using render::FrameDrawing;
using render::Polygon;
using render::Segment;

// Colours of the lines gnuplot draws itself; the fills come shaded from render_scene.hpp.
constexpr int kGroundEdgeColour = 0xb0b0b0;
constexpr int kGridColour = 0xcdcdcd;
constexpr int kEdgeColour = 0x2a2a2a;

// Browsers show GIF delays under 2/100 s as 1/10 s, so a real-time animation never asks for less.
constexpr double kMinGifDelay = 0.02;  // s

// Layout of one panel, pixels: a band for the title, a band for the time, and a margin around
// the picture. render::frameScene() decides how much of what is left the scene fills.
constexpr double kTextBand = 24.0;
constexpr double kPad = 6.0;

enum class ImageType { png, svg, gif };

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

// Where the panels and text bands lie on the canvas, pixels.
struct PanelLayout {
  int panels = 1;            // a strip puts the frames side by side; a GIF shows one at a time
  double panelWidth = 0.0;   // width of one panel
  double height = 0.0;       // height of the canvas
  double canvasWidth = 0.0;  // panels × panelWidth
  double titleBand = 0.0;    // band for the title at the top (0 without a title)
  double timeBand = 0.0;     // band for the time, below the title
  double areaTop = 0.0;      // top of the picture area, from the bottom of the canvas
};

PanelLayout panelLayout(ImageType type, std::size_t frameCount, const RenderOptions& options) {
  PanelLayout l;
  // A strip puts the frames side by side; a GIF shows them one after another.
  l.panels = type == ImageType::gif ? 1 : static_cast<int>(frameCount);
  l.panelWidth = std::max(16, options.width);
  l.height = std::max(16, options.height);
  l.canvasWidth = l.panelWidth * l.panels;
  l.titleBand = options.title.empty() ? 0.0 : std::min(kTextBand, 0.25 * l.height);
  l.timeBand = std::min(kTextBand, 0.25 * l.height);
  l.areaTop = l.height - l.titleBand - l.timeBand;
  return l;
}

// The script's preamble: terminal, output, view and the fixed axis ranges.
void writePreamble(ScriptWriter& script, ImageType type, const std::string& outputPath,
                   const PanelLayout& layout, const render::Framing& framing, int gifDelay) {
  std::ostringstream& s = script.out();
  const Vec3& c = framing.centre;
  s << terminalCommand(type, static_cast<int>(layout.canvasWidth), static_cast<int>(layout.height),
                       gifDelay)
    << "\n";
  s << "set output " << quoted(outputPath) << "\n";
  s << "set encoding utf8\n";
  s << "unset key\nunset border\nunset tics\nunset colorbox\n";
  s << "set view " << render::kViewRotX << ", " << render::kViewRotZ << ", 1, 1\n";
  s << "set view equal xyz\n";
  s << "set xyplane relative 0\n";
  s << "set pm3d depthorder\n";
  s << "set pm3d border lc rgb '" << hexColour(kEdgeColour) << "' lw 0.6\n";
  s << "set xrange [" << c.x() - 0.5 * framing.span << ":" << c.x() + 0.5 * framing.span << "]\n";
  s << "set yrange [" << c.y() - 0.5 * framing.span << ":" << c.y() + 0.5 * framing.span << "]\n";
  s << "set zrange [" << c.z() - framing.zHalf << ":" << c.z() + framing.zHalf << "]\n";
}

// A panel's margins, title (first panel, or every GIF frame) and time label.
void writePanelFrame(ScriptWriter& script, const PanelLayout& layout, double left,
                     const std::string& title, double t) {
  std::ostringstream& s = script.out();
  s << "unset object\nunset arrow\nunset label\n";
  s << "set lmargin at screen " << (left + kPad) / layout.canvasWidth << "\n";
  s << "set rmargin at screen " << (left + layout.panelWidth - kPad) / layout.canvasWidth << "\n";
  s << "set bmargin at screen " << kPad / layout.height << "\n";
  s << "set tmargin at screen " << layout.areaTop / layout.height << "\n";
  if (!title.empty()) {
    s << "set label 1 " << quoted(title) << " at screen 0.5, "
      << (layout.height - 0.5 * layout.titleBand) / layout.height
      << " center noenhanced font ',12'\n";
  }
  char time[64];
  std::snprintf(time, sizeof time, "t = %.2f s", t);
  s << "set label 2 " << quoted(time) << " at screen "
    << (left + 0.5 * layout.panelWidth) / layout.canvasWidth << ", "
    << (layout.areaTop + 0.5 * layout.timeBand) / layout.height << " center noenhanced\n";
}

// A filled polygon behind the plot as `set object` number `object`; `style` ends the line.
void writePolygonObject(ScriptWriter& script, int object, const Polygon& polygon,
                        const std::string& style) {
  std::ostringstream& s = script.out();
  s << "set object " << object << " polygon from ";
  for (std::size_t i = 0; i < polygon.corners.size(); ++i) {
    if (i > 0) s << " to ";
    script.point(polygon.corners[i]);
  }
  s << " to ";
  script.point(polygon.corners[0]);
  s << " behind fc rgb '" << hexColour(polygon.rgb) << "' fillstyle solid 1.0 " << style << "\n";
}

// The floors, the shadows on them and the grid, drawn behind the boxes.
void writeBackdrop(ScriptWriter& script, const FrameDrawing& drawing) {
  std::ostringstream& s = script.out();
  int object = 0;
  const std::string groundBorder = "border lc rgb '" + hexColour(kGroundEdgeColour) + "' lw 0.6";
  for (const Polygon& ground : drawing.grounds)
    writePolygonObject(script, ++object, ground, groundBorder);
  for (const Polygon& shadow : drawing.shadows)
    writePolygonObject(script, ++object, shadow, "noborder");
  for (const Segment& line : drawing.grid) {
    s << "set arrow from ";
    script.point(line.from);
    s << " to ";
    script.point(line.to);
    s << " nohead back lc rgb '" << hexColour(kGridColour) << "' lw 0.6\n";
  }
}

// The box faces as one `splot ... with polygons`, or a lone dot when there are none.
void writeFaces(ScriptWriter& script, const FrameDrawing& drawing, const render::Framing& framing) {
  std::ostringstream& s = script.out();
  const Vec3& c = framing.centre;
  if (drawing.faces.empty()) {
    // splot needs data: one dot in the background colour at the far corner of the ranges.
    s << "$frame << EOD\n"
      << c.x() - 0.5 * framing.span << ' ' << c.y() + 0.5 * framing.span << ' '
      << c.z() - framing.zHalf << "\nEOD\n";
    s << "splot $frame using 1:2:3 with dots lc rgb '#ffffff' notitle\n";
    return;
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

std::string scriptFor(const Trajectory& trajectory, ImageType type, const std::string& outputPath,
                      const RenderOptions& options) {
  const FramePlan plan = planFrames(trajectory, type, options);
  const render::SceneDrawer drawer(trajectory, options.groundHalfSize, options.bodyColours);
  // The camera is fixed by every frame, drawn or not, so that all pictures of a run agree.
  render::SceneBounds bounds;
  for (int f = 0; f < static_cast<int>(trajectory.frames.size()); ++f) {
    bounds.include(drawer.draw(f));
  }
  std::vector<FrameDrawing> drawings;
  for (const int f : plan.frames) drawings.push_back(drawer.draw(f));

  const PanelLayout layout = panelLayout(type, plan.frames.size(), options);
  const double areaWidth = layout.panelWidth - 2.0 * kPad;
  const double areaHeight = layout.areaTop - kPad;
  const render::Framing framing = render::frameScene(bounds, areaWidth, areaHeight);

  ScriptWriter script;
  std::ostringstream& s = script.out();
  s << "# boxsim render: " << plan.frames.size() << " frame(s) of " << trajectory.bodies.size()
    << " bodies\n";
  writePreamble(script, type, outputPath, layout, framing, plan.gifDelay);
  if (layout.panels > 1) s << "set multiplot\n";
  for (std::size_t panel = 0; panel < plan.frames.size(); ++panel) {
    const int f = plan.frames[panel];
    const double left =
        type == ImageType::gif ? 0.0 : layout.panelWidth * static_cast<double>(panel);
    const bool titled = panel == 0 || type == ImageType::gif;
    s << "# frame " << f << "\n";
    writePanelFrame(script, layout, left, titled ? options.title : std::string(),
                    trajectory.frames[f].t);
    writeBackdrop(script, drawings[panel]);
    writeFaces(script, drawings[panel], framing);
  }
  if (layout.panels > 1) s << "unset multiplot\n";
  s << "unset output\n";
  return script.str();
}

// gnuplot's standard error, for the message when it fails.
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
