#!/usr/bin/env bash
# Runs the paper's study (section 5 of the reference paper) with
# furniture_quake and writes paper/results/<case>/ plus the comparison figures in paper/results/.
#
#   bash paper/run_paper.sh [--configs 1,2,3] [--cases kobe50_1d,kobe100_1d,kobe100_3d,haga100_3d]
#                           [--records DIR] [--haga EW NS UD] [--haga-window START END]
#                           [--build DIR] [--duration S] [--skip-existing] [--no-build] [--dry-run]
#                           [--iterate] [--refresh-every S]
#
# Cases: (i) kobe50_1d, (ii) kobe100_1d, (iii) kobe100_3d: the PEER-processed JMA-Kobe records
# (RSN1106; NS along X, EW along Y, UD along Z) from --records (default $FFEM_RECORDS, else
# ../shared/ground_motions next to the repository), record time 4-16 s as configuration(k) sets it. When the records are absent
# these cases are skipped with a message. (iv) haga100_3d runs only when --haga gives the three
# K-NET/KiK-net ASCII files of the KiK-net Haga record (TCGH16, 2011-03-11 14:46; EW first: it goes
# along X as in the paper, then NS along Y, UD along Z); the window is 4.5 s before to 7.5 s after
# the EW peak unless --haga-window gives it (s of record time).
#
# --iterate runs the sensitivity variant: Newton iterations to equilibrium in every step instead of
# the paper's carry-over of the unbalanced force (cases named <case>_iterate).
# --refresh-every S: seconds between refactorisations (make_scenes' default 0.02, what results/ was
# run with; the toolkit's default is 0.1). The results go to the same folders.
#
# Environment: FURNITURE_QUAKE=<path> uses an existing furniture_quake instead of building one;
# NICE (default 10) is the niceness of the runs. Runs are sequential.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(dirname "$here")
records="${FFEM_RECORDS:-$repo/../shared/ground_motions}"
build="$repo/build-paper"
configs="1,2,3"
cases="kobe50_1d,kobe100_1d,kobe100_3d,haga100_3d"
haga=()
haga_window=()
duration=()
skip_existing=0
dry_run=0
no_build=0
suffix=""
refresh_every=()

while [[ $# -gt 0 ]]; do
  case "$1" in
    --configs) configs="$2"; shift 2 ;;
    --cases) cases="$2"; shift 2 ;;
    --records) records="$2"; shift 2 ;;
    --haga) haga=("$2" "$3" "$4"); shift 4 ;;
    --haga-window) haga_window=(--haga-window "$2" "$3"); shift 3 ;;
    --build) build="$2"; shift 2 ;;
    --duration) duration=(--duration "$2"); shift 2 ;;
    --skip-existing) skip_existing=1; shift ;;
    --dry-run) dry_run=1; shift ;;
    --no-build) no_build=1; shift ;;
    --iterate) suffix="_iterate"; shift ;;
    --refresh-every) refresh_every=(--refresh-every "$2"); shift 2 ;;
    -h|--help) sed -n '2,25p' "$0"; exit 0 ;;
    *) echo "run_paper.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done

# Tools: make_scenes and paper_figures always; furniture_quake unless FURNITURE_QUAKE is given.
targets=(make_scenes paper_figures)
if [[ -z "${FURNITURE_QUAKE:-}" ]]; then
  targets+=(furniture_quake)
  FURNITURE_QUAKE="$build/furniture_quake"
fi
if [[ $no_build -eq 0 ]]; then
  echo "== building ${targets[*]} in $build"
  mkdir -p "$build"
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release > "$build/configure.log" 2>&1 ||
    { cat "$build/configure.log"; exit 1; }
  cmake --build "$build" --target "${targets[@]}" -j2
fi

# Scene files.
scene_args=(--scenes "$here/scenes" --results results --configs "$configs")
[[ -n "$suffix" ]] && scene_args+=(--iterate)
scene_args+=("${refresh_every[@]}")
kobe_files=(jma_kobe_1995_NS_PEER_RSN1106_KJM000.AT2 jma_kobe_1995_EW_PEER_RSN1106_KJM090.AT2
            jma_kobe_1995_UD_PEER_RSN1106_KJM-UP.AT2)
have_kobe=1
for f in "${kobe_files[@]}"; do [[ -f "$records/$f" ]] || have_kobe=0; done
if [[ $have_kobe -eq 1 ]]; then
  scene_args+=(--records "$records")
else
  echo "== JMA-Kobe records not found in $records (need ${kobe_files[*]}):"
  echo "   skipping cases (i)-(iii). Give --records DIR (or FFEM_RECORDS=DIR) to run them; the PEER NGA-West2"
  echo "   database has them (RSN1106, files RSN1106_KOBE_KJM000/KJM090/KJM-UP.AT2, saved under the names above):"
  echo "   docs/excitation/ground_motions.md, \"Getting the records\"."
  scene_args+=(--no-kobe)
fi
if [[ ${#haga[@]} -eq 3 ]]; then
  for f in "${haga[@]}"; do [[ -f "$f" ]] || { echo "run_paper.sh: KiK-net file not found: $f" >&2; exit 2; }; done
  scene_args+=(--haga "$(realpath "${haga[0]}")" "$(realpath "${haga[1]}")" "$(realpath "${haga[2]}")" "${haga_window[@]}")
else
  echo "== case (iv) KiK-net Haga: no record given (--haga EW NS UD); skipped. The record is not"
  echo "   redistributable; obtain TCGH16 2011-03-11 14:46 from https://www.kyoshin.bosai.go.jp/"
fi
if [[ $have_kobe -eq 0 && ${#haga[@]} -ne 3 ]]; then
  echo "== nothing to run"
  exit 0
fi
"$build/make_scenes" "${scene_args[@]}" > /dev/null

# Runs, sequentially, from paper/ (outputs.folder is results/<case>, relative to it).
cd "$here"
mkdir -p results
IFS=',' read -r -a config_list <<< "$configs"
IFS=',' read -r -a case_list <<< "$cases"
for k in "${config_list[@]}"; do
  for c in "${case_list[@]}"; do
    name="config${k}_${c}${suffix}"
    scene="scenes/$name.json"
    [[ -f "$scene" ]] || continue
    if [[ $skip_existing -eq 1 && -f "results/$name/summary.json" ]] &&
       grep -q '"status": "completed"' "results/$name/summary.json"; then
      echo "== $name: completed earlier, skipped"
      continue
    fi
    echo "== $name ($(date '+%H:%M:%S'))"
    [[ $dry_run -eq 1 ]] && continue
    mkdir -p "results/$name"
    # Wall and CPU time of the run (the summary has the wall time only; on a shared machine the CPU
    # time is the fairer speed figure).
    set +e
    TIMEFORMAT='time: wall %R s, user %U s, sys %S s'
    # --overwrite: the folder already holds this script's logs (not the program's files, which it keeps).
    { time nice -n "${NICE:-10}" "$FURNITURE_QUAKE" "$scene" --quiet --overwrite "${duration[@]}" \
        > "results/$name/run.log" 2> "results/$name/stderr.log"; } 2> "results/$name/time.log"
    rc=$?
    set -e
    cat "results/$name/run.log" "results/$name/time.log"
    [[ $rc -eq 0 ]] || echo "   furniture_quake exited with $rc (see results/$name/stderr.log)"
  done
done

[[ $dry_run -eq 1 ]] && exit 0
echo "== figures and event times"
"$build/paper_figures" --results results | tee results/cases.md
