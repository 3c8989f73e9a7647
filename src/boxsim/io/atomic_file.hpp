/// \file
/// Output files are written whole or not at all: into a temporary file beside the target,
/// then renamed over it, so a crash or an error never leaves a partial file behind.
#pragma once

#include <string>

namespace boxsim {

/// Writes `content` to `path` atomically (temporary file in the same directory, then rename).
/// Throws std::runtime_error naming the path and the system error when it cannot; no
/// temporary file is left behind.
void writeFileAtomically(const std::string& path, const std::string& content);

/// A temporary path beside `path` (same directory, so a rename is atomic), created empty and
/// unique. The caller renames it over `path` with commitTemporary() or removes it.
std::string makeTemporaryBeside(const std::string& path);

/// Renames `temporaryPath` over `path`; throws std::runtime_error (and removes the temporary
/// file) when it cannot.
void commitTemporary(const std::string& temporaryPath, const std::string& path);

}  // namespace boxsim
