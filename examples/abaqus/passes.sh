#!/usr/bin/env bash
# Runs an Abaqus job that uses jointlin pass by pass until the contact amplitudes are
# consistent (docs/abaqus.md, "Using jointlin from Abaqus", step 6). From the job directory:
#
#   bash passes.sh INPUT.inp [ABAQUS OPTIONS...]     e.g.  bash passes.sh block.inp cpus=4 mp_mode=mpi
#
# Pass n is the job pass<n>: `$ABAQUS job=pass<n> input=INPUT user=$USER_FILE OPTIONS
# ask_delete=OFF interactive` (ABAQUS default `abaqus`, USER_FILE default `user.f`). After
# each job the action file (jointlin.cfg's action_file) says what comes next: RUN_PASS
# with the increments to re-run (increment k is the k-th frequency line of the full
# sweep, blank and `**` comment lines not counted; they become sweep.frq), RUN_FINAL
# (every frequency once more with converged amplitudes: that job's results are the
# answer), DONE or FAILED. The full sweep is kept in frequencies.frq while the passes
# run and sweep.frq is restored when they stop, however they stop.
#
# Exit status: 0 done (the last line names the job with the answer), 1 a job failed or
# the iteration did not converge (FAILED: the increments left), 2 the job directory is
# not ready (no sweep.frq; no jointlin.cfg with restart_file, action_file and
# kinc_numbering = sequential, which a job per pass needs; the files of an earlier run:
# delete them to start over; no Abaqus command).
set -euo pipefail

die() { echo "passes.sh: $1" >&2; exit "${2:-2}"; }

[ $# -ge 1 ] || die "usage: bash passes.sh INPUT.inp [ABAQUS OPTIONS...]"
input=$1; shift
abaqus=${ABAQUS:-abaqus}
user_file=${USER_FILE:-user.f}
config=${JOINTLIN_CONFIG:-jointlin.cfg}
[ -f "$input" ] || die "$input: no such input file"
[ -f sweep.frq ] || die "no sweep.frq in $(pwd): the steady-state step's frequencies (jointlin export writes it)"
[ -f "$config" ] || die "no $config: the UEXTERNALDB configuration (jointlin export writes it)"

# A key of the configuration as the shim reads it: `key = value`, keys in any case,
# comments from # or !, the value trimmed (the last one given).
setting() {
    awk -v want="$1" '
        function trim(s) { gsub(/^[ \t]+|[ \t\r]+$/, "", s); return s }
        { sub(/[#!].*/, ""); i = index($0, "="); if (!i) next
          if (tolower(trim(substr($0, 1, i - 1))) == want) value = trim(substr($0, i + 1)) }
        END { print value }' "$config"
}
action_file=$(setting action_file)
restart_file=$(setting restart_file)
numbering=$(setting kinc_numbering | tr '[:upper:]' '[:lower:]')
[ -n "$action_file" ] || die "$config sets no action_file: the passes cannot be driven without it"
[ -n "$restart_file" ] || die "$config sets no restart_file: every pass is a job of its own and needs it"
[ "$numbering" = sequential ] ||
    die "$config: kinc_numbering = sequential is needed (each pass is a new job numbering its increments 1..m)"
command -v "$abaqus" >/dev/null || die "$abaqus: no such command (ABAQUS names the Abaqus command)"
if [ -e frequencies.frq ]; then
    die "frequencies.frq exists: an earlier run stopped while its passes ran; restore sweep.frq from it and delete it and $restart_file* to start over"
fi
if compgen -G "$restart_file*" >/dev/null; then
    die "$restart_file exists: an earlier run's store; delete $restart_file* to start over"
fi

cp sweep.frq frequencies.frq
restore() { if [ -e frequencies.frq ]; then mv -f frequencies.frq sweep.frq; fi; }
trap restore EXIT
# The frequency lines of the full sweep: increment k of the first job is line k here.
mapfile -t lines < <(grep -v -e '^[[:space:]]*$' -e '^[[:space:]]*\*\*' frequencies.frq)

n=0
while :; do
    n=$((n + 1))
    job=pass$n
    rm -f "$action_file"
    echo "passes.sh: job $job ($(grep -c . sweep.frq) frequencies)" >&2
    if ! "$abaqus" "job=$job" "input=$input" "user=$user_file" "$@" ask_delete=OFF interactive; then
        die "job $job failed (its .log and .msg say why)" 1
    fi
    [ -f "$action_file" ] ||
        die "job $job wrote no $action_file: is jointlin linked into the job (abaqus_v6.env) and $config in the job directory?" 1
    action=$(sed -n 's/^action //p' "$action_file")
    increments=$(sed -n 's/^increments *//p' "$action_file")
    case $action in
        RUN_PASS)
            for k in $increments; do printf '%s\n' "${lines[k - 1]}"; done > sweep.frq ;;
        RUN_FINAL)
            cp frequencies.frq sweep.frq ;;
        DONE)
            echo "passes.sh: done after $n jobs; the answer is job $job" >&2
            echo "$job"
            exit 0 ;;
        FAILED)
            die "not converged after $n jobs: increments $increments (lines of sweep.frq) are out of tolerance (max_passes in $config)" 1 ;;
        *)
            die "$action_file: unexpected action '$action'" 1 ;;
    esac
done
