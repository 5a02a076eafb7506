#pragma once

namespace bsmpm {
// The program's version and the source tree it was built from (sim/core/version.cpp.in,
// written at every build by sim/core/git_revision.cmake): the git revision, with
// "-dirty.HASH" when the tree had uncommitted changes (HASH from those changes). Stored in
// every run and checkpoint, and part of a study case's key (docs/studies.md).
extern const char* const kVersion;
extern const char* const kGitRevision;
}  // namespace bsmpm
