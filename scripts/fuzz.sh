#!/usr/bin/env bash
# Runs the libFuzzer harnesses of tests/fuzz (docs/fuzzing.md). Usage: scripts/fuzz.sh [SECONDS] [HARNESS...]
# SECONDS per harness (default 60), two harnesses at a time; HARNESS: fuzz_record_at2 fuzz_record_knet
# fuzz_record_jma fuzz_record_columns fuzz_mesh fuzz_scene (default: all). Builds them with clang in
# build-fuzz, seeds each one's corpus from tests/corpus/cases (copied into build-fuzz/seeds), keeps
# what they find new in build-fuzz/corpus, and exits non-zero on any finding (crash, sanitizer report,
# uncaught exception, time-out, out of memory), printing the file that reproduces it:
#   build-fuzz/tests/fuzz/<harness> <file>
set -euo pipefail
cd "$(dirname "$0")/.."
secs="${1:-60}"
[ $# -gt 0 ] && shift
all="fuzz_record_at2 fuzz_record_knet fuzz_record_jma fuzz_record_columns fuzz_mesh fuzz_scene"
harnesses="${*:-$all}"

pkgs="cmake make clang libclang-rt-14-dev libeigen3-dev zlib1g-dev libcgal-dev libboost-dev nlohmann-json3-dev"
bash scripts/install_packages.sh $pkgs

B="$PWD/build-fuzz"
start=$(date +%s)
# Debug: assertions (Eigen's included) stay on; the harnesses add -O1 -g and the sanitizers.
cmake -S . -B $B -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DCGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE=TRUE -DFFEM_BUILD_FUZZ=ON \
      -DFFEM_BUILD_TESTS=OFF -DFFEM_BUILD_EXAMPLES=OFF -DFFEM_BUILD_BENCH=OFF >/dev/null
# build-fuzz holds the harnesses alone: build them all (one make, two jobs), whichever run.
# Only the harnesses asked for (and the libraries they link): `all` would also build the compiled scene
# and study libraries, which no harness needs.
targets=""
for h in $harnesses; do targets="$targets --target $h"; done
cmake --build $B -j 2 $targets
echo "fuzz: harnesses built in $(( $(date +%s) - start )) s"

# Seeds: the corpus files of each harness's format (named <class>_<file>: names repeat across classes).
# The mesh harness reads its format from the first byte (0 OFF, 1 OBJ, 2 STL).
C=tests/corpus/cases
seed() {  # seed <harness> <extension> [prefix byte]
  local dir=$B/seeds/$1 f
  mkdir -p "$dir"
  for f in $C/*/*."$2" tests/fuzz/seeds/*."$2"; do
    [ -f "$f" ] || continue
    local name="$dir/$(basename "$(dirname "$f")")_$(basename "$f")"
    if [ -n "${3:-}" ]; then { printf "\\$3"; cat "$f"; } > "$name"; else cp "$f" "$name"; fi
  done
}
rm -rf $B/seeds $B/logs
mkdir -p $B/logs $B/findings
seed fuzz_record_at2 AT2
seed fuzz_record_knet NS
seed fuzz_record_jma csv
seed fuzz_record_columns txt
seed fuzz_mesh off 000
seed fuzz_mesh obj 001
seed fuzz_mesh stl 002
seed fuzz_scene json

run() {  # run <harness>: its log in build-fuzz/logs/<harness>.log
  local h=$1
  mkdir -p $B/corpus/$h
  local dict=tests/fuzz/fuzz_scene.dict
  case $h in fuzz_record_*) dict=tests/fuzz/fuzz_record.dict ;; fuzz_mesh) dict="" ;; esac
  # -max_len: the corpus has 100 kB scenes (deep nesting); mutating inputs that long is slow.
  set +e
  $B/tests/fuzz/$h -max_total_time="$secs" -rss_limit_mb=2048 -timeout=10 -max_len=32768 -print_final_stats=1 \
      ${dict:+-dict=$dict} -artifact_prefix="$B/findings/$h-" "$B/corpus/$h" "$B/seeds/$h" > $B/logs/$h.log 2>&1
  echo $? > $B/logs/$h.rc
}
echo "fuzz: $secs s per harness, two at a time: $harnesses"
for h in $harnesses; do
  # At most two at once (the machine has two cores).
  while [ "$(jobs -rp | wc -l)" -ge 2 ]; do wait -n || true; done
  run "$h" &
done
wait

found=0
printf '%-22s %12s %10s %8s  %s\n' harness executions exec/s corpus result
for h in $harnesses; do
  log=$B/logs/$h.log
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  units=$(ls $B/corpus/$h | wc -l)
  rc=$(cat $B/logs/$h.rc)
  if [ "$rc" = 0 ]; then
    result="no finding"
  else
    found=1
    artifact=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | tail -1)
    result="FINDING (exit $rc): ${artifact} log $log"
  fi
  printf '%-22s %12s %10s %8s  %s\n' "$h" "${execs:-?}" "${rate:-?}" "$units" "$result"
done
if [ $found -ne 0 ]; then
  echo "fuzz: findings; reproduce one with build-fuzz/tests/fuzz/<harness> <file>. Log excerpts:"
  for h in $harnesses; do
    [ "$(cat $B/logs/$h.rc)" = 0 ] || { echo "--- $h"; grep -E "FFEM FUZZ FINDING|ERROR: |runtime error|terminate called|what\(\)|SUMMARY|Test unit written" $B/logs/$h.log | head -20; }
  done
  exit 1
fi
echo "fuzz: no findings"
