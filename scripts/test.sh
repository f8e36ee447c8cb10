#!/usr/bin/env bash
# The test command of the README: installs the Debian packages, configures and builds the
# `release` preset into build/release/, then runs every test (CTest labels unit and validation).
# Re-running reuses build/release/ and rebuilds only what changed. The exit code is CTest's, and
# CTest's summary is the last thing printed. Afterwards docs/validation.md is rendered from the
# figures the validation tests wrote (scripts/render_validation.py).
#
# usage: bash scripts/test.sh [extra ctest arguments, e.g. -L unit or -R DamBreak]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/install-deps.sh
cmake --preset release
cmake --build --preset release -j"$(nproc)"
# Two tests at a time: the validation cases are the long ones, and each runs OpenMP threads.
# Tests whose name ends in KnownFailure hold a claim that the model does not meet yet (the README's
# validation table lists them with the measured values); they are left out here and run with
# `ctest --test-dir build/release -R KnownFailure`.
status=0
ctest --preset release --output-on-failure -j2 -E 'KnownFailure$' "$@" || status=$?
# docs/validation.md from the figures the validation tests wrote (tests/validation/validation_table.h);
# quietly, so that CTest's summary stays the last thing printed.
if compgen -G "build/release/validation/*.jsonl" >/dev/null; then
  /usr/bin/python3 scripts/render_validation.py >build/release/render_validation.log 2>&1 ||
    echo "test.sh: docs/validation.md not rendered: see build/release/render_validation.log" >&2
fi
exit "$status"
