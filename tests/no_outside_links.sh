#!/usr/bin/env bash
# Nothing in the repository points outside it (issue 25). Fails, listing each line, if a
# tracked file (git ls-files; .ci/ and this script left out) contains
#   - `../shared`: the folder of the specification beside the author's checkout, which no
#     clone has (the contract is docs/contract.md);
#   - `SPEC.md`: that specification by name;
#   - an absolute path into somebody's machine: /work/, /root/, /home/, /Users/, /mnt/,
#     /media/, /scratch/, /srv/ (also as file:///work/...), or a Windows C:\Users\.
# Paths a program or a page legitimately names are not matched: system paths such as
# /usr/include, /dev/null, /dev/stdout, /proc/self/exe, /etc, /opt/heavytop, mkstemp's
# /tmp/NAME-XXXXXX; HDF5 paths (/axes/0); relative paths that merely contain such a word
# (build/work/, docs/work-precision.png, "$work/out").
# Usage: bash no_outside_links.sh [SOURCE_DIR]   (default: the checkout holding this script)
# Exit 0 clean, 1 found, 77 (skipped) outside a git checkout or without git.
set -u
src=${1:-"$(dirname "$0")/.."}
cd "$src" || exit 2
if ! command -v git >/dev/null 2>&1 || ! git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  echo "no_outside_links: $src is not a git checkout (or git is missing): skipped"
  exit 77
fi

# Extended regular expressions, one a line (grep -E). A machine path starts a word: the
# character before its first slash is not one of a relative path's (a name, $var, ${var}).
patterns=(
  '\.\./shared'
  'SPEC\.md'
  '(^|[^A-Za-z0-9_.~$}-])/(work|root|home|Users|mnt|media|scratch|srv)/'
  '[A-Za-z]:\\(Users|Documents and Settings)\\'
)
args=()
for p in "${patterns[@]}"; do args+=(-e "$p"); done

# Tracked files as they are in the work tree; -I skips binary files (PNG figures).
found=$(git grep -n -I -E "${args[@]}" -- . ':(exclude).ci' ':(exclude)tests/no_outside_links.sh')
status=$?
if [ $status -eq 1 ]; then
  echo "no_outside_links: no tracked file points outside the repository"
  exit 0
elif [ $status -ne 0 ]; then
  echo "no_outside_links: git grep failed (status $status)"
  exit 2
fi
echo "$found" | cut -c1-240
files=$(echo "$found" | cut -d: -f1 | sort -u)
echo
echo "no_outside_links: $(echo "$found" | wc -l) line(s) in $(echo "$files" | wc -l) file(s) point outside the" \
     "repository (../shared, SPEC.md, or a path of the author's machine): $(echo $files)"
echo "  Link to docs/contract.md (with a section anchor, e.g. docs/contract.md#7-the-lyapunov-verdict) instead."
exit 1
