#include "boxsim/io/trajectory.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "boxsim/io/atomic_file.hpp"
#include "boxsim/core/frame_sink.hpp"

namespace boxsim {

namespace {

constexpr int kFrameColumns = 7;  // t kinetic potential total contacts events bisections
constexpr int kBodyColumns = 7;   // x y z qw qx qy qz

TrajectoryFormatError formatError(const std::string& path, int line, const std::string& what) {
  return TrajectoryFormatError(path + ":" + std::to_string(line) + ": " + what +
                               " (is this a trajectory written by `boxsim run`?)");
}

void requireValidName(const TrajectoryBody& b) {
  const bool blank = std::any_of(b.name.begin(), b.name.end(),
                                 [](unsigned char c) { return std::isspace(c) != 0; });
  if (b.name.empty() || blank)
    throw std::invalid_argument("trajectory body name '" + b.name +
                                "' must be non-empty and free of white space");
}

/// Reads a trajectory file line by line: header lines into meta and bodies, frame rows into
/// the sink (begun at the first row).
class TrajectoryParser {
 public:
  TrajectoryParser(std::string path, FrameSink& sink) : path_(std::move(path)), sink_(sink) {}

  void line(const std::string& text) {
    ++lineNumber_;
    if (text.empty()) return;
    if (text[0] == '#') {
      header(text);
      return;
    }
    if (!sawMagic_) throw formatError(path_, lineNumber_, "missing '# boxsim trajectory' header");
    begin();
    sink_.push(frame(text));
  }

  void end() {
    if (!sawMagic_) throw formatError(path_, lineNumber_, "missing '# boxsim trajectory' header");
    begin();
    sink_.finish();
  }

 private:
  std::string path_;
  FrameSink& sink_;
  int lineNumber_ = 0;
  bool sawMagic_ = false;
  bool begun_ = false;
  std::map<std::string, std::string> meta_;
  std::vector<TrajectoryBody> bodies_;

  void begin() {
    if (begun_) return;
    begun_ = true;
    sink_.begin(meta_, bodies_);
  }

  void header(const std::string& text) {
    if (begun_) throw formatError(path_, lineNumber_, "a header line after the first frame");
    if (text.rfind("# boxsim trajectory", 0) == 0) {
      sawMagic_ = true;
    } else if (text.rfind("# body ", 0) == 0) {
      bodies_.push_back(body(text));
    } else if (text.rfind("# columns:", 0) != 0) {
      const std::size_t colon = text.find(": ");
      if (colon != std::string::npos && colon > 2)
        meta_[text.substr(2, colon - 2)] = text.substr(colon + 2);
    }
  }

  TrajectoryBody body(const std::string& text) const {
    std::istringstream fields(text.substr(7));
    int index = -1;
    TrajectoryBody b;
    std::string word;
    int immovable = 0;
    fields >> index >> b.name >> word >> b.halfExtents[0] >> b.halfExtents[1] >>
        b.halfExtents[2] >> word >> immovable;
    if (!fields || index != static_cast<int>(bodies_.size()))
      throw formatError(path_, lineNumber_, "malformed '# body' line");
    b.immovable = immovable != 0;
    return b;
  }

  TrajectoryFrame frame(const std::string& text) const {
    std::istringstream fields(text);
    TrajectoryFrame f;
    double total = 0.0;
    fields >> f.t >> f.kinetic >> f.potential >> total >> f.contacts >> f.events >> f.bisections;
    const std::size_t n = bodies_.size();
    f.x.resize(n);
    f.q.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      double w = 0, x = 0, y = 0, z = 0;
      fields >> f.x[i][0] >> f.x[i][1] >> f.x[i][2] >> w >> x >> y >> z;
      f.q[i] = Quat(w, x, y, z);
    }
    std::string extra;
    if (!fields || (fields >> extra))
      throw formatError(path_, lineNumber_,
                        "expected " + std::to_string(kFrameColumns + kBodyColumns * n) +
                            " numeric columns for " + std::to_string(n) + " bodies");
    return f;
  }
};

}  // namespace

std::string formatTrajectoryHeader(const std::map<std::string, std::string>& meta,
                                   const std::vector<TrajectoryBody>& bodies) {
  for (const TrajectoryBody& b : bodies) requireValidName(b);
  std::string out = "# boxsim trajectory 1\n";
  for (const auto& [key, value] : meta) out += "# " + key + ": " + value + "\n";
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const TrajectoryBody& b = bodies[i];
    out += "# body " + std::to_string(i) + " " + b.name + " half_extents ";
    for (int k = 0; k < 3; ++k) {
      appendShortestText(out, b.halfExtents[k]);
      out += ' ';
    }
    out += std::string("immovable ") + (b.immovable ? "1" : "0") + "\n";
  }
  out += "# columns: t kinetic potential total contacts events bisections";
  for (std::size_t i = 0; i < bodies.size(); ++i)
    for (const char* c : {"x", "y", "z", "qw", "qx", "qy", "qz"})
      out += " b" + std::to_string(i) + "_" + c;
  out += '\n';
  return out;
}

void appendTrajectoryRow(std::string& out, const TrajectoryFrame& f) {
  for (double value : {f.t, f.kinetic, f.potential, f.kinetic + f.potential}) {
    appendShortestText(out, value);
    out += ' ';
  }
  out += std::to_string(f.contacts) + ' ' + std::to_string(f.events) + ' ' +
         std::to_string(f.bisections);
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    for (double value : {f.x[i].x(), f.x[i].y(), f.x[i].z(), f.q[i].w(), f.q[i].x(), f.q[i].y(),
                         f.q[i].z()}) {
      out += ' ';
      appendShortestText(out, value);
    }
  }
  out += '\n';
}

std::string formatTrajectory(const Trajectory& trajectory) {
  std::string out = formatTrajectoryHeader(trajectory.meta, trajectory.bodies);
  for (const TrajectoryFrame& f : trajectory.frames) appendTrajectoryRow(out, f);
  return out;
}

void writeTrajectory(const std::string& path, const Trajectory& trajectory) {
  writeFileAtomically(path, formatTrajectory(trajectory));
}

Trajectory readTrajectory(const std::string& path) {
  TrajectoryCollector collector;
  readTrajectory(path, collector);
  return collector.take();
}

void readTrajectory(const std::string& path, FrameSink& sink) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open trajectory file '" + path + "'");
  TrajectoryParser parser(path, sink);
  std::string line;
  while (std::getline(in, line)) parser.line(line);
  if (in.bad()) throw std::runtime_error("cannot read trajectory file '" + path + "'");
  parser.end();
}

}  // namespace boxsim
