#!/usr/bin/env bash
# The test groups under clang's AddressSanitizer and UndefinedBehaviorSanitizer (with
# float-cast-overflow), -O1, in build-asan (docs/fuzzing.md). Usage: scripts/sanitize_tests.sh [TEST...]
# TEST: a ctest name (a test group such as excitation or scene; corpus: the malformed-input corpus
# through a sanitized furniture_quake; command_line: its exit codes, signals and resume), or "all"
# (every test); default: excitation io restraints, the input-facing groups and the restraints' laws (10 s
# to build), those that fit CI's budget (scene and corpus take about 35 min to build here: docs/fuzzing.md). FFEM_SAN_OPT (default -O1) sets the
# optimisation level; another level builds in its own folder (build-asan-O2 for -O2), for the long
# groups (contact_dynamics: stopped after 38 min at -O1 without an end, 99 min at -O2).
set -euo pipefail
cd "$(dirname "$0")/.."
tests="${*:-excitation io restraints}"
pkgs="cmake make clang libclang-rt-14-dev libeigen3-dev zlib1g-dev libcgal-dev libboost-dev catch2 nlohmann-json3-dev libcli11-dev"
bash scripts/install_packages.sh $pkgs
san="-fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all"
opt="${FFEM_SAN_OPT:--O1}"
case "$opt" in -O1) dir=build-asan ;; -O0|-O2|-O3|-Og) dir="build-asan-${opt#-}" ;;
  *) echo "FFEM_SAN_OPT: '$opt' is not one of -O0 -O1 -O2 -O3 -Og" >&2; exit 2 ;; esac
start=$(date +%s)
cmake -S . -B "$dir" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DCGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE=TRUE \
      -DCMAKE_CXX_FLAGS="$opt -fno-omit-frame-pointer $san" -DCMAKE_EXE_LINKER_FLAGS="$san" \
      -DFFEM_BUILD_BENCH=OFF -DFFEM_BUILD_FUZZ=OFF >/dev/null
targets=""
regex=""
for t in $tests; do
  case "$t" in
    all) targets="all"; regex="" ; break ;;
    # The main program's own tests: the corpus, and its command line (exit codes, signals, resume).
    corpus) targets="$targets furniture_quake" ;;
    command_line) targets="$targets furniture_quake"; regex="$regex|^command_line_resume\$" ;;
    *) targets="$targets test_$t" ;;
  esac
  regex="$regex|^$t\$"
done
for t in $targets; do cmake --build "$dir" -j "${FFEM_SAN_JOBS:-2}" --target "$t"; done
built=$(date +%s)
echo "sanitized build ($opt, $dir): $((built - start)) s ($targets)"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
status=0
ctest --test-dir "$dir" --output-on-failure -j 2 ${regex:+-R "${regex#|}"} || status=$?
echo "sanitized tests: $(( $(date +%s) - built )) s, build $((built - start)) s"
exit $status
