/// \file
/// The comparison's outputs: the Markdown page (docs/benchmarks.md), stamped with the date,
/// commit, machine and compiler it was measured on, and the data of the scaling figure.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "peer_run.hpp"

namespace boxsim::peers {

/// The results of one scene under every engine, in the order they ran.
struct SceneResults {
  SceneSpec spec;
  std::vector<RunResult> runs;
};

/// The measures of a row the comparison with an earlier page reads, as the page prints them.
struct PrintedPhysics {
  std::string meanPenetration;   ///< mm, one decimal
  std::string finalPenetration;  ///< mm, one decimal
  std::string kinetic;           ///< J, three decimals
  std::string allAsleep;         ///< s, two decimals, or "never"
};

/// A page this tool wrote before (docs/benchmarks.md of an earlier commit), as
/// baselineComparison reads it.
struct BaselinePage {
  std::string path;    ///< where it was read from, as given
  std::string commit;  ///< the commit its stamp names; "unknown" when none
  /// Its rows by "scene label|engine", every engine's.
  std::map<std::string, PrintedPhysics> rows;
};

/// Reads the table of a page this tool wrote (`text`, read from `path`) by its header's column
/// names, so pages of earlier versions with other columns read too. Throws
/// std::invalid_argument, naming `path`, when it has no such table.
BaselinePage parseBaseline(const std::string& text, const std::string& path);

/// How the comparison was run, for the page's header.
struct RunSetup {
  int reps = 3;
  double dt = 1.0 / 60.0;     ///< s
  std::string command;        ///< the command line that made the page
  std::map<std::string, std::string> settings;  ///< engine name -> its settings
  std::string absent;         ///< peers not found at configure time
  /// A page written before (--baseline), whose boxsim rows' physics the page compares with
  /// this run's (baselineComparison); none: no comparison.
  std::optional<BaselinePage> baseline;
};

/// The physics of every boxsim row (the thesis' damped integration and its variants) beside
/// the same row of `baseline`: mean and final penetration, the kinetic energy at the end and
/// the time from which every box stays asleep, before → after, each compared as the pages
/// print it (a row is worse when one of them is: deeper, more energy, asleep later or never
/// where it slept), worse rows first. Rows missing from either page are left out; "" when
/// none is in both.
std::string baselineComparison(const std::vector<SceneResults>& scenes, const BaselinePage& baseline);

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
