#!/usr/bin/env python3
"""Runs `trackphys info` on every file of the hostile corpus (make_hostile_meshes.py) in a
child process of its own and checks, for each: exit status 1, an error naming the file, at
most 1 s of CPU time and at most 256 MB resident (both from the child's getrusage), and no
file left behind (the child runs in an empty folder, and the corpus folder is unchanged).

CPU time, not wall time: the machines that run the suite are shared, and a refusal that takes
0.01 s of CPU can wait a second for a core. A child still running after 20 s is killed and
reported as a hang.

Usage: hostile_meshes_test.py TRACKPHYS_COMMAND WORK_DIR
"""

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

MAX_CPU_SECONDS = 1.0
MAX_RESIDENT_MB = 256
HANG_SECONDS = 20


def run(command, mesh, folder):
    """Exit status, stderr, CPU seconds, peak resident MB of `command info mesh` run in folder."""
    err_path = folder.parent / "stderr.txt"
    with open(err_path, "wb") as err:
        child = subprocess.Popen([command, "info", str(mesh)], cwd=folder,
                                 stdout=subprocess.DEVNULL, stderr=err)
        deadline = time.monotonic() + HANG_SECONDS
        while True:
            pid, status, usage = os.wait4(child.pid, os.WNOHANG)
            if pid != 0:
                break
            if time.monotonic() > deadline:
                os.kill(child.pid, signal.SIGKILL)
                pid, status, usage = os.wait4(child.pid, 0)
                break
            time.sleep(0.005)
        child.returncode = os.waitstatus_to_exitcode(status)  # reaped here, not by Popen
    stderr = err_path.read_text(errors="replace")
    return (os.waitstatus_to_exitcode(status), stderr, usage.ru_utime + usage.ru_stime,
            usage.ru_maxrss / 1024)


def main():
    command, work = sys.argv[1], Path(sys.argv[2])
    shutil.rmtree(work, ignore_errors=True)
    corpus, folder = work / "corpus", work / "cwd"
    folder.mkdir(parents=True)
    generator = Path(__file__).with_name("make_hostile_meshes.py")
    subprocess.run([sys.executable, str(generator), str(corpus)], check=True)
    before = sorted(p.name for p in corpus.iterdir())

    failures = []
    worst_cpu, worst_mb = 0.0, 0.0
    for name in before:
        mesh = corpus / name
        code, stderr, cpu, mb = run(command, mesh, folder)
        worst_cpu, worst_mb = max(worst_cpu, cpu), max(worst_mb, mb)
        problems = []
        if code != 1:
            problems.append(f"exit status {code}, not 1")
        if f"mesh file '{mesh}'" not in stderr:
            problems.append("the message does not name the file")
        if cpu > MAX_CPU_SECONDS:
            problems.append(f"{cpu:.2f} s of CPU")
        if mb > MAX_RESIDENT_MB:
            problems.append(f"{mb:.0f} MB resident")
        if any(folder.iterdir()):
            problems.append("left files: " + ", ".join(p.name for p in folder.iterdir()))
        if problems:
            failures.append(f"{name}: {'; '.join(problems)}\n  {stderr.strip()[:300]}")
        print(f"{name:40} exit {code}  {cpu:5.2f} s CPU  {mb:6.1f} MB  {stderr.strip()[:110]}")

    after = sorted(p.name for p in corpus.iterdir())
    if after != before:
        failures.append("the corpus folder changed: " + ", ".join(set(after) ^ set(before)))
    print(f"{len(before)} hostile files; worst {worst_cpu:.2f} s CPU, {worst_mb:.1f} MB resident")
    if len(before) < 90:
        failures.append(f"only {len(before)} files in the corpus, expected at least 90")
    for f in failures:
        print("FAILED " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
