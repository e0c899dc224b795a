#!/usr/bin/env bash
# A validation or cross-check campaign on a Slurm cluster (docs/cluster.md):
# one shard per task of a job array, then a merge job that depends on all.
#
#   cluster/validate-campaign.sh submit DIR SHARDS [--cpus K] [--hold] -- MISSION --world WORLD --trials N [validate options]
#   cluster/validate-campaign.sh submit DIR SHARDS [--cpus K] [--hold] -- crosscheck [crosscheck options]
#   cluster/validate-campaign.sh rerun DIR I[,J...]    # only those shards again, then a new merge
#   cluster/validate-campaign.sh status DIR            # each shard's progress, and the merge's outcome
#
# DIR (on a file system every node sees) gets the campaign's arguments, the
# parts (shard-I-of-N.part), the logs (logs/) and the result: result.json,
# result.txt and (validation) runs.csv, byte for byte what one unsharded
# `vipars validate ... --json --csv` with the same seed gives. A cross-check
# campaign (sharded by mission) also writes its own --out folder, as unsharded.
# The vipars binary: $VIPARS, else the one on PATH. Slurm's own SBATCH_*
# variables (SBATCH_PARTITION, SBATCH_TIMELIMIT, SBATCH_ACCOUNT, ...) apply
# to every job submitted here. Prints the job ids, one per line:
#   array <id>
#   merge <id>
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
die() { echo "validate-campaign: $*" >&2; exit 2; }
usage() { sed -n '5,8p' "$0" | sed 's/^# *//' >&2; exit 2; }

vipars_binary() {
  local v="${VIPARS:-$(command -v vipars || true)}"
  [ -n "$v" ] && [ -x "$v" ] || die "no vipars binary: set VIPARS=/path/to/vipars or put it on PATH"
  (cd "$(dirname "$v")" && echo "$(pwd)/$(basename "$v")")
}

# sbatch --parsable prints "id" or "id;cluster".
submit_job() { sbatch --parsable "$@" | cut -d';' -f1; }

submit_merge() {  # dir shards vipars dependency
  submit_job --dependency="afterany:$4" --output="$1/logs/merge-%j.out" \
    --export="ALL,VIPARS=$3" "$here/validate-merge.sbatch" "$1" "$2"
}

cmd="${1:-}"
[ -n "$cmd" ] || usage
shift
case "$cmd" in
  submit)
    [ $# -ge 2 ] || usage
    dir="$1"; shards="$2"; shift 2
    cpus=1
    hold=()
    while [ $# -gt 0 ] && [ "$1" != "--" ]; do
      case "$1" in
        --cpus) cpus="${2:?--cpus needs a number}"; shift 2 ;;
        --hold) hold=(--hold); shift ;;  # start no shard until `scontrol release`
        *) die "unknown option '$1' (campaign arguments go after --)" ;;
      esac
    done
    [ "${1:-}" = "--" ] || usage
    shift
    [ $# -gt 0 ] || die "no campaign arguments after --"
    [[ "$shards" =~ ^[1-9][0-9]*$ ]] || die "SHARDS: expected a whole number >= 1, got '$shards'"
    [[ "$cpus" =~ ^[1-9][0-9]*$ ]] || die "--cpus: expected a whole number >= 1, got '$cpus'"
    subcommand=validate
    if [ "$1" = crosscheck ] || [ "$1" = validate ]; then subcommand="$1"; shift; fi
    for a in "$@"; do
      case "$a" in --shard|--shard=*|--part|--part=*|--json|--csv|--csv=*|--jobs|--jobs=*)
        die "'$a' is set per shard by this script (merge writes the JSON and CSV)" ;; esac
    done
    vipars="$(vipars_binary)"
    mkdir -p "$dir/logs"
    dir="$(cd "$dir" && pwd)"
    if compgen -G "$dir/shard-*.part" >/dev/null; then
      die "$dir already holds parts of a campaign: use a new folder, or 'rerun' for missing shards"
    fi
    # The arguments, quoted for bash, so every task and a later rerun run the
    # same campaign (relative paths are taken from this folder).
    {
      echo "# written by validate-campaign.sh submit; sourced by each shard"
      echo "cd $(printf '%q' "$(pwd)")"
      declare -p cpus shards vipars subcommand | sed 's/^declare -- /declare -g /'
      campaign_args=("$@")
      declare -p campaign_args | sed 's/^declare -a /declare -ga /'
    } > "$dir/campaign.args"
    array="$(submit_job "${hold[@]}" --array="0-$((shards - 1))" --cpus-per-task="$cpus" \
      --output="$dir/logs/shard-%a-%A.out" --export="ALL,VIPARS=$vipars" \
      "$here/validate-shard.sbatch" "$dir" "$shards")"
    merge="$(submit_merge "$dir" "$shards" "$vipars" "$array")"
    echo "array $array"
    echo "merge $merge"
    ;;
  rerun)
    [ $# -eq 2 ] || usage
    dir="$(cd "$1" && pwd)"; list="$2"
    [ -f "$dir/campaign.args" ] || die "$dir/campaign.args not found: not a campaign folder"
    [[ "$list" =~ ^[0-9]+(,[0-9]+)*$ ]] || die "expected shard indices like 2 or 1,3; got '$list'"
    # shellcheck disable=SC1091
    (source "$dir/campaign.args" >/dev/null; echo "$shards $cpus $vipars") > "$dir/.rerun.$$"
    read -r shards cpus vipars < "$dir/.rerun.$$"
    rm -f "$dir/.rerun.$$"
    IFS=',' read -r -a indices <<< "$list"
    for i in "${indices[@]}"; do
      [ "$i" -lt "$shards" ] || die "shard $i: this campaign has shards 0..$((shards - 1))"
      rm -f "$dir/shard-$i-of-$shards.part"
    done
    array="$(submit_job --array="$list" --cpus-per-task="$cpus" \
      --output="$dir/logs/shard-%a-%A.out" --export="ALL,VIPARS=$vipars" \
      "$here/validate-shard.sbatch" "$dir" "$shards")"
    merge="$(submit_merge "$dir" "$shards" "$vipars" "$array")"
    echo "array $array"
    echo "merge $merge"
    ;;
  status)
    [ $# -eq 1 ] || usage
    dir="$(cd "$1" && pwd)"
    squeue --me -o '%.16i %.16j %.9T %.10M %k' || true
    ls "$dir"/shard-*.part 2>/dev/null | sed 's|.*/||' | tr '\n' ' '; echo
    last_merge="$(ls -t "$dir"/logs/merge-*.out 2>/dev/null | head -1 || true)"
    [ -n "$last_merge" ] && { echo "--- $last_merge"; cat "$last_merge"; }
    ;;
  *) usage ;;
esac
