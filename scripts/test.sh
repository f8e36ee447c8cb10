#!/usr/bin/env bash
# The test command of the README: installs the Debian packages, configures and builds the
# `release` preset into build/release/, then runs every test (CTest labels unit and validation).
# Re-running reuses build/release/ and rebuilds only what changed. The exit code is CTest's, and
# CTest's summary is the last thing printed.
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
exec ctest --preset release --output-on-failure -j2 -E 'KnownFailure$' "$@"
