#!/usr/bin/env bash
# Runs two furniture_quake binaries on the same scenes and compares every output file byte for byte
# (all but run.json and summary.json, which hold wall times): the gate for a change that must not
# change a result (issue 48, "the same results"). Exit 0 when every file is identical, 1 otherwise.
#
#   scripts/compare_outputs.sh BASE_BINARY NEW_BINARY [--full]
#
# Scenes: the default job (1 s; --full: its 10 s), examples/scenes/configuration3_rigid.json (2 s), and
# examples/scenes/single_cabinet.json under each built-in contact law (1 s, direct solver; also CG under the
# paper's two laws: binaries before issue 48's law kernel refuse CG with the others). Results in ${FFEM_COMPARE_OUT:-/tmp/ffem_compare}/{base,new}/<case>.
set -euo pipefail
if [[ $# -lt 2 ]]; then
  sed -n 2,11p "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
base=$(realpath "$1")
new=$(realpath "$2")
full=${3:-}
here=$(cd "$(dirname "$0")/.." && pwd)
out=${FFEM_COMPARE_OUT:-/tmp/ffem_compare}
rm -rf "$out"
mkdir -p "$out/scenes"

# case name, then the binary's arguments after the binary and before --out
cases=()
add() { cases+=("$*"); }
if [[ "$full" == --full ]]; then add default; else add default --duration 1; fi
add configuration3_rigid "$here/examples/scenes/configuration3_rigid.json" --duration 2
for law in paper paper_anisotropic stiff spring_dashpot hunt_crossley stick_slip; do
  for solver in direct cg; do
    [[ $solver == cg && $law != paper && $law != paper_anisotropic ]] && continue
    scene="$out/scenes/single_cabinet_${law}_${solver}.json"
    python3 - "$here/examples/scenes/single_cabinet.json" "$scene" "$law" "$solver" <<'EOF'
import json, sys
src, dst, law, solver = sys.argv[1:]
s = json.load(open(src))
c = s.setdefault("contact", {})
c["law"] = law
if law not in ("paper", "paper_anisotropic"):
    c["implicit"] = "all"  # the explicit contact of the paper's laws diverges with the stiffer laws at dt 1 ms
if law == "stick_slip":
    c.pop("stick_length", None)  # its own tangential spring k_t
s["solver"] = solver
json.dump(s, open(dst, "w"), indent=1)
EOF
    add "single_cabinet_${law}_${solver}" "$scene" --duration 1
  done
done

status=0
for c in "${cases[@]}"; do
  read -r -a words <<<"$c"
  name=${words[0]}
  args=("${words[@]:1}")
  for side in base new; do
    bin=$base
    [[ $side == new ]] && bin=$new
    rc=0
    "$bin" "${args[@]}" --out "$out/$side/$name" --quiet >"$out/$side.$name.log" 2>&1 || rc=$?
    echo "$rc" >"$out/$side.$name.rc"
  done
  if [[ ! -d "$out/base/$name" ]]; then
    echo "FAILED $name: no results (exit code $(cat "$out/base.$name.rc"); $out/base.$name.log)"
    status=1
    continue
  fi
  if ! cmp -s "$out/base.$name.rc" "$out/new.$name.rc"; then
    echo "DIFFERS $name: exit codes $(cat "$out/base.$name.rc") and $(cat "$out/new.$name.rc")"
    status=1
    continue
  fi
  files=0
  while IFS= read -r -d '' f; do
    rel=${f#"$out/base/$name/"}
    case $(basename "$rel") in run.json | summary.json | .furniture_fem.lock) continue ;; esac
    files=$((files + 1))
    if ! cmp -s "$f" "$out/new/$name/$rel"; then
      echo "DIFFERS $name/$rel"
      status=1
    fi
  done < <(find "$out/base/$name" -type f -print0 | sort -z)
  # The folder's lock file (.furniture_fem.lock, one writer per folder) is not a result.
  extra=$(comm -13 <(cd "$out/base/$name" && find . -type f ! -name .furniture_fem.lock | sort) \
                   <(cd "$out/new/$name" && find . -type f ! -name .furniture_fem.lock | sort))
  if [[ -n "$extra" ]]; then
    echo "DIFFERS $name: only in the new run: $extra"
    status=1
  fi
  echo "compared $name: $files files, exit code $(cat "$out/base.$name.rc")"
done
[[ $status == 0 ]] && echo "identical: every file of every case" || echo "some files differ"
exit $status
