#!/usr/bin/env bash
# Do two batstudy binaries give the same results? Runs each bundled study (or the ones
# named) with both and compares the files bit for bit with scripts/compare_results.py
# (every dataset and attribute; only the attributes that describe the run may differ).
# Used to show that a change of structure changes no number.
#   bash scripts/same_results.sh OLD_BINARY NEW_BINARY [studies/x.yaml ...]
# Exit 0 when every study matches, 1 otherwise.
set -euo pipefail
cd "$(dirname "$0")/.."
old=$1 new=$2
shift 2
studies=("$@")
[ ${#studies[@]} -gt 0 ] || studies=(studies/*.yaml)
py=.venv/bin/python
[ -x "$py" ] || py=python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
for s in "${studies[@]}"; do
  name=$(basename "$s" .yaml)
  "$old" run "$s" -o "$work/$name.old.h5" --force --quiet || [ $? -eq 1 ]
  "$new" run "$s" -o "$work/$name.new.h5" --force --quiet || [ $? -eq 1 ]
  if "$py" scripts/compare_results.py "$work/$name.old.h5" "$work/$name.new.h5" >"$work/$name.log" 2>&1; then
    echo "same: $s"
  else
    echo "DIFFERENT: $s"; sed 's/^/  /' "$work/$name.log" | head -20
    status=1
  fi
done
exit $status
