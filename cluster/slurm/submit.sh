#!/usr/bin/env bash
# Submits a split render to Slurm: a job array that renders the parts, and a job that runs when
# every task of the array has succeeded (afterok) and merges them.
#
#   submit.sh SCENE --parts N -o OUT.png|OUT.exr [options] [-- render options…]
#       a still in N parts (tiles): render-parts.sbatch, then merge.sbatch
#   submit.sh SCENE --parts N --frames A..B -o DIR [--video OUT.mp4] [options] [-- animate options…]
#       frames A..B (B excluded; A..=B includes B) in N slices: render-frames.sbatch, then
#       assemble.sbatch (checks every frame, makes the video if ffmpeg is there)
#
# Options:
#   --work DIR       where the parts go (default OUT.parts); must be seen by every node
#   --nullpath BIN   the nullpath binary the jobs run (default: nullpath on PATH, else this
#                    checkout's target/release/nullpath)
#   --cpus C         CPUs (and render threads) per task (default 1)
#   --time T         time limit per task, Slurm syntax (default: the partition's)
#   --partition P    partition (default: the cluster's default)
#   --logs DIR       the jobs' output files (default WORK/logs or DIR/logs)
# Anything after `--` is passed to every `nullpath render`/`animate` (--width, --spp, --seed,
# --view, --time, --format …; not --threads, which is --cpus).
#
# Prints the two job ids as `render_job=ID` and `merge_job=ID` (one per line, for `eval`).
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)

usage() {
    sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2
    exit 64
}
fail() {
    echo "submit.sh: $*" >&2
    exit 1
}

(($# > 0)) || usage
scene="" parts="" out="" frames="" video="" work="" bin="" cpus=1 logs=""
sbatch_extra=()
while (($# > 0)); do
    case $1 in
    --parts) parts=${2:?--parts needs N} && shift ;;
    -o | --output) out=${2:?-o needs a path} && shift ;;
    --frames) frames=${2:?--frames needs A..B} && shift ;;
    --video) video=${2:?--video needs a path} && shift ;;
    --work) work=${2:?--work needs a directory} && shift ;;
    --nullpath) bin=${2:?--nullpath needs a path} && shift ;;
    --cpus) cpus=${2:?--cpus needs a number} && shift ;;
    --logs) logs=${2:?--logs needs a directory} && shift ;;
    --time) sbatch_extra+=("--time=${2:?--time needs a limit}") && shift ;;
    --partition) sbatch_extra+=("--partition=${2:?--partition needs a name}") && shift ;;
    --) shift && break ;;
    -h | --help) usage ;;
    -*) fail "unknown option $1 (render options go after --)" ;;
    *)
        [[ -z $scene ]] || fail "one scene only (got $scene and $1)"
        scene=$1
        ;;
    esac
    shift
done
options=("$@")

[[ -n $scene ]] || fail "no scene file"
[[ -f $scene ]] || fail "$scene: no such scene file"
[[ $parts =~ ^[1-9][0-9]*$ ]] || fail "--parts must be a whole number ≥ 1, got '${parts}'"
[[ -n $out ]] || fail "no output: -o OUT"
[[ $cpus =~ ^[1-9][0-9]*$ ]] || fail "--cpus must be a whole number ≥ 1, got '$cpus'"
command -v sbatch >/dev/null || fail "sbatch not found: is this a Slurm login node?"

if [[ -z $bin ]]; then
    bin=$(command -v nullpath || echo "$here/../../target/release/nullpath")
fi
[[ -x $bin ]] || fail "$bin: no nullpath binary (build it with cargo build --release, or give --nullpath)"
# Absolute paths: the jobs may start in another directory, on another node.
bin=$(realpath "$bin")
scene=$(realpath "$scene")
out=$(realpath -m "$out")

submit() {
    sbatch --parsable --export=ALL,NULLPATH="$bin" --cpus-per-task="$cpus" "${sbatch_extra[@]}" "$@" |
        cut -d';' -f1
}

if [[ -z $frames ]]; then
    [[ -z $video ]] || fail "--video is for animations (with --frames)"
    [[ $out == *.png || $out == *.exr ]] || fail "-o must end in .png or .exr, got $out"
    work=$(realpath -m "${work:-$out.parts}")
    logs=$(realpath -m "${logs:-$work/logs}")
    mkdir -p "$work" "$logs" "$(dirname "$out")"
    render_job=$(submit --array="1-$parts" --output="$logs/part_%a.log" \
        "$here/render-parts.sbatch" "$parts" "$work" "$scene" "${options[@]}")
    merge_job=$(submit --dependency="afterok:$render_job" --kill-on-invalid-dep=yes \
        --output="$logs/merge.log" "$here/merge.sbatch" "$parts" "$work" "$out")
else
    [[ $frames =~ ^([0-9]+)\.\.(=?)([0-9]+)$ ]] || fail "--frames must be A..B or A..=B, got '$frames'"
    first=$((10#${BASH_REMATCH[1]}))
    end=$((10#${BASH_REMATCH[3]}))
    [[ -z ${BASH_REMATCH[2]} ]] || end=$((end + 1))
    ((first < end)) || fail "--frames $frames holds no frames"
    ((parts <= end - first)) || fail "--parts $parts is more than the $((end - first)) frames"
    [[ -z $work ]] || fail "--work is for stills; the frames go to -o DIR"
    logs=$(realpath -m "${logs:-$out/logs}")
    mkdir -p "$out" "$logs"
    [[ -z $video ]] || video=$(realpath -m "$video")
    render_job=$(submit --array="1-$parts" --output="$logs/frames_%a.log" \
        "$here/render-frames.sbatch" "$parts" "$first" "$end" "$out" "$scene" "${options[@]}")
    merge_job=$(submit --dependency="afterok:$render_job" --kill-on-invalid-dep=yes \
        --output="$logs/assemble.log" "$here/assemble.sbatch" "$first" "$end" "$out" "$scene" \
        "${video:--}" "${options[@]}")
fi
echo "render_job=$render_job"
echo "merge_job=$merge_job"
