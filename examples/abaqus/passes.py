"""Runs an Abaqus job that uses jointlin pass by pass until the contact amplitudes are
consistent (docs/abaqus.md, "Using jointlin from Abaqus", step 6): the same driver as passes.sh,
for the Python that Abaqus ships (2.7 in older releases, 3 since 2024) and any other.
From the job directory:

    abaqus python passes.py INPUT.inp [ABAQUS OPTIONS...]    (or: python3 passes.py ...)

Pass n is the job pass<n>: `$ABAQUS job=pass<n> input=INPUT user=$USER_FILE OPTIONS
ask_delete=OFF interactive` (ABAQUS default `abaqus`, one command, USER_FILE default
`user.f`). After each job the action file (jointlin.cfg's action_file) says what comes
next: RUN_PASS with the increments to re-run (increment k is the k-th frequency line of
the full sweep, blank and `**` comment lines not counted; they become sweep.frq),
RUN_FINAL (every
frequency once more with converged amplitudes: that job's results are the answer), DONE
or FAILED. The full sweep is kept in frequencies.frq while the passes run and sweep.frq
is restored when they stop, however they stop (an error, Ctrl-C, SIGTERM or SIGHUP from
a batch system).

Exit status: 0 done (the last line on stdout names the job with the answer), 1 a job
failed or the iteration did not converge (FAILED: the increments left), 2 the job
directory is not ready (no sweep.frq; no jointlin.cfg with restart_file, action_file and
kinc_numbering = sequential, which a job per pass needs; the files of an earlier run:
delete them to start over; no Abaqus command), 128 + N on signal N (130 on Ctrl-C).
"""
from __future__ import print_function

import glob
import os
import shutil
import signal
import subprocess
import sys


class Stop(Exception):
    """Ends the driver with a message and an exit status."""

    def __init__(self, message, status):
        Exception.__init__(self, message)
        self.status = status


def setting(config, key):
    """The value of `key = value` in the configuration as the shim reads it: keys in any
    case, comments from # or !, the value trimmed (the last one given)."""
    value = None
    with open(config) as f:
        for line in f:
            line = line.split("#")[0].split("!")[0]
            if "=" not in line:
                continue
            k, v = line.split("=", 1)
            if k.strip().lower() == key:
                value = v.strip()
    return value or None


def read_action(path):
    """The action file: (action, [increments])."""
    action, increments = None, []
    with open(path) as f:
        for line in f:
            words = line.split()
            if words[:1] == ["action"] and len(words) > 1:
                action = words[1]
            elif words[:1] == ["increments"]:
                increments = [int(k) for k in words[1:]]
    return action, increments


def lines(path):
    """The frequency lines of a .frq file (blank and `**` comment lines left out)."""
    with open(path) as f:
        return [l for l in f.read().splitlines()
                if l.strip() and not l.lstrip().startswith("**")]


def check_ready(input_file, config):
    """The job directory's files; returns (action_file, restart_file)."""
    if not os.path.isfile(input_file):
        raise Stop("%s: no such input file" % input_file, 2)
    if not os.path.isfile("sweep.frq"):
        raise Stop("no sweep.frq in %s: the steady-state step's frequencies "
                   "(jointlin export writes it)" % os.getcwd(), 2)
    if not os.path.isfile(config):
        raise Stop("no %s: the UEXTERNALDB configuration (jointlin export writes it)"
                   % config, 2)
    action_file = setting(config, "action_file")
    restart_file = setting(config, "restart_file")
    if not action_file:
        raise Stop("%s sets no action_file: the passes cannot be driven without it"
                   % config, 2)
    if not restart_file:
        raise Stop("%s sets no restart_file: every pass is a job of its own and needs it"
                   % config, 2)
    if (setting(config, "kinc_numbering") or "").lower() != "sequential":
        raise Stop("%s: kinc_numbering = sequential is needed (each pass is a new job "
                   "numbering its increments 1..m)" % config, 2)
    if os.path.exists("frequencies.frq"):
        raise Stop("frequencies.frq exists: an earlier run stopped while its passes ran; "
                   "restore sweep.frq from it and delete it and %s* to start over"
                   % restart_file, 2)
    if glob.glob(restart_file + "*"):
        raise Stop("%s exists: an earlier run's store; delete %s* to start over"
                   % (restart_file, restart_file), 2)
    return action_file, restart_file


def passes(input_file, options):
    """Runs the jobs; returns the name of the job with the answer."""
    abaqus = os.environ.get("ABAQUS", "abaqus")
    user_file = os.environ.get("USER_FILE", "user.f")
    config = os.environ.get("JOINTLIN_CONFIG", "jointlin.cfg")
    action_file, _ = check_ready(input_file, config)
    shutil.copyfile("sweep.frq", "frequencies.frq")
    try:
        every = lines("frequencies.frq")
        n = 0
        while True:
            n += 1
            job = "pass%d" % n
            if os.path.exists(action_file):
                os.remove(action_file)
            print("passes.py: job %s (%d frequencies)" % (job, len(lines("sweep.frq"))),
                  file=sys.stderr)
            sys.stderr.flush()
            command = [abaqus, "job=" + job, "input=" + input_file,
                       "user=" + user_file] + options + ["ask_delete=OFF", "interactive"]
            try:
                status = subprocess.call(command)
            except OSError as e:
                raise Stop("%s: cannot run it (%s); ABAQUS names the Abaqus command"
                           % (abaqus, e), 2)
            if status != 0:
                raise Stop("job %s failed (its .log and .msg say why)" % job, 1)
            if not os.path.isfile(action_file):
                raise Stop("job %s wrote no %s: is jointlin linked into the job "
                           "(abaqus_v6.env) and %s in the job directory?"
                           % (job, action_file, config), 1)
            action, increments = read_action(action_file)
            if action == "RUN_PASS":
                with open("sweep.frq", "w") as f:
                    for k in increments:
                        f.write(every[k - 1] + "\n")
            elif action == "RUN_FINAL":
                shutil.copyfile("frequencies.frq", "sweep.frq")
            elif action == "DONE":
                print("passes.py: done after %d jobs; the answer is job %s" % (n, job),
                      file=sys.stderr)
                return job
            elif action == "FAILED":
                raise Stop("not converged after %d jobs: increments %s (lines of sweep.frq) "
                           "are out of tolerance (max_passes in %s)"
                           % (n, " ".join(str(k) for k in increments), config), 1)
            else:
                raise Stop("%s: unexpected action %r" % (action_file, action), 1)
    finally:
        if os.path.exists("frequencies.frq"):
            shutil.copyfile("frequencies.frq", "sweep.frq")
            os.remove("frequencies.frq")


def stopped_by(signum, frame):
    """A batch system's SIGTERM or a lost terminal's SIGHUP: leave as after an error."""
    raise Stop("stopped by signal %d" % signum, 128 + signum)


def main(argv):
    if len(argv) < 2:
        print("usage: python passes.py INPUT.inp [ABAQUS OPTIONS...]", file=sys.stderr)
        return 2
    for name in ("SIGTERM", "SIGHUP"):
        if hasattr(signal, name):
            signal.signal(getattr(signal, name), stopped_by)
    try:
        print(passes(argv[1], argv[2:]))
        return 0
    except Stop as e:
        print("passes.py: %s" % e, file=sys.stderr)
        return e.status
    except KeyboardInterrupt:
        print("passes.py: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main(sys.argv))
