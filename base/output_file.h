#pragma once
// Outputs appear whole or not at all: write a temporary file beside the target, then rename.
#include <filesystem>
#include <string>

namespace manylight {

// A hidden temporary path in the target's folder that keeps the target's extension (so
// format-by-extension writers still work). Creates the folder. Throws Error.
std::filesystem::path prepareTemporaryFor(const std::filesystem::path& target);

// Renames `tmp` to `target`, or removes `tmp` and throws Error naming `target`.
void commitTemporary(const std::filesystem::path& tmp, const std::filesystem::path& target);

// Writes `bytes` (text or binary) to `path` through a temporary file. Throws Error.
void writeFileAtomic(const std::string& path, const std::string& bytes);

}  // namespace manylight
