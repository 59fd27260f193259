#!/usr/bin/env bash
# Runs every case of the cpfg oracle and checks that each one graftal passes (listed one by
# one in view_cases_passing.txt, view-file cases and language cases alike) still passes. The oracle pack lives beside the checkout
# (../shared/cpfg-oracle) or where GRAFTAL_CPFG_ORACLE points; without it the test is
# skipped (exit 77) with a note.
#   view_cases.sh GRAFTAL SOURCE_DIR
set -u
graftal=$1
source_dir=$2
oracle=${GRAFTAL_CPFG_ORACLE:-$source_dir/../shared/cpfg-oracle}
if [ ! -x "$oracle/check.sh" ]; then
    echo "note: no cpfg oracle pack at $oracle; skipped (set GRAFTAL_CPFG_ORACLE)"
    exit 77
fi

# Each check that passes: "NAME" for the string, "NAME (bbox)" for the bounding box.
expected=$(cat "$(dirname -- "${BASH_SOURCE[0]}")/view_cases_passing.txt")

result=$("$oracle/check.sh" "$graftal")
missing=0
while IFS= read -r check; do
    [ -z "$check" ] && continue
    if ! grep -qxF "PASS  $check" <<< "$result"; then
        echo "no longer passes: $check"
        grep -F " $check" <<< "$result" | head -n 1
        missing=$((missing + 1))
    fi
done <<< "$expected"
echo "$(grep -c '^PASS' <<< "$result") oracle checks pass; $missing listed ones do not"
[ $missing -eq 0 ]
