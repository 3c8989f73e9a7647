#include "boxsim/io/trajectory.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "boxsim/io/atomic_file.hpp"

namespace boxsim {

namespace {

constexpr int kFrameColumns = 7;  // t kinetic potential total contacts events bisections
constexpr int kBodyColumns = 7;   // x y z qw qx qy qz

void appendNumber(std::string& out, double value) { out += shortestText(value); }

std::runtime_error formatError(const std::string& path, int line, const std::string& what) {
  return std::runtime_error(path + ":" + std::to_string(line) + ": " + what +
                            " (is this a trajectory written by `boxsim run`?)");
}

}  // namespace

std::string formatTrajectory(const Trajectory& trajectory) {
  for (const TrajectoryBody& b : trajectory.bodies) {
    const bool blank = std::any_of(b.name.begin(), b.name.end(),
                                   [](unsigned char c) { return std::isspace(c) != 0; });
    if (b.name.empty() || blank)
      throw std::invalid_argument("trajectory body name '" + b.name +
                                  "' must be non-empty and free of white space");
  }
  std::string out = "# boxsim trajectory 1\n";
  for (const auto& [key, value] : trajectory.meta) out += "# " + key + ": " + value + "\n";
  for (std::size_t i = 0; i < trajectory.bodies.size(); ++i) {
    const TrajectoryBody& b = trajectory.bodies[i];
    out += "# body " + std::to_string(i) + " " + b.name + " half_extents ";
    for (int k = 0; k < 3; ++k) {
      appendNumber(out, b.halfExtents[k]);
      out += ' ';
    }
    out += std::string("immovable ") + (b.immovable ? "1" : "0") + "\n";
  }
  out += "# columns: t kinetic potential total contacts events bisections";
  for (std::size_t i = 0; i < trajectory.bodies.size(); ++i)
    for (const char* c : {"x", "y", "z", "qw", "qx", "qy", "qz"})
      out += " b" + std::to_string(i) + "_" + c;
  out += '\n';
  for (const TrajectoryFrame& f : trajectory.frames) {
    for (double value : {f.t, f.kinetic, f.potential, f.kinetic + f.potential}) {
      appendNumber(out, value);
      out += ' ';
    }
    out += std::to_string(f.contacts) + ' ' + std::to_string(f.events) + ' ' +
           std::to_string(f.bisections);
    for (std::size_t i = 0; i < f.x.size(); ++i) {
      for (double value : {f.x[i].x(), f.x[i].y(), f.x[i].z(), f.q[i].w(), f.q[i].x(),
                           f.q[i].y(), f.q[i].z()}) {
        out += ' ';
        appendNumber(out, value);
      }
    }
    out += '\n';
  }
  return out;
}

void writeTrajectory(const std::string& path, const Trajectory& trajectory) {
  writeFileAtomically(path, formatTrajectory(trajectory));
}

Trajectory readTrajectory(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open trajectory file '" + path + "'");
  Trajectory trajectory;
  std::string line;
  int lineNumber = 0;
  bool sawMagic = false;
  while (std::getline(in, line)) {
    ++lineNumber;
    if (line.empty()) continue;
    if (line[0] == '#') {
      if (line.rfind("# boxsim trajectory", 0) == 0) {
        sawMagic = true;
      } else if (line.rfind("# body ", 0) == 0) {
        std::istringstream fields(line.substr(7));
        int index = -1;
        TrajectoryBody body;
        std::string word;
        int immovable = 0;
        fields >> index >> body.name >> word >> body.halfExtents[0] >> body.halfExtents[1] >>
            body.halfExtents[2] >> word >> immovable;
        if (!fields || index != static_cast<int>(trajectory.bodies.size()))
          throw formatError(path, lineNumber, "malformed '# body' line");
        body.immovable = immovable != 0;
        trajectory.bodies.push_back(body);
      } else if (line.rfind("# columns:", 0) != 0) {
        const std::size_t colon = line.find(": ");
        if (colon != std::string::npos && colon > 2)
          trajectory.meta[line.substr(2, colon - 2)] = line.substr(colon + 2);
      }
      continue;
    }
    if (!sawMagic) throw formatError(path, lineNumber, "missing '# boxsim trajectory' header");
    std::istringstream fields(line);
    TrajectoryFrame f;
    double total = 0.0;
    fields >> f.t >> f.kinetic >> f.potential >> total >> f.contacts >> f.events >> f.bisections;
    const std::size_t n = trajectory.bodies.size();
    f.x.resize(n);
    f.q.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      double w = 0, x = 0, y = 0, z = 0;
      fields >> f.x[i][0] >> f.x[i][1] >> f.x[i][2] >> w >> x >> y >> z;
      f.q[i] = Quat(w, x, y, z);
    }
    std::string extra;
    if (!fields || (fields >> extra))
      throw formatError(path, lineNumber,
                        "expected " + std::to_string(kFrameColumns + kBodyColumns * n) +
                            " numeric columns for " + std::to_string(n) + " bodies");
    trajectory.frames.push_back(std::move(f));
  }
  if (!sawMagic) throw formatError(path, lineNumber, "missing '# boxsim trajectory' header");
  return trajectory;
}

}  // namespace boxsim
