#!/usr/bin/env bash
# Renders a graph's frame range on a Slurm cluster: one array job whose tasks each render one
# chunk of frames with `aquarelle render --resume` (a requeued or re-run task redoes only the
# frames that are missing), then a final job, run after every task has ended however it ended,
# that checks each frame is present and readable and prints what is missing. Slurm does the
# distribution, retries and accounting; this script only cuts the range and submits.
#
#   scripts/slurm-render.sh GRAPH OUT --frames A-B --chunk N [sbatch options] [-- render options]
#
#   GRAPH    the graph file, on a filesystem every node sees
#   OUT      the output pattern with #### for the frame number, on a shared filesystem
#            (e.g. /shared/shots/sh010/####.exr); its folder is created
#   --frames A-B   the range; --chunk N   frames per array task
#   sbatch options go to both jobs (e.g. --partition=gpu --time=01:00:00 --array throttling
#            with --array-limit=K, written here as %K by Slurm's own syntax)
#   after `--`: options for `aquarelle render` (--size, --quality, --set ...)
#
# Environment: AQUARELLE (the executable; default: `aquarelle` on PATH, else this checkout's
# build/app/aquarelle), AQ_SLURM_LOGS (the log folder; default OUT's folder/slurm-logs).
# Prints the two job ids; per-task logs are render-<job>_<task>.log, the check's check-<job>.log.
set -euo pipefail

usage() {
  sed -n '2,/^set -euo/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//' >&2
  exit 1
}

[ $# -ge 2 ] || usage
graph="$1"
output="$2"
shift 2
frames="" chunk="" array_limit=""
sbatch_options=()
render_options=()
while [ $# -gt 0 ]; do
  case "$1" in
    --frames) frames="${2:?--frames needs A-B}"; shift 2 ;;
    --frames=*) frames="${1#--frames=}"; shift ;;
    --chunk) chunk="${2:?--chunk needs a number}"; shift 2 ;;
    --chunk=*) chunk="${1#--chunk=}"; shift ;;
    --array-limit=*) array_limit="%${1#--array-limit=}"; shift ;;
    --) shift; render_options=("$@"); break ;;
    -h|--help) usage ;;
    *) sbatch_options+=("$1"); shift ;;
  esac
done

fail() {
  echo "slurm-render: $*" >&2
  exit 1
}
# Values from the command line reach messages and the job scripts only quoted (%q: a newline
# in a file name cannot start a line of its own) and numbers only as decimal: bash arithmetic
# reads 0240 as octal (160), so every number is rebuilt with 10# from at most 7 digits.
quoted() { printf '%q' "$1"; }
decimal() { # SIGN DIGITS -> the decimal number
  local value=$((10#$2))
  [ "$1" = "-" ] && value=$((-value))
  echo "$value"
}
[[ "$frames" =~ ^(-?)([0-9]{1,7})-(-?)([0-9]{1,7})$ ]] ||
  fail "--frames $(quoted "$frames"): A-B is required, frame numbers of at most 7 digits, e.g. --frames 1-48"
first="$(decimal "${BASH_REMATCH[1]}" "${BASH_REMATCH[2]}")"
last="$(decimal "${BASH_REMATCH[3]}" "${BASH_REMATCH[4]}")"
[ "$first" -le "$last" ] || fail "--frames $(quoted "$frames"): the first frame is after the last"
[[ "$chunk" =~ ^[0-9]{1,7}$ ]] && chunk=$((10#$chunk)) && [ "$chunk" -ge 1 ] ||
  fail "--chunk N (frames per task, 1..9999999) is required"
if [ -n "$array_limit" ]; then
  [[ "$array_limit" =~ ^%([0-9]{1,7})$ ]] && array_limit="%$((10#${BASH_REMATCH[1]}))" ||
    fail "--array-limit=K: K must be a whole number"
fi
[[ "$output" == *"#"* ]] || fail "OUT $(quoted "$output") needs #### for the frame number, e.g. out/####.exr"
[ -f "$graph" ] || fail "graph file $(quoted "$graph") does not exist or is not a regular file"
command -v sbatch >/dev/null || fail "sbatch not found: run this on a Slurm login node (apt-get install slurm-client)"

# Tasks run on other machines: every path they see is absolute.
here="$(cd "$(dirname "$0")/.." && pwd)"
aquarelle="${AQUARELLE:-}"
if [ -z "$aquarelle" ]; then
  aquarelle="$(command -v aquarelle || true)"
  [ -n "$aquarelle" ] || aquarelle="$here/build/app/aquarelle"
fi
[ -x "$aquarelle" ] || fail "no aquarelle executable at $(quoted "$aquarelle") (build it, or set AQUARELLE)"
# Made absolute by prefixing the working folder, not through $(dirname/basename): command
# substitution drops a name's trailing newlines and would name another file.
[[ "$aquarelle" == /* ]] || aquarelle="$PWD/$aquarelle"
[[ "$graph" == /* ]] || graph="$PWD/$graph"
[[ "$output" == /* ]] || output="$PWD/$output"
out_dir="${output%/*}"
out_dir="${out_dir:-/}"
mkdir -p -- "$out_dir"
logs="${AQ_SLURM_LOGS:-$out_dir/slurm-logs}"
[[ "$logs" == /* ]] || logs="$PWD/$logs"
mkdir -p -- "$logs"

tasks=$(((last - first + chunk) / chunk))
quoted_render_options=""
for option in "${render_options[@]}"; do quoted_render_options+=" $(quoted "$option")"; done

# The job scripts are written beside the logs, so what ran can be read and re-submitted.
stamp="$(date +%Y%m%d-%H%M%S)-$$"
render_script="$logs/render-$stamp.sbatch"
check_script="$logs/check-$stamp.sbatch"
cat >"$render_script" <<EOF
#!/usr/bin/env bash
# One chunk of frames $first-$last of $(quoted "$graph") ($chunk per task), from SLURM_ARRAY_TASK_ID.
set -euo pipefail
task=\${SLURM_ARRAY_TASK_ID:?run this as a Slurm array task}
chunk_first=\$(($first + task * $chunk))
chunk_last=\$((chunk_first + $chunk - 1))
[ "\$chunk_last" -le $last ] || chunk_last=$last
echo "slurm-render: task \$task on \$(hostname): frames \$chunk_first-\$chunk_last"
exec $(printf '%q' "$aquarelle") render $(printf '%q' "$graph") -o $(printf '%q' "$output") \\
  --frames "\$chunk_first-\$chunk_last" --resume -q$quoted_render_options
EOF
cat >"$check_script" <<EOF
#!/usr/bin/env bash
# Every frame of $first-$last present and readable (all its pixels decode); lists what is not.
set -uo pipefail
pattern=$(printf '%q' "$output")
hashes="\${pattern//[^#]/}"
missing=()
for ((frame = $first; frame <= $last; ++frame)); do
  number=\$(printf "%0\${#hashes}d" "\$frame")
  file="\${pattern/"\$hashes"/\$number}"
  if [ ! -s "\$file" ]; then
    missing+=("\$frame (no file \$file)")
  elif ! iinfo --stats "\$file" >/dev/null 2>&1; then
    missing+=("\$frame (unreadable \$file)")
  fi
done
total=$((last - first + 1))
if [ \${#missing[@]} -eq 0 ]; then
  echo "slurm-render: all \$total frames of $first-$last present and readable in $(printf '%q' "$out_dir")"
  exit 0
fi
echo "slurm-render: \${#missing[@]} of \$total frames missing or unreadable:"
printf '  %s\n' "\${missing[@]}"
echo "re-submit the same command: tasks render only what is missing (--resume)"
exit 1
EOF
chmod +x "$render_script" "$check_script"

render_job=$(sbatch --parsable --job-name=aq-render --array="0-$((tasks - 1))$array_limit" \
  --output="$logs/render-%A_%a.log" "${sbatch_options[@]}" "$render_script")
render_job="${render_job%%;*}"
check_job=$(sbatch --parsable --job-name=aq-check --dependency="afterany:$render_job" \
  --kill-on-invalid-dep=no --output="$logs/check-%j.log" "${sbatch_options[@]}" "$check_script")
check_job="${check_job%%;*}"

echo "slurm-render: frames $first-$last of $(quoted "$graph") in $tasks task(s) of $chunk"
echo "  render array job $render_job  (logs: $(quoted "$logs")/render-${render_job}_<task>.log)"
echo "  check job        $check_job  (log:  $(quoted "$logs")/check-$check_job.log)"
echo "  follow with: squeue -j $render_job,$check_job"
echo "$render_job $check_job" >"$logs/last-submission"
