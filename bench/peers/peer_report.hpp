/// \file
/// The comparison's outputs: the Markdown page (docs/benchmarks.md), stamped with the date,
/// commit, machine and compiler it was measured on, and the data of the scaling figure.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "peer_run.hpp"

namespace boxsim::peers {

/// The results of one scene under every engine, in the order they ran.
struct SceneResults {
  SceneSpec spec;
  std::vector<RunResult> runs;
};

/// How the comparison was run, for the page's header.
struct RunSetup {
  int reps = 3;
  double dt = 1.0 / 60.0;     ///< s
  std::string command;        ///< the command line that made the page
  std::map<std::string, std::string> settings;  ///< engine name -> its settings
  std::string absent;         ///< peers not found at configure time
  /// A page written before (--baseline), whose boxsim rows' physics the page compares with
  /// this run's (baselineComparison); empty: no comparison.
  std::string baselinePage;
  std::string baselinePath;   ///< where baselinePage was read from, as given
};

/// The physics of every boxsim row (the thesis' damped integration and its variants) beside
/// the same row of `baselinePage`, a page this tool wrote before: mean and final penetration,
/// the kinetic energy at the end and the time from which every box stays asleep, before →
/// after, each compared as the pages print it (a row is worse when one of them is: deeper,
/// more energy, asleep later or never where it slept), worse rows first. Rows missing from
/// either page are left out; "" when none is in both. Throws std::invalid_argument when
/// `baselinePage` has no table of this tool's form.
std::string baselineComparison(const std::vector<SceneResults>& scenes,
                               const std::string& baselinePage, const std::string& baselinePath);

/// "date, commit, machine, compiler" lines, measured now (the commit read from git in
/// `sourceDir`; "unknown" where git does not answer).
std::string stamp(const std::string& sourceDir);

/// The Markdown page: stamp, method, the summary (where boxsim damped integration is ahead of
/// the faster peer and where it is behind, by the ratio of mean ms per step), the table, and
/// every engine's settings.
std::string markdownPage(const std::vector<SceneResults>& scenes, const RunSetup& setup,
                         const std::string& stampText);

/// The scaling figure's data: one row per clump at restitution `restitution` and engine
/// (boxes, "engine", mean, median and 95th percentile ms per step, min and max of the
/// repetitions' means).
std::string scalingData(const std::vector<SceneResults>& scenes, double restitution,
                        const RunSetup& setup, const std::string& stampText);

}  // namespace boxsim::peers
