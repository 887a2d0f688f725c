#pragma once
// Writing output files so that a failure never leaves a half-written file behind.
#include <functional>
#include <ostream>
#include <string>

namespace rad {

/// Writes `path` through a temporary file in the same folder, renamed onto `path` only when
/// `write` returns without throwing and every byte reached the disk; otherwise the temporary
/// file is removed and an InputError names the path.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

/// Checks, before any work, that `path` names a file in an existing folder; throws InputError.
void checkOutputPath(const std::string& path);

}  // namespace rad
