#!/usr/bin/env bash
# The compile cost of a whole build, unit by unit (docs/performance.md section 6):
#   scripts/compile_times.sh [BUILD_DIR] [extra cmake arguments ...]
# Configures BUILD_DIR (default build-times; emptied first) as CI builds (Release, no benchmarks), builds
# every target with two jobs, each compile run under /usr/bin/time through CMAKE_CXX_COMPILER_LAUNCHER,
# and prints the units by CPU (user + system s) with their peak (the compiler's largest resident set),
# then the totals. The raw log is BUILD_DIR/compile_times.log: wall, user, sys s, peak KB, object.
set -euo pipefail
cd "$(dirname "$0")/.."
B="${1:-build-times}"
[ $# -gt 0 ] && shift
command -v /usr/bin/time > /dev/null || { echo "compile_times: /usr/bin/time is missing (Debian package time)" >&2; exit 1; }
rm -rf "$B"
mkdir -p "$B"
B="$(cd "$B" && pwd)"
log="$B/compile_times.log"
launcher="$B/time_compile.sh"
cat > "$launcher" <<LAUNCHER
#!/usr/bin/env bash
out=""; prev=""
for a in "\$@"; do [ "\$prev" = "-o" ] && out="\$a"; prev="\$a"; done
exec /usr/bin/time -a -o "$log" -f "%e %U %S %M \$out" "\$@"
LAUNCHER
chmod +x "$launcher"
cmake -S . -B "$B" -DCMAKE_BUILD_TYPE=Release -DFFEM_BUILD_BENCH=OFF -DCMAKE_CXX_COMPILER_LAUNCHER="$launcher" "$@" > /dev/null
start=$(date +%s)
cmake --build "$B" -j 2 > "$B/build.log" 2>&1 || { echo "compile_times: the build failed, see $B/build.log" >&2; exit 1; }
wall=$(( $(date +%s) - start ))
sort -k2 -g -r "$log" | awk '{printf "%7.0f s %6.2f GB  %s\n", $2 + $3, $4 / 1e6, $5}'
awk -v wall="$wall" '{cpu += $2 + $3; if ($4 > 2e6) big++; if ($4 > peak) peak = $4}
     END {printf "%d units, %.0f s of CPU, %d above 2.0 GB, the largest %.2f GB; the build took %d s wall\n",
                 NR, cpu, big, peak / 1e6, wall}' "$log"
