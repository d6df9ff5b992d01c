#!/usr/bin/env bash
# CI: every C++ file follows .clang-format (Google style, 100 columns). Fix with
#   git ls-files '*.cpp' '*.h' | xargs clang-format -i
set -euo pipefail
cd "$(dirname "$0")/.."
git ls-files '*.cpp' '*.h' | xargs clang-format --dry-run -Werror
echo "format-check.sh: all C++ files formatted"
