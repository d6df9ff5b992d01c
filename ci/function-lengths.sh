#!/usr/bin/env bash
# Functions a reader can hold: none over 100 lines and at most three over 80, as pmccabe
# counts them (its fifth column), over every C++ source of the libraries, app, tests and
# benchmarks. Prints the offenders and fails when either limit is passed.
set -euo pipefail
cd "$(dirname "$0")/.."
# pmccabe reads no C++17 nested namespace ("namespace a::b {"): it reports nothing for such a
# file. Each file is read through a copy with them written out as nested blocks (clang-format
# closes every namespace with "}  // namespace a::b"), under its own path; a .cpp of
# which pmccabe still reads no function fails the check.
copies=$(mktemp -d)
trap 'rm -rf "$copies"' EXIT
files=$(find base scene bake cuts glsl gl render image tools generators app tests bench \
  -name '*.cpp' -o -name '*.h' | sort)
for f in $files; do
  mkdir -p "$copies/$(dirname "$f")"
  perl -pe 'if (/^namespace ([\w:]+) \{/) {
              my $n = $1;
              $_ = join(" ", map { "namespace $_ {" } split(/::/, $n)) . "\n" if $n =~ /::/;
            } elsif (/^\}  \/\/ namespace ([\w:]+)/) {
              my $n = $1;
              $_ = join(" ", map { "}" } split(/::/, $n)) . "\n" if $n =~ /::/;
            }' "$f" >"$copies/$f"
done
report=$(cd "$copies" && xargs pmccabe 2>/dev/null <<<"$files" | sort -t$'\t' -k5,5nr)
unread=$(cd "$copies" && for f in $files; do
  [[ $f == *.cpp && -z $(pmccabe "$f" 2>/dev/null) ]] && echo "$f"; done || true)
if [[ -n "$unread" ]]; then
  echo "function-lengths.sh: pmccabe read no function of:"; echo "$unread"; exit 1
fi
over100=$(awk -F'\t' '$5 > 100' <<<"$report")
over80=$(awk -F'\t' '$5 > 80' <<<"$report")
count80=$(grep -c . <<<"$over80" || true)
if [[ -n "$over100" ]]; then
  echo "function-lengths.sh: functions over 100 lines:"; cut -f5,6 <<<"$over100"; exit 1
fi
if (( count80 > 3 )); then
  echo "function-lengths.sh: $count80 functions over 80 lines (at most 3):"; cut -f5,6 <<<"$over80"; exit 1
fi
echo "function-lengths.sh: none over 100 lines, $count80 over 80:"
[[ -n "$over80" ]] && cut -f5,6 <<<"$over80"
exit 0
